#pragma once
// A subcommand of gonio: its name, one line of help, and how it declares its options and runs.
// Each command lives in its own file (gonio/cli/<name>_command.cpp) and is listed once in
// commands(); main.cpp knows none of them by name.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

// What every command may need from the process.
struct CliContext {
    std::string command_line; // as typed, stored in result files
    int rank = 0, ranks = 1;  // under mpirun
};

struct Command {
    const char* name;
    const char* summary;
    // Declares the command's options on `app` (bound to state the returned action owns) and
    // returns the action, run after parsing; it returns the exit code.
    std::function<int()> (*setup)(CLI::App& app, const CliContext& context);
};

// Every command, in the order `gonio --help` lists them.
const std::vector<const Command*>& commands();

const Command& run_command();
const Command& model_command();
const Command& surface_command();
const Command& merge_command();
const Command& ndf_command();
const Command& compare_command();
const Command& info_command();
const Command& keys_command();
const Command& export_command();
const Command& report_command();
const Command& masking_command();
const Command& fit_command();
const Command& render_command();
const Command& cache_command();

} // namespace gonio
