#include "gonio/run/memory_estimate.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace gonio {

namespace {
// Bytes per sample of a surface at its peak: generation's FFT buffers and gradient fields (about
// ten n^2 float arrays and complex spectra), more than either backend's scene.
constexpr double kSurfaceBytesPerSample = 48;

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
        const bool surface = simulated || c.needs_surface();
        const double samples = c.surface.input.empty() ? double(c.surface.size) * c.surface.size
                                                       : 0; // a loaded map: its own size
        const double surface_bytes = surface ? samples * kSurfaceBytesPerSample : 0;
        // A trace in flight: the tally's batches, the result's copy and its means (x 2.5).
        const double trace = 2.5 * sides * c.trace.batches * orders * map;
        const double held = c.surface.realisations > 1
                                ? incidences *
                                      std::max(c.surface.realisations,
                                               c.trace.target.active() ? c.surface.max_realisations
                                                                       : c.surface.realisations) *
                                      sides * c.trace.batches * orders * map
                                : 0;
        double model_flight = 0, model_results = 0;
        for (const ModelChoice& m : c.model.models) {
            model_flight = std::max(model_flight, (m.monte_carlo ? 33.0 : 1.0) * 2.5 * map);
            model_results += incidences * (m.monte_carlo ? 6.0 : 2.0) * map;
        }
        const double sim_results =
            simulated ? incidences * map * (2 * sides * orders + 14 + 2 * c.model.models.size())
                      : 0;
        results += sim_results + model_results;
        const double in_flight =
            std::max(surface_bytes, (simulated ? trace + held : 0) + model_flight);
        if (in_flight > peak_case) {
            peak_case = in_flight;
            e.largest = "case " + c.name + ": " +
                        (surface_bytes >= in_flight
                             ? "its " + std::to_string(c.surface.size) + "^2 surface"
                             : "its traces' batches (" + std::to_string(c.trace.batches) + " x " +
                                   std::to_string(int(orders)) + " orders x " +
                                   std::to_string(c.sensor_cells) + " cells x " +
                                   std::to_string(c.channels()) + " channels)");
        }
    }
    e.bytes = peak_case + results;
    if (results > peak_case) e.largest = "the results of every case";
    return e;
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
