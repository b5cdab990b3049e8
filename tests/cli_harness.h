#pragma once
// Running the gonio binary from tests: its exit code, its output, a fresh directory to run in.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace gonio::test {

namespace fs = std::filesystem;

struct Run {
    int code;
    std::string out, err;
};

inline std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs the gonio binary with arguments (shell-quoted by the caller) in `dir`.
inline Run run_gonio(const fs::path& dir, const std::string& args) {
    const std::string cmd = "cd '" + dir.string() + "' && '" + GONIO_BINARY + "' " + args +
                            " > stdout.txt 2> stderr.txt < /dev/null";
    const int status = std::system(cmd.c_str());
    Run r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout.txt"),
          slurp(dir / "stderr.txt")};
    fs::remove(dir / "stdout.txt");
    fs::remove(dir / "stderr.txt");
    return r;
}

inline fs::path fresh_dir(const std::string& name) {
    const fs::path d =
        fs::temp_directory_path() / ("gonio_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

inline void write(const fs::path& p, const std::string& text) {
    std::ofstream(p) << text;
}

inline int files_in(const fs::path& d) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(d)) n += e.is_regular_file();
    return n;
}

} // namespace gonio::test
