// A run through the library alone, as a program of one's own would make it: no command line,
// only gonio/config and gonio/run (CTest holds its file equal, bit for bit, to `gonio run`'s).
//
//     library_run CONFIG OUT.h5
#include "gonio/config/config.h"
#include "gonio/run/run.h"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: library_run CONFIG OUT.h5\n");
        return 2;
    }
    try {
        const gonio::Config cfg = gonio::load_config(argv[1]);
        gonio::RunOptions options; // every core, no surface cache
        options.observer.incidence = [](const gonio::IncidenceReport& r) {
            const gonio::Estimate& l1 = r.simulation->reflected.first_albedo;
            std::printf("%s theta_i=%g phi_i=%g: L1 albedo %.6f +- %.1e\n", r.config->name.c_str(),
                        r.theta_deg, r.phi_deg, l1.mean.at({r.id.theta_index, r.id.phi_index, 0}),
                        l1.error.at({r.id.theta_index, r.id.phi_index, 0}));
        };
        const gonio::RunResult result = gonio::run_local(cfg, options);
        gonio::write_result_file(result, argv[2], /*overwrite=*/true);
        std::printf("wrote %s\n", argv[2]);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "library_run: %s\n", e.what());
        return 1;
    }
}
