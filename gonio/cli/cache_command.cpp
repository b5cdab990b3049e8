#include "gonio/cli/commands.h"
#include "heightfield/surface_cache.h"

#include <cstdio>

namespace gonio {

int run_cache_command(const std::string& action, const std::string& directory) {
    const SurfaceCache cache(directory.empty() ? default_cache_directory() : directory);
    const std::string dir = directory.empty() ? default_cache_directory() : directory;
    if (action == "clear") {
        const int n = cache.clear();
        std::printf("%s: removed %d file%s\n", dir.c_str(), n, n == 1 ? "" : "s");
        return 0;
    }
    const auto entries = cache.list();
    long long total = 0;
    for (const CacheEntry& e : entries) total += e.bytes;
    const long long limit = cache_size_limit();
    std::printf(
        "%s: %zu surface%s, %.1f MB%s\n", dir.c_str(), entries.size(),
        entries.size() == 1 ? "" : "s", total / 1e6,
        limit > 0 ? (", limit " + std::to_string(limit / 1000000) + " MB (GONIO_CACHE_MAX)").c_str()
                  : "");
    for (const CacheEntry& e : entries)
        std::printf("%s  %8.1f MB  used %8.0f s ago  %s\n", e.key.c_str(), e.bytes / 1e6,
                    e.age_seconds, e.identity.c_str());
    return 0;
}

} // namespace gonio
