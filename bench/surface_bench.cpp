// Surface-generation benchmark (issues 3 and 35): Beckmann alpha = 0.75 at growing sizes. First
// sliced matching's two paths side by side, per size: the pool's marginal at 500 iterations (the
// generator before issue 35) and the exact marginal at its default iterations: time, iterations,
// fidelity (TV distance on 1000 cells, mean relative Schwarz error), peak memory and the speed-up;
// then R19 Algorithm 1 up to 512^2 with its FFT share. Each generation runs in its own process, so
// that its peak memory is its own (metrics included). Not a test: numbers depend on the machine.
//
// A second table (issue 5) gives the fidelity of sliced matching on the distributions that are hard
// to realise, up to 1024^2: heavy-tailed Student's t, a multi-lobe sinc curve and two anisotropic
// blends [R19 Eq. 10], each with the mean distance of an ideal independent sample of as many
// facets.
//
// Usage: surface_bench [max_size=2048] [iterations=500] [threads=all]
//        (iterations: of the pool path, Algorithm 1 and the hard targets; R19 Algorithm 1 is run up
//        to 512^2: its reassignment is far slower.)
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

// One generation in its own process: time, FFT time, fidelity and peak memory.
struct Generated {
    double seconds = 0, fft_seconds = 0, tv = 0, alpha_x = 0, alpha_y = 0, schwarz = 0, peak = 0;
    int iterations = 0;
};
static Generated generate_isolated(const Ndf& ndf, SurfaceSpec spec, int threads) {
    int fd[2];
    if (pipe(fd) != 0) return {};
    Generated g;
    g.peak = run_isolated([&] {
        close(fd[0]);
        GenerationLog log;
        const HeightField h = generate_surface(ndf, spec, threads, &log);
        const SurfaceMetrics m = measure_surface(h, ndf, 1000);
        Generated r;
        r.seconds = log.seconds, r.fft_seconds = log.fft_seconds, r.tv = m.ndf_distance;
        r.alpha_x = m.alpha_eff_x, r.alpha_y = m.alpha_eff_y, r.schwarz = log.schwarz_mean.back();
        r.iterations = log.iterations;
        if (write(fd[1], &r, sizeof r) != ssize_t(sizeof r)) _exit(1);
    });
    close(fd[1]);
    const double peak = g.peak;
    if (read(fd[0], &g, sizeof g) != ssize_t(sizeof g)) g = {};
    close(fd[0]);
    g.peak = peak;
    return g;
}

int main(int argc, char** argv) {
    const int max_size = argc > 1 ? std::atoi(argv[1]) : 2048;
    const int iterations = argc > 2 ? std::atoi(argv[2]) : 500;
    const int threads = argc > 3 ? std::atoi(argv[3]) : int(std::thread::hardware_concurrency());
    const Beckmann ndf(0.75);
    // The generator paths side by side: sliced matching as it was (the pool's marginal, one
    // direction per iteration, 500 iterations) and as it is (the exact marginal, two directions,
    // its default iterations), then R19 Algorithm 1.
    std::printf("Beckmann alpha = 0.75, %d threads, %u hardware threads; TV on 1000 cells\n",
                threads, std::thread::hardware_concurrency());
    std::printf("%6s | %9s %7s %8s %9s %8s | %9s %7s %8s %9s %8s | %7s\n", "size", "pool s", "its",
                "TV", "schwarz", "MiB", "exact s", "its", "TV", "schwarz", "MiB", "speedup");
    for (int n = 256; n <= max_size; n *= 2) {
        SurfaceSpec before;
        before.size = n, before.target = MatchTarget::pool, before.iterations = iterations;
        SurfaceSpec now;
        now.size = n; // the defaults
        const Generated a = generate_isolated(ndf, before, threads);
        const Generated b = generate_isolated(ndf, now, threads);
        std::printf("%6d | %9.2f %7d %8.5f %9.2e %8.0f | %9.2f %7d %8.5f %9.2e %8.0f | %7.2f\n", n,
                    a.seconds, a.iterations, a.tv, a.schwarz, a.peak, b.seconds, b.iterations, b.tv,
                    b.schwarz, b.peak, a.seconds / b.seconds);
        std::fflush(stdout);
    }
    std::printf("\n%-16s %6s %9s %9s %7s %8s %8s %8s %9s %9s\n", "generator", "size", "total_s",
                "ffts_s", "ratio", "TV", "alpha_x", "alpha_y", "schwarz", "peak_MiB");
    for (int n = 256; n <= std::min(max_size, 512); n *= 2) {
        SurfaceSpec spec;
        spec.generator = &algorithm1_generator();
        spec.size = n;
        spec.iterations = iterations;
        const Generated g = generate_isolated(ndf, spec, threads);
        std::printf("%-16s %6d %9.2f %9.2f %7.2f %8.4f %8.4f %8.4f %9.2e %9.0f\n", "algorithm1", n,
                    g.seconds, g.fft_seconds, g.seconds / g.fft_seconds, g.tv, g.alpha_x, g.alpha_y,
                    g.schwarz, g.peak);
    }

    std::printf(
        "\nsliced-matching on hard targets, both paths (TV on 1000 cells; iid: the mean TV of "
        "an ideal sample of 2 n^2 facets)\n");
    std::printf("%-38s %5s | %8s %8s %8s | %8s %8s %8s | %8s\n", "distribution", "size", "pool s",
                "TV", "ratio", "exact s", "TV", "ratio", "iid_TV");
    std::vector<std::unique_ptr<Ndf>> hard;
    hard.push_back(std::make_unique<StudentT>(0.5, 0.5, 2.2));
    hard.push_back(std::make_unique<Ggx>(0.3, 0.3));
    hard.push_back(std::make_unique<SincNdf>(6.0, 0.05, 128));
    hard.push_back(std::make_unique<AnisotropicBlend>(std::make_unique<SincNdf>(6.0, 0.05, 128),
                                                      std::make_unique<SincNdf>(3.5, 0.02, 128)));
    hard.push_back(std::make_unique<AnisotropicBlend>(std::make_unique<Ggx>(0.5, 0.5),
                                                      std::make_unique<Beckmann>(0.5)));
    const char* names[] = {"student_t alpha 0.5 gamma 2.2", "ggx alpha 0.3", "sinc k 6 floor 0.05",
                           "blend sinc k 6 (x) / sinc k 3.5 (y)",
                           "blend ggx 0.5 (x) / beckmann 0.5 (y)"};
    for (size_t k = 0; k < hard.size(); ++k) {
        for (int n = 256; n <= std::min(max_size, 1024); n *= 2) {
            SurfaceSpec before;
            before.size = n, before.target = MatchTarget::pool, before.iterations = iterations;
            SurfaceSpec now;
            now.size = n;
            const Generated a = generate_isolated(*hard[k], before, threads);
            const Generated b = generate_isolated(*hard[k], now, threads);
            double iid = 0;
            for (double p : target_cell_mass(*hard[k], 1000))
                iid += 0.5 * std::sqrt(2 * p * (1 - p) / (2.0 * n * n) / 3.14159265358979);
            std::printf("%-38s %5d | %8.2f %8.4f %8.2f | %8.2f %8.4f %8.2f | %8.4f\n", names[k], n,
                        a.seconds, a.tv, a.tv / iid, b.seconds, b.tv, b.tv / iid, iid);
            std::fflush(stdout);
        }
    }
    return 0;
}
