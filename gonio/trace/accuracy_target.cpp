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
    const bool albedo = t.quantity.find("albedo") != std::string::npos;
    if (!albedo && t.quantity != "l1_cells" && t.quantity != "linf_cells")
        throw std::invalid_argument("unknown accuracy target quantity " + t.quantity);
    // Per batch, the quantity's albedos [channel] or cell energies [cell][channel].
    const std::vector<double> x =
        sum_orders(albedo ? r.ledger_batches.reflected : r.energy_batches, B, no, from, to);
    const std::vector<double> mean = batch_mean(x, B), err = batch_stderr(x, B);
    auto relative = [&](size_t i) { return mean[i] != 0 ? err[i] / std::abs(mean[i]) : 0.0; };
    double worst = 0;
    if (albedo) {
        for (size_t k = 0; k < size_t(nc); ++k) worst = std::max(worst, relative(k));
        return worst;
    }
    // The cells that count: BRDF (energy over projected solid angle) at least the fraction of
    // the brightest, per channel.
    auto brdf = [&](size_t i) {
        return mean[i] / sensor.cell(int(i / size_t(nc))).projected_solid_angle;
    };
    for (size_t k = 0; k < size_t(nc); ++k) {
        double peak = 0;
        for (size_t i = k; i < mean.size(); i += size_t(nc)) peak = std::max(peak, brdf(i));
        for (size_t i = k; i < mean.size(); i += size_t(nc))
            if (peak > 0 && brdf(i) >= t.cell_fraction * peak) worst = std::max(worst, relative(i));
    }
    return worst;
}

} // namespace gonio
