#include "heightfield/ndf/student_t.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
RadialProfile student_t_profile(double gamma) {
    if (!(gamma >= StudentT::kGammaMin && gamma <= StudentT::kGammaMax))
        throw std::invalid_argument(
            "student_t: gamma must be in [2, 1e6] (below 2, D diverges at the horizon; at or below "
            "1.5 Smith's Lambda is infinite)");
    RadialProfile p;
    p.name = "student_t";
    p.parameters = parameter_list({{"gamma", gamma}});
    // R19 section 2.1 at unit roughness; log1p keeps gamma -> infinity exact (-> exp(-r2)).
    p.p22 = [gamma](double r2) { return std::exp(-gamma * std::log1p(r2 / (gamma - 1))) / kPi; };
    return p;
}
} // namespace

StudentT::StudentT(double alpha_x, double alpha_y, double gamma)
    : RadialNdf(alpha_x, alpha_y, student_t_profile(gamma)), gamma_(gamma) {}

} // namespace gonio
