#include "heightfield/surface_cache.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace gonio {

std::string surface_identity(const Ndf& ndf, const SurfaceSpec& s) {
    std::ostringstream o;
    o.precision(17);
    // Bump the version when a generator's output changes for the same inputs.
    o << "gonio-surface v3|" << ndf.describe() << "|generator=" << name_of(s.generator)
      << "|size=" << s.size << "|spacing=" << s.spacing << "|iterations=" << s.iterations
      << "|threshold=" << s.threshold << "|stop_when_converged=" << s.stop_when_converged
      << "|seed=" << s.seed;
    if (s.generator == Generator::heitz) o << "|correlation_length=" << s.correlation_length;
    o << "|constraint=" << name_of(s.constraint);
    if (s.constraint != Constraint::none) o << "|lattice=" << s.lattice << "|relief=" << s.relief;
    return o.str();
}

std::string surface_cache_key(const Ndf& ndf, const SurfaceSpec& spec) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : surface_identity(ndf, spec)) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string default_cache_directory() {
    if (const char* d = std::getenv("GONIO_CACHE_DIR")) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
        return std::string(x) + "/gonio/surfaces";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::string(home) + "/.cache/gonio/surfaces";
    return ".gonio-cache";
}

std::string SurfaceCache::path(const std::string& key) const {
    return dir_ + "/" + key + ".exr";
}

std::optional<HeightField> SurfaceCache::load(const std::string& key, const std::string& identity,
                                              ExrAttributes* attrs) const {
    if (!enabled() || !std::filesystem::exists(path(key))) return std::nullopt;
    ExrAttributes a;
    HeightField s;
    try {
        s = read_height_exr(path(key), &a);
    } catch (const std::exception&) {
        return std::nullopt; // a damaged cache entry is regenerated, not trusted
    }
    if (a.text["gonio_identity"] != identity) return std::nullopt;
    if (attrs) *attrs = a;
    return s;
}

void SurfaceCache::store(const std::string& key, const HeightField& surface,
                         const ExrAttributes& attrs) const {
    if (!enabled()) return;
    std::filesystem::create_directories(dir_);
    write_height_exr(path(key), surface, attrs);
}

} // namespace gonio
