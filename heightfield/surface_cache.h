#pragma once
// Generated surfaces are cached on disk as EXR height maps, keyed by a hash of everything that
// defines them (NDF and its parameters, generator, size, spacing, iterations, threshold, seed,
// ...), so that sweeps and repeated runs never regenerate a surface.
#include "heightfield/exr_io.h"
#include "heightfield/ndf/ndf.h"
#include "heightfield/surface_spec.h"

#include <optional>
#include <string>
#include <vector>

namespace gonio {

// The canonical description hashed into the key (readable, stored in the cached file).
std::string surface_identity(const Ndf& ndf, const SurfaceSpec& spec);
// 16 hex digits of the FNV-1a 64-bit hash of surface_identity().
std::string surface_cache_key(const Ndf& ndf, const SurfaceSpec& spec);

// The default cache directory: $GONIO_CACHE_DIR, else $XDG_CACHE_HOME/gonio/surfaces, else
// $HOME/.cache/gonio/surfaces.
std::string default_cache_directory();

// One cached surface, for `gonio cache list`.
struct CacheEntry {
    std::string path, key, identity;
    long long bytes = 0;
    double age_seconds = 0; // since it was last used
};

// A size limit from $GONIO_CACHE_MAX ("500M", "2G", "1e9", bytes); 0 when unset. Throws
// std::invalid_argument naming the variable for anything else.
long long cache_size_limit();

class SurfaceCache {
  public:
    // An empty directory disables the cache.
    explicit SurfaceCache(std::string directory) : dir_(std::move(directory)) {}
    bool enabled() const { return !dir_.empty(); }
    std::string path(const std::string& key) const;
    // The cached surface, if present and its stored identity matches (guards against collisions).
    std::optional<HeightField> load(const std::string& key, const std::string& identity,
                                    ExrAttributes* attrs = nullptr) const;
    // Written under a temporary name and renamed, so that concurrent writers of the same
    // surface never leave a half-written entry (the last rename wins; both are the same
    // surface); then, with a size limit, the least recently used entries are evicted.
    void store(const std::string& key, const HeightField& surface,
               const ExrAttributes& attrs) const;
    // Entries, most recently used first (a load marks an entry used).
    std::vector<CacheEntry> list() const;
    // Removes every entry (and stray temporaries); returns how many files went.
    int clear() const;
    // Evicts least recently used entries until the cache holds at most `limit` bytes, never
    // `keep`; returns how many went.
    int evict(long long limit, const std::string& keep = "") const;

  private:
    std::string dir_;
};

} // namespace gonio
