#include "gonio/trace/accuracy_target.h"

#include "core/batch_means.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

const std::vector<std::string>& accuracy_target_quantities() {
    static const std::vector<std::string> q{"l1_albedo", "l2plus_albedo", "linf_albedo", "l1_cells",
                                            "linf_cells"};
    return q;
}

double relative_error_of(const TraceResult& r, const AccuracyTarget& t,
                         const BeckersSensor& sensor) {
    const int B = r.batches, nc = r.channels, no = r.orders;
    const bool first_only = t.quantity == "l1_albedo" || t.quantity == "l1_cells";
    const int from = t.quantity == "l2plus_albedo" ? 1 : 0, to = first_only ? 1 : no;
    auto relative = [](double mean, double err) { return mean != 0 ? err / std::abs(mean) : 0.0; };
    double worst = 0;
    if (t.quantity.find("albedo") != std::string::npos) {
        for (int k = 0; k < nc; ++k) {
            auto batch = [&](int b) {
                double s = 0;
                for (int o = from; o < to; ++o)
                    s += r.ledger_batches.reflected[(size_t(b) * no + o) * nc + k];
                return s;
            };
            double mean = 0;
            for (int b = 0; b < B; ++b) mean += batch(b) / B;
            worst = std::max(worst, relative(mean, batch_stderr(B, batch)));
        }
        return worst;
    }
    if (t.quantity != "l1_cells" && t.quantity != "linf_cells")
        throw std::invalid_argument("unknown accuracy target quantity " + t.quantity);
    const size_t per_order = size_t(r.cells) * nc, per_batch = size_t(no) * per_order;
    auto batch = [&](int b, size_t i) {
        double s = 0;
        for (int o = 0; o < to; ++o)
            s += r.energy_batches[size_t(b) * per_batch + o * per_order + i];
        return s;
    };
    std::vector<double> mean(per_order, 0.0), brdf(per_order);
    for (size_t i = 0; i < per_order; ++i) {
        for (int b = 0; b < B; ++b) mean[i] += batch(b, i) / B;
        brdf[i] = mean[i] / sensor.cell(int(i / size_t(nc))).projected_solid_angle;
    }
    for (int k = 0; k < nc; ++k) {
        double peak = 0;
        for (int c = 0; c < r.cells; ++c) peak = std::max(peak, brdf[size_t(c) * nc + k]);
        for (int c = 0; c < r.cells; ++c) {
            const size_t i = size_t(c) * nc + k;
            if (peak > 0 && brdf[i] >= t.cell_fraction * peak)
                worst = std::max(
                    worst, relative(mean[i], batch_stderr(B, [&](int b) { return batch(b, i); })));
        }
    }
    return worst;
}

} // namespace gonio
