// gonio: a virtual gonioreflectometer for explicit microfacet surfaces. See README.md.
// The commands are registered in gonio/cli/commands.cpp; the work is the library's (gonio/run).
// Exit codes: 0 done, 1 failed, 2 a usage or config error, 3 a format cannot hold the data
// (gonio export), 130 interrupted.
#include "core/config_error.h"
#include "core/float_mode.h"
#include "core/message.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/run/mpi_job.h"
#include "gonio_version.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

namespace {

// One line on stderr, long quotes cut; returns the exit code.
int fail(const std::string& message, int code) {
    std::fprintf(stderr, "gonio: error: %s\n", gonio::one_line(message).c_str());
    return code;
}

int gonio_main(int argc, char** argv, const gonio::MpiJob& job) {
    CLI::App app{"gonio: a virtual gonioreflectometer for microfacet surfaces"};
    app.set_version_flag("--version",
                         std::string(gonio::kVersion) + " (git " + gonio::kGitHash + ")");
    app.require_subcommand(1);
    // CLI11's errors in gonio's style: one line, exit 2 (below).
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return "gonio: error: " + gonio::one_line(e.what()) + " (gonio --help lists the usage)\n";
    });
    gonio::CliContext context;
    for (int k = 0; k < argc; ++k) context.command_line += (k ? " " : "") + std::string(argv[k]);
    context.rank = job.rank, context.ranks = job.size;

    std::vector<std::pair<CLI::App*, std::function<int()>>> actions;
    for (const gonio::Command* c : gonio::commands()) {
        CLI::App* sub = app.add_subcommand(c->name, c->summary);
        actions.emplace_back(sub, c->setup(*sub, context));
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : 2;
    }
    try {
        for (auto& [sub, action] : actions)
            if (*sub) return action();
    } catch (const gonio::UsageError& e) {
        return fail(e.what(), 2);
    } catch (const gonio::ConfigError& e) {
        return fail(e.what(), 2);
    } catch (const std::bad_alloc&) {
        return fail("out of memory (the run asked for more than the machine could give)", 1);
    } catch (const std::exception& e) {
        return fail(e.what(), 1);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    gonio::use_result_float_mode(); // before any thread exists
    // Under mpirun: MPI starts here, and every rank but 0 keeps quiet.
    const gonio::MpiJob job = gonio::mpi_start(&argc, &argv);
    const int code = gonio_main(argc, argv, job);
    gonio::mpi_finish();
    return code;
}
