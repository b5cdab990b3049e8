#pragma once
// Generated surfaces are cached on disk as EXR height maps, keyed by a hash of everything that
// defines them (NDF and its parameters, generator, size, spacing, iterations, threshold, seed,
// ...), so that sweeps and repeated runs never regenerate a surface.
#include "heightfield/exr_io.h"
#include "heightfield/ndf/ndf.h"
#include "heightfield/surface_spec.h"

#include <optional>
#include <string>

namespace gonio {

// The canonical description hashed into the key (readable, stored in the cached file).
std::string surface_identity(const Ndf& ndf, const SurfaceSpec& spec);
// 16 hex digits of the FNV-1a 64-bit hash of surface_identity().
std::string surface_cache_key(const Ndf& ndf, const SurfaceSpec& spec);

// The default cache directory: $GONIO_CACHE_DIR, else $XDG_CACHE_HOME/gonio/surfaces, else
// $HOME/.cache/gonio/surfaces.
std::string default_cache_directory();

class SurfaceCache {
  public:
    // An empty directory disables the cache.
    explicit SurfaceCache(std::string directory) : dir_(std::move(directory)) {}
    bool enabled() const { return !dir_.empty(); }
    std::string path(const std::string& key) const;
    // The cached surface, if present and its stored identity matches (guards against collisions).
    std::optional<HeightField> load(const std::string& key, const std::string& identity,
                                    ExrAttributes* attrs = nullptr) const;
    void store(const std::string& key, const HeightField& surface,
               const ExrAttributes& attrs) const;

  private:
    std::string dir_;
};

} // namespace gonio
