#pragma once
// Small simulated result files for the export tests, run once per build of gonio and shared by
// the test processes CTest starts (a file named by a hash of the config and the binary's time
// stamp; gonio writes under a temporary name and renames, so concurrent makers are harmless).
#include "tests/cli_harness.h"

#include <functional>
#include <stdexcept>
#include <string>

namespace gonio::test {

inline std::string fixture(const std::string& name, const std::string& config,
                           const std::string& command = "run") {
    const auto stamp = fs::last_write_time(GONIO_BINARY).time_since_epoch().count();
    const size_t key = std::hash<std::string>{}(config + command + std::to_string(stamp));
    const fs::path dir = fs::temp_directory_path() / "gonio_test_fixtures";
    fs::create_directories(dir);
    const fs::path out = dir / (name + "_" + std::to_string(key) + ".h5");
    if (fs::exists(out)) return out.string();
    const fs::path cfg =
        dir / (name + "_" + std::to_string(key) + "_" + std::to_string(::getpid()) + ".toml");
    write(cfg, config);
    // Each maker writes its own file and renames it: tests that CTest runs at once may make the
    // same fixture together (a run's checkpoint beside its output is its own).
    const fs::path mine = out.string() + "." + std::to_string(::getpid()) + ".h5";
    const Run r =
        run_gonio(dir, command + " '" + cfg.string() + "' -o '" + mine.string() +
                           "' --overwrite --quiet" + (command == "run" ? " --no-cache" : ""));
    fs::remove(cfg);
    if (r.code != 0) throw std::runtime_error("fixture " + name + ": " + r.err);
    fs::rename(mine, out);
    return out.string();
}

// Beckmann 0.5 gold, theta_i 0..85 every 5 degrees: what the exporters need.
inline std::string gold_table() {
    std::string theta;
    for (int t = 0; t <= 85; t += 5) theta += (theta.empty() ? "" : ", ") + std::to_string(t);
    return fixture("gold", "seed = 2\n[ndf]\ntype = \"beckmann\"\nalpha = 0.5\n"
                           "[material]\ntype = \"conductor\"\nior = \"Au\"\n"
                           "[spectrum]\nwavelengths = [450, 550, 650]\n"
                           "[beam]\ntheta_i = [" +
                               theta +
                               "]\nphi_i = 0\n"
                               "[sensor]\ncells = 1200\n[surface]\nsize = 128\n"
                               "[trace]\nrays = 262144\n[[case]]\nname = \"gold\"\n");
}

inline std::string sweep_config(const std::string& ndf, const std::string& material, int cells,
                                int rays, int size, const std::string& phi = "0", int step = 5,
                                int last = 85) {
    std::string theta;
    for (int t = 0; t <= last; t += step) theta += (theta.empty() ? "" : ", ") + std::to_string(t);
    return "seed = 4\nndf = " + ndf + "\nmaterial = " + material + "\n[beam]\ntheta_i = [" + theta +
           "]\nphi_i = " + phi + "\n[sensor]\ncells = " + std::to_string(cells) +
           "\n[surface]\nsize = " + std::to_string(size) +
           "\n[trace]\nrays = " + std::to_string(rays) + "\n";
}

} // namespace gonio::test
