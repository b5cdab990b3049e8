#include "gonio/run/ensemble_plan.h"

#include <algorithm>
#include <cmath>

namespace gonio {

EnsembleStep plan_ensemble(const AccuracyTarget& target, int most, const EnsembleStatus& s,
                           const std::function<double()>& surface_share) {
    EnsembleStep step;
    step.per_surface = s.per_surface;
    if (!target.active()) return step; // the configured surfaces, once
    const double goal = target.relative_error;
    if (s.passes > 1) { // the sized pass: what it achieved is what it reports
        step.stop = s.error <= goal ? StopReason::target : StopReason::target_not_met;
        return step;
    }
    if (s.elapsed >= target.max_seconds) return step.stop = StopReason::max_seconds, step;
    const int has = s.realisations;
    if (has >= most) return step.stop = StopReason::max_realisations, step;
    // Both parts of the variance fall as 1 / R, so R' = R e^2 / g^2 (a little past the need; at
    // least twice the pilot, so that the pilot is at most half of the final estimate). Where the
    // rays' part would still be more than half the target's variance, the new surfaces get more
    // rays each.
    // (An error that is not finite, a quantity of mean 0, asks for the most: clamped in double
    // before any cast.)
    const double e2 = std::isfinite(s.error) ? s.error * s.error : 1e300, g2 = goal * goal;
    const double rays = (1 - surface_share()) * e2;
    int want = int(std::min(double(most), std::max(2.0 * has, std::ceil(has * e2 / g2 * 1.05))));
    const double rays_then = rays * has / want;
    if (rays_then > 0.5 * g2)
        step.per_surface = (long long)std::min(
            double(target.max_rays), std::ceil(double(s.per_surface) * rays_then / (0.5 * g2)));
    const long long left = target.max_rays - s.rays;
    want = int(std::min<long long>(want, has + std::max(0LL, left) / step.per_surface));
    if (want <= has) return step.stop = StopReason::max_rays, step;
    step.done = false;
    step.wanted = want;
    return step;
}

} // namespace gonio
