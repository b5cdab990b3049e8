#include "heightfield/surface_cache.h"

#include "heightfield/surface_generator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace gonio {

std::string surface_identity(const Ndf& ndf, const SurfaceSpec& s) {
    std::ostringstream o;
    o.precision(17);
    // Bump the version when a generator's output changes for the same inputs.
    o << "gonio-surface v3|" << ndf.describe() << "|generator=" << generator_name(s)
      << "|size=" << s.size << "|spacing=" << s.spacing << "|iterations=" << s.iterations
      << "|threshold=" << s.threshold << "|stop_when_converged=" << s.stop_when_converged
      << "|seed=" << s.seed;
    if (s.generator) s.generator->identity(s, o); // what else defines its surfaces
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
    std::error_code
        ec; // the time of last use, for eviction (best effort: a read-only cache is fine)
    std::filesystem::last_write_time(path(key), std::filesystem::file_time_type::clock::now(), ec);
    return s;
}

void SurfaceCache::store(const std::string& key, const HeightField& surface,
                         const ExrAttributes& attrs) const {
    if (!enabled()) return;
    std::filesystem::create_directories(dir_);
    write_height_exr(path(key), surface, attrs);
    if (const long long limit = cache_size_limit(); limit > 0) evict(limit, path(key));
}

long long cache_size_limit() {
    const char* v = std::getenv("GONIO_CACHE_MAX");
    if (!v || !*v) return 0;
    char* end = nullptr;
    double x = std::strtod(v, &end); // (it skips leading spaces)
    std::string unit = end ? std::string(end) : "";
    // Spaces around the unit mean nothing: "2G", " 2G", "2G " and "2 G" are the same size.
    unit.erase(0, unit.find_first_not_of(" \t"));
    unit.erase(unit.find_last_not_of(" \t") + 1);
    const double scale = unit.empty() || unit == "B"   ? 1
                         : unit == "K" || unit == "KB" ? 1e3
                         : unit == "M" || unit == "MB" ? 1e6
                         : unit == "G" || unit == "GB" ? 1e9
                                                       : -1;
    if (end == v || scale < 0 || !(x >= 0) || !std::isfinite(x) || x * scale > 9e18)
        throw std::invalid_argument(std::string("GONIO_CACHE_MAX=") + v +
                                    ": expected a size in bytes, optionally with K, M or G");
    return static_cast<long long>(x * scale);
}

std::vector<CacheEntry> SurfaceCache::list() const {
    namespace fs = std::filesystem;
    std::vector<CacheEntry> out;
    std::error_code ec;
    if (!enabled() || !fs::is_directory(dir_, ec)) return out;
    const auto now = fs::file_time_type::clock::now();
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
        if (!e.is_regular_file() || e.path().extension() != ".exr") continue;
        CacheEntry c;
        c.path = e.path().string();
        c.key = e.path().stem().string();
        c.bytes = static_cast<long long>(e.file_size(ec));
        c.age_seconds = std::chrono::duration<double>(now - e.last_write_time(ec)).count();
        try {
            ExrAttributes a;
            read_height_exr(c.path, &a);
            c.identity = a.text["gonio_identity"];
        } catch (const std::exception&) {
            c.identity = "(unreadable)";
        }
        out.push_back(c);
    }
    std::sort(out.begin(), out.end(), [](const CacheEntry& a, const CacheEntry& b) {
        return a.age_seconds < b.age_seconds;
    });
    return out;
}

int SurfaceCache::clear() const {
    namespace fs = std::filesystem;
    int removed = 0;
    std::error_code ec;
    if (!enabled() || !fs::is_directory(dir_, ec)) return 0;
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
        const std::string name = e.path().filename().string();
        if (e.is_regular_file() &&
            (e.path().extension() == ".exr" || name.find(".exr.tmp") != std::string::npos))
            removed += fs::remove(e.path(), ec);
    }
    return removed;
}

int SurfaceCache::evict(long long limit, const std::string& keep) const {
    namespace fs = std::filesystem;
    std::vector<CacheEntry> entries;
    std::error_code ec;
    if (!enabled() || !fs::is_directory(dir_, ec)) return 0;
    const auto now = fs::file_time_type::clock::now();
    long long total = 0;
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
        if (!e.is_regular_file() || e.path().extension() != ".exr") continue;
        CacheEntry c;
        c.path = e.path().string();
        c.bytes = static_cast<long long>(e.file_size(ec));
        c.age_seconds = std::chrono::duration<double>(now - e.last_write_time(ec)).count();
        total += c.bytes;
        entries.push_back(c);
    }
    std::sort(entries.begin(), entries.end(), [](const CacheEntry& a, const CacheEntry& b) {
        return a.age_seconds > b.age_seconds;
    });
    int removed = 0;
    for (const CacheEntry& c : entries) {
        if (total <= limit) break;
        if (c.path == keep) continue;
        if (fs::remove(c.path, ec)) {
            total -= c.bytes;
            ++removed;
        }
    }
    return removed;
}

} // namespace gonio
