#include "gonio/model/model_comparison.h"

#include "core/batch_means.h"

#include <algorithm>
#include <cmath>

namespace gonio {

Comparison compare_model(const TraceResult& sim, ModelTarget target, const ModelIncidence& model) {
    const int from = target == ModelTarget::l2plus ? 1 : 0;
    const int to = target == ModelTarget::l1 ? 1 : sim.orders;
    const size_t nc = size_t(sim.channels), cells = size_t(sim.cells), map = cells * nc;
    const int B = sim.batches, MB = model.batches;
    const std::vector<double>& s_batches = sim.sum_batches(from, to);
    const std::vector<double> s = batch_mean(s_batches, B), s_err = batch_stderr(s_batches, B);
    const std::vector<double> m_err =
        MB > 1 ? batch_stderr(model.energy_batches, MB) : std::vector<double>(map, 0.0);
    const std::vector<double>& m = model.energy;
    Comparison c;
    for (auto* v : {&c.model_albedo, &c.relative_difference, &c.relative_difference_stderr,
                    &c.sigmas, &c.distance, &c.distance_stderr})
        v->assign(nc, 0.0);
    c.ratio.assign(map, 0.0), c.ratio_stderr.assign(map, 0.0);
    auto sum_cells = [&](const double* v, size_t k) {
        double a = 0;
        for (size_t cell = 0; cell < cells; ++cell) a += v[cell * nc + k];
        return a;
    };
    // The distance of a simulated map to a model map, channel k.
    auto distance = [&](const std::vector<double>& fs, const std::vector<double>& fm, size_t k) {
        double num = 0, den = 0;
        for (size_t cell = 0; cell < cells; ++cell) {
            num += std::abs(fs[cell * nc + k] - fm[cell * nc + k]);
            den += fm[cell * nc + k];
        }
        return den > 0 ? num / den : 0.0;
    };
    for (size_t k = 0; k < nc; ++k) {
        const double a_s = sum_cells(s.data(), k), a_m = sum_cells(m.data(), k);
        const double e_s =
            batch_stderr(B, [&](int b) { return sum_cells(&s_batches[b * map], k); });
        const double e_m =
            MB > 1 ? batch_stderr(
                         MB, [&](int b) { return sum_cells(&model.energy_batches[b * map], k); })
                   : model.relative_tolerance * a_m;
        c.model_albedo[k] = a_m;
        if (a_m > 0) {
            c.relative_difference[k] = (a_s - a_m) / a_m;
            c.relative_difference_stderr[k] =
                std::hypot(e_s / a_m, a_s * e_m / (a_m * a_m)); // delta method
        }
        const double e = std::hypot(e_s, e_m);
        c.sigmas[k] = e > 0 ? (a_s - a_m) / e : 0.0;
        c.distance[k] = distance(s, m, k);
        // Jackknife over the simulation's batches, then over the model's: independent, so the
        // variances add. (Channel k's cells alone: the distance reads no other.)
        std::vector<double> without(map);
        const double j_s = jackknife_stderr(B, [&](int b) {
            for (size_t i = k; i < map; i += nc)
                without[i] = mean_without(s[i], s_batches[b * map + i], B);
            return distance(without, m, k);
        });
        const double j_m = jackknife_stderr(MB, [&](int b) {
            for (size_t i = k; i < map; i += nc)
                without[i] = mean_without(m[i], model.energy_batches[b * map + i], MB);
            return distance(s, without, k);
        });
        c.distance_stderr[k] = std::hypot(j_s, j_m);
        // Ratios where the model is not negligible (a ratio to a denormal is no information, and
        // its error overflows).
        double peak = 0;
        for (size_t cell = 0; cell < cells; ++cell) peak = std::max(peak, m[cell * nc + k]);
        for (size_t cell = 0; cell < cells; ++cell) {
            const size_t i = cell * nc + k;
            if (m[i] <= 1e-12 * peak) continue;
            const double me = MB > 1 ? m_err[i] : model.relative_tolerance * m[i];
            c.ratio[i] = s[i] / m[i];
            c.ratio_stderr[i] = std::hypot(s_err[i] / m[i], s[i] * me / (m[i] * m[i]));
        }
    }
    return c;
}

Comparison compare_case_model(const TraceResult& sim, ModelTarget target,
                              const ModelIncidence& model) {
    Comparison c = compare_model(sim, target, model);
    if (target != ModelTarget::linf || !model.has_orders()) return c;
    ModelIncidence rest; // every order but the first
    rest.energy = model.energy;
    for (size_t i = 0; i < rest.energy.size(); ++i) rest.energy[i] -= model.l1_energy[i];
    rest.relative_tolerance = model.relative_tolerance;
    rest.batches = model.batches;
    rest.energy_batches = model.energy_batches;
    for (size_t i = 0; i < rest.energy_batches.size(); ++i)
        rest.energy_batches[i] -= model.l1_energy_batches[i];
    c.l2plus.push_back(compare_model(sim, ModelTarget::l2plus, rest));
    return c;
}

} // namespace gonio
