#include "heightfield/ndf/student_t.h"

#include "core/check.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
RadialProfile student_t_profile(double gamma) {
    GONIO_DCHECK(gamma >= StudentT::kGammaMin && gamma <= StudentT::kGammaMax); // key gamma
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

namespace gonio {
namespace {
const Key kGamma = Key::number("gamma", {StudentT::kGammaMin, StudentT::kGammaMax},
                               "tailedness γ (2 is GGX, → ∞ Beckmann)")
                       .cited("R19 section 2.1");
std::vector<Key> student_t_keys() {
    std::vector<Key> k{kGamma};
    k.insert(k.end(), roughness_keys().begin(), roughness_keys().end());
    return k;
}
} // namespace

const NdfFamily& student_t_family() {
    static const NdfFamily f{
        "student_t", "Student's t slopes [R19 section 2.1]", student_t_keys(),
        [](TableReader& r, int) -> std::unique_ptr<Ndf> {
            // A valid distribution below 2, but not a surface's: say why.
            const double gamma = r.number(kGamma.name, {1, StudentT::kGammaMax, true, false});
            if (gamma < StudentT::kGammaMin)
                r.fail("gamma", "value " + shortest(gamma) +
                                    " is outside gonio's domain [2, 1e6]: below 2 the slopes' "
                                    "variance is infinite (no height field follows them) and "
                                    "D diverges at the horizon; at 3/2 or below Smith's Lambda "
                                    "is infinite");
            const Roughness a = read_roughness(r);
            return std::make_unique<StudentT>(a.x, a.y, gamma);
        },
        true};
    return f;
}
} // namespace gonio
