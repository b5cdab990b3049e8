#include "gonio/cli/run_table.h"

#include <cstdio>

namespace gonio {

RunTable::RunTable(long long units, bool quiet, std::string checkpoint)
    : quiet_(quiet), checkpoint_(std::move(checkpoint)), progress_(units, quiet) {
    if (!quiet)
        std::printf("%-20s %7s %7s %10s %8s %10s %10s %7s %10s %10s %9s\n", "case", "theta_i",
                    "phi_i", "L1", "+-", "model", "rel_diff", "sigmas", "L2+", "T", "lost");
}

RunObserver RunTable::observer() {
    RunObserver o;
    o.started = [this](const std::string& label) { progress_.update(done_, label); };
    o.incidence = [this](const IncidenceReport& r) {
        ++done_;
        if (quiet_) return;
        progress_.finish();
        print(r);
    };
    o.warn = [this](const std::string& w) {
        if (!quiet_) std::fprintf(stderr, "gonio: warning: %s\n", w.c_str());
    };
    o.resumed = [this](long long done, long long total) {
        if (!quiet_)
            std::printf("resuming %s: %lld of %lld incidences done\n", checkpoint_.c_str(), done,
                        total);
    };
    return o;
}

void RunTable::print(const IncidenceReport& r) {
    const CaseConfig& c = *r.config;
    int shown = -1; // the first model of single scattering
    for (size_t m = 0; m < c.model.models.size() && shown < 0; ++m)
        if (c.model.models[m].compared_with == ModelTarget::l1) shown = int(m);
    const TraceResult& t = *r.trace;
    const SimulationResult& sim = *r.simulation;
    const size_t ti = r.id.theta_index, pi = r.id.phi_index;
    for (size_t k = 0; k < size_t(c.channels()); ++k) {
        const Estimate& l1 = sim.reflected.first_albedo;
        std::printf("%-20s %7.2f %7.2f %10.6f %8.1e", c.name.c_str(), r.theta_deg, r.phi_deg,
                    l1.mean.at({ti, pi, k}), l1.error.at({ti, pi, k}));
        if (shown >= 0) {
            const Comparison& cmp = (*r.comparisons)[size_t(shown)];
            std::printf(" %10.6f %+10.4f %+7.1f", cmp.model_albedo[k], cmp.relative_difference[k],
                        cmp.sigmas[k]);
        } else {
            std::printf(" %10s %10s %7s", "-", "-", "-");
        }
        std::printf(" %10.6f", sim.reflected.higher_albedo.mean.at({ti, pi, k}));
        if (c.material.transmits)
            std::printf(" %10.6f", sim.transmitted.all_albedo.mean.at({ti, pi, k}));
        else
            std::printf(" %10s", "-");
        std::printf(" %9.2e", sim.lost.mean.at({ti, pi, k}));
        if (c.trace.target.active())
            std::printf("  %s: %.2e with %lld rays", name_of(t.stop), t.achieved_error, t.rays);
        std::printf("\n");
    }
}

} // namespace gonio
