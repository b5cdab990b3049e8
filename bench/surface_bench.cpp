// Surface-generation benchmark (issue 3): Beckmann alpha = 0.75, 500 iterations, at growing sizes.
// Prints, per generator and size: total time, the FFTs alone in the same run (fftwf_execute, the
// floor of any Frankot-Chellappa iteration), their ratio, the whole integration (FFTs + spectral
// product), the fidelity metrics and the peak memory (each configuration runs in its own
// process, metrics included). Not a test: numbers depend on the machine.
//
// A second table (issue 5) gives the fidelity of sliced matching on the distributions that are hard
// to realise, up to 1024^2: heavy-tailed Student's t, a multi-lobe sinc curve and two anisotropic
// blends [R19 Eq. 10], each with the mean distance of an ideal independent sample of as many
// facets.
//
// Usage: surface_bench [max_size=2048] [iterations=500] [threads=all]
//        (R19 Algorithm 1 is run up to 512^2: its reassignment is far slower.)
#include "heightfield/generate.h"
#include "heightfield/ndf/anisotropic_blend.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/sinc_ndf.h"
#include "heightfield/ndf/student_t.h"
#include "heightfield/surface_generator.h"
#include "heightfield/surface_metrics.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace gonio;

// Runs one configuration in a child process, so that its peak memory is its own.
template <class Body>
static double run_isolated(Body body) {
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
        body();
        std::fflush(stdout);
        _exit(0);
    }
    int status = 0;
    rusage u{};
    wait4(pid, &status, 0, &u);
    return u.ru_maxrss / 1024.0;
}

int main(int argc, char** argv) {
    const int max_size = argc > 1 ? std::atoi(argv[1]) : 2048;
    const int iterations = argc > 2 ? std::atoi(argv[2]) : 500;
    const int threads = argc > 3 ? std::atoi(argv[3]) : int(std::thread::hardware_concurrency());
    const Beckmann ndf(0.75);
    std::printf("Beckmann alpha = 0.75, %d iterations, %d threads, %u hardware threads\n",
                iterations, threads, std::thread::hardware_concurrency());
    std::printf("%-16s %6s %9s %9s %7s %9s %8s %8s %8s %9s %9s\n", "generator", "size", "total_s",
                "ffts_s", "ratio", "integ_s", "TV", "alpha_x", "alpha_y", "schwarz", "peak_MiB");
    for (const std::string generator : {"sliced-matching", "algorithm1"}) {
        for (int n = 256; n <= max_size; n *= 2) {
            if (generator == "algorithm1" && n > 512) break;
            const double peak = run_isolated([&] {
                SurfaceSpec spec;
                spec.generator = &generator_named(generator);
                spec.size = n;
                spec.iterations = iterations;
                GenerationLog log;
                const HeightField h = generate_surface(ndf, spec, threads, &log);
                const SurfaceMetrics m = measure_surface(h, ndf, 1000);
                std::printf("%-16s %6d %9.2f %9.2f %7.2f %9.2f", generator.c_str(), n, log.seconds,
                            log.fft_seconds, log.seconds / log.fft_seconds, log.integrate_seconds);
                std::printf(" %8.4f %8.4f %8.4f %9.2e", m.ndf_distance, m.alpha_eff_x,
                            m.alpha_eff_y, log.schwarz_mean.back());
            });
            std::printf(" %9.0f\n", peak);
        }
    }

    std::printf(
        "\nsliced-matching on hard targets, %d iterations (TV on 1000 cells; iid: the mean TV "
        "of an ideal sample of 2 n^2 facets)\n",
        iterations);
    std::printf("%-44s %6s %9s %8s %8s %7s %8s %8s\n", "distribution", "size", "total_s", "TV",
                "iid_TV", "ratio", "alpha_x", "alpha_y");
    std::vector<std::unique_ptr<Ndf>> hard;
    hard.push_back(std::make_unique<StudentT>(0.5, 0.5, 2.2));
    hard.push_back(std::make_unique<SincNdf>(6.0, 0.05, 128));
    hard.push_back(std::make_unique<AnisotropicBlend>(std::make_unique<SincNdf>(6.0, 0.05, 128),
                                                      std::make_unique<SincNdf>(3.5, 0.02, 128)));
    hard.push_back(std::make_unique<AnisotropicBlend>(std::make_unique<Ggx>(0.5, 0.5),
                                                      std::make_unique<Beckmann>(0.5)));
    const char* names[] = {"student_t alpha 0.5 gamma 2.2", "sinc k 6 floor 0.05",
                           "blend sinc k 6 (x) / sinc k 3.5 (y)",
                           "blend ggx 0.5 (x) / beckmann 0.5 (y)"};
    for (size_t k = 0; k < hard.size(); ++k) {
        for (int n = 256; n <= std::min(max_size, 1024); n *= 2) {
            run_isolated([&] {
                SurfaceSpec spec;
                spec.size = n;
                spec.iterations = iterations;
                GenerationLog log;
                const HeightField h = generate_surface(*hard[k], spec, threads, &log);
                const SurfaceMetrics m = measure_surface(h, *hard[k], 1000);
                double iid = 0;
                for (double p : m.target_mass)
                    iid += 0.5 * std::sqrt(2 * p * (1 - p) / (2.0 * n * n) / 3.14159265358979);
                std::printf("%-44s %6d %9.2f %8.4f %8.4f %7.2f %8.4f %8.4f\n", names[k], n,
                            log.seconds, m.ndf_distance, iid, m.ndf_distance / iid, m.alpha_eff_x,
                            m.alpha_eff_y);
            });
        }
    }
    return 0;
}
