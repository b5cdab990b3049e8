#include "heightfield/ndf/generalized_normal.h"

#include "core/check.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
RadialProfile generalized_normal_profile(double p) {
    GONIO_DCHECK(p >= GeneralizedNormal::kPMin && p <= GeneralizedNormal::kPMax); // key p
    RadialProfile f;
    f.name = "generalized_normal";
    f.parameters = parameter_list({{"p", p}});
    const double c = p / (2 * kPi * std::tgamma(2 / p)); // R19 section 2.1, alpha = 1
    f.p22 = [p, c](double r2) { return c * std::exp(-std::pow(r2, 0.5 * p)); };
    f.bulk = std::pow(2 / p, 1 / p); // where r^p reaches its mean 2/p
    if (p > 4) f.kinks = {1.0};      // a flat top that drops steeply at r = 1
    f.narrow = std::min(1.0, f.bulk);
    f.wide = std::max(1.0, f.bulk);
    return f;
}
} // namespace

GeneralizedNormal::GeneralizedNormal(double alpha_x, double alpha_y, double p)
    : RadialNdf(alpha_x, alpha_y, generalized_normal_profile(p)), p_(p) {}

} // namespace gonio

namespace gonio {
namespace {
const Key kP = Key::number("p", {GeneralizedNormal::kPMin, GeneralizedNormal::kPMax},
                           "shape p (2 is Beckmann / Student's t)")
                   .cited("R19 section 2.1");
}
const NdfFamily& generalized_normal_family() {
    static const NdfFamily f{"generalized_normal", "generalised normal slopes [R19 section 2.1]",
                             [] {
                                 std::vector<Key> k{kP};
                                 k.insert(k.end(), roughness_keys().begin(),
                                          roughness_keys().end());
                                 return k;
                             }(),
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const double p = r.number(kP);
                                 const Roughness a = read_roughness(r);
                                 return std::make_unique<GeneralizedNormal>(a.x, a.y, p);
                             },
                             true};
    return f;
}
} // namespace gonio
