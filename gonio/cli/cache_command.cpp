#include "core/enum_names.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "heightfield/surface_cache.h"

#include <cstdio>

namespace gonio {

namespace {
enum class CacheAction { list, clear };
} // namespace
template <>
struct EnumNames<CacheAction> {
    static constexpr const char* what = "cache action";
    static constexpr const char* names[] = {"list", "clear"};
};

namespace {
int cache_command_run(CacheAction action, const std::string& directory) {
    const std::string dir = directory.empty() ? default_cache_directory() : directory;
    const SurfaceCache cache(dir);
    if (action == CacheAction::clear) {
        const int n = cache.clear();
        std::printf("%s: removed %d file%s\n", dir.c_str(), n, n == 1 ? "" : "s");
        return 0;
    }
    const auto entries = cache.list();
    long long total = 0;
    for (const CacheEntry& e : entries) total += e.bytes;
    const long long limit = checked_cache_limit();
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

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto action = std::make_shared<std::string>();
    auto dir = std::make_shared<std::string>();
    app.add_option("action", *action, "list or clear")
        ->required()
        ->check(CLI::IsMember(enum_names<CacheAction>()));
    app.add_option("--cache-dir", *dir, "Surface cache directory");
    return [action, dir] { return cache_command_run(enum_named<CacheAction>(*action), *dir); };
}
} // namespace

const Command& cache_command() {
    static const Command c{
        "cache", "List or clear the surface cache ($GONIO_CACHE_DIR; $GONIO_CACHE_MAX caps it)",
        setup};
    return c;
}
} // namespace gonio
