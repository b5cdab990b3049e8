#include "gonio/run/memory_estimate.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <sys/resource.h>

namespace gonio {

namespace {
// Bytes per sample of a surface at its peak: generation's FFT buffers and gradient fields (about
// ten n^2 float arrays and complex spectra), more than either backend's scene.
constexpr double kSurfaceBytesPerSample = 48;
// The process itself: code, libraries, the threads' stacks and arenas (measured: 30 MB for a
// run of one incidence, 1024 rays, 100 cells).
constexpr double kProcessBytes = 30e6;

std::string gigabytes(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
    return text;
}
} // namespace

MemoryEstimate estimate_memory(const Config& cfg, bool simulated) {
    MemoryEstimate e;
    double results = 0, peak_case = 0;
    for (const CaseConfig& c : cfg.cases) {
        const double cells = c.sensor_cells, nc = c.channels();
        const double incidences = double(c.theta_i_deg.size()) * double(c.phi_i_deg.size());
        const double map = cells * nc * 8; // one cell map of doubles
        const double orders = c.trace.orders + 1.0, sides = c.material.transmits ? 2.0 : 1.0;
        const double B = c.trace.batches, models = double(c.model.models.size());
        const bool surface = simulated || c.needs_surface();
        const double samples = c.surface.input.empty() ? double(c.surface.size) * c.surface.size
                                                       : 0; // a loaded map: its own size
        const double surface_bytes = surface ? samples * kSurfaceBytesPerSample : 0;
        // A trace in flight (batch_tally.h): streamed, the open batch, the reducer's three maps
        // per order and the result's two, and the three order sums per batch; an accuracy
        // target keeps every batch (and a batch shard hands them on as well).
        const bool target = c.trace.target.active(), shard = c.trace.batch_shard_count > 1;
        double trace = sides * ((6 * orders + 3 * B) * map);
        if (target || shard) trace += sides * B * orders * map * (shard ? 2 : 1);
        // A unit's completion (unit_completion.h): means and errors, jackknife scratch, the
        // comparisons' ratio maps; then its record, one queued and one being written.
        const double record = sides * (2 * orders + 3) * map + models * 4 * map;
        const double completion = 4 * map + 2 * record;
        // An ensemble keeps every surface's means (and two maps of ray variance) per incidence
        // until its last pass, and stacks one incidence's to combine them.
        const double R = c.surface.realisations > 1
                             ? std::max(c.surface.realisations, target ? c.surface.max_realisations
                                                                       : c.surface.realisations)
                             : 0;
        const double held = R * sides * map * (incidences * (orders + 2) + orders);
        double model_flight = 0, model_results = 0;
        for (const ModelChoice& m : c.model.models) {
            model_flight = std::max(model_flight, (m.monte_carlo ? 6 * 11 + 3 * B : 1.0) * map);
            model_results += incidences * (m.monte_carlo ? 6.0 : 2.0) * map;
        }
        const double sim_results =
            simulated ? incidences * map * (2 * sides * orders + 14 + 2 * models) : 0;
        const double case_results = sim_results + model_results;
        results += case_results;
        // An ensemble's surfaces are held until its last pass, its results filled after: the
        // two overlap little, so only what the held means exceed the results by adds up.
        const double in_flight =
            std::max(surface_bytes, (simulated ? surface_bytes + trace + completion : 0) +
                                        model_flight + std::max(0.0, held - case_results));
        if (in_flight > peak_case) {
            peak_case = in_flight;
            e.largest =
                "case " + c.name + ": " +
                (surface_bytes >= in_flight - surface_bytes
                     ? "its " + std::to_string(c.surface.size) + "^2 surface"
                     : "its traces in flight (" + std::to_string(c.trace.batches) + " batches, " +
                           std::to_string(int(orders)) + " orders, " +
                           std::to_string(c.sensor_cells) + " cells, " +
                           std::to_string(c.channels()) + " channels" +
                           (R > 0 ? ", " + std::to_string(int(R)) + " surfaces" : "") + ")");
        }
    }
    e.bytes = kProcessBytes + peak_case + results;
    if (results > peak_case) e.largest = "the results of every case";
    return e;
}

double peak_memory_bytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) * 1024; // kilobytes on Linux
}

double available_memory_bytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    double value = 0;
    std::string unit;
    while (in >> key >> value >> unit)
        if (key == "MemAvailable:") return value * 1024;
    return 0;
}

void check_memory(const Config& cfg, bool simulated) {
    const double available = available_memory_bytes();
    if (available <= 0) return;
    const MemoryEstimate e = estimate_memory(cfg, simulated);
    if (e.bytes > available)
        throw std::runtime_error("the run needs about " + gigabytes(e.bytes) + " of memory (" +
                                 e.largest + "); the machine has " + gigabytes(available) +
                                 " available: fewer cells, batches, incidences or samples");
}

} // namespace gonio
