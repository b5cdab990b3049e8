// `gonio merge PART... -o OUT.h5`: the part files of a sharded run (gonio run --shard), checked
// and put together into the result one process would have written.
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/run_table.h"
#include "gonio/io/result_writer.h"
#include "gonio/run/run.h"

#include <cstdio>
#include <filesystem>

namespace gonio {

namespace {
struct MergeArgs {
    CommonOptions common;
    std::vector<std::string> parts;
};

int merge(const MergeArgs& a) {
    const auto start = PhaseTimes::Clock::now();
    const auto limit = limit_threads(a.common.threads);
    namespace fs = std::filesystem;
    for (const std::string& p : a.parts)
        if (fs::weakly_canonical(p) == fs::weakly_canonical(a.common.output))
            throw UsageError(p + ": the output is one of the parts to merge");
    refuse_existing(a.common.output, a.common.overwrite);
    ResultWriter writer(a.common.output, true); // an unwritable output fails before any work
    RunTable table(0, a.common.quiet);          // its rows as the parts are put together
    RunOptions o;
    o.threads = a.common.threads;
    o.started = start;
    o.observer = table.observer();
    const RunResult result = merge_parts(a.parts, o);
    write_result(result, writer);
    if (!a.common.quiet) std::printf("wrote %s\n", a.common.output.c_str());
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto a = std::make_shared<MergeArgs>();
    app.add_option("parts", a->parts, "Part files of gonio run --shard")->required();
    app.add_option("-o,--output", a->common.output, "HDF5 result file")->required();
    add_common_options(app, a->common, kOverwrite | kQuiet | kThreads);
    return [a] { return merge(*a); };
}
} // namespace

const Command& merge_command() {
    static const Command c{"merge", "Put the parts of a sharded gonio run together", setup};
    return c;
}

} // namespace gonio
