#include "heightfield/ndf/generalized_t.h"

#include "core/check.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
RadialProfile generalized_t_profile(double p, double q) {
    // The keys p and q, and p q >= 2, checked where they are read.
    GONIO_DCHECK(p >= GeneralizedT::kPMin && p <= GeneralizedT::kPMax);
    GONIO_DCHECK(q > 0 && q <= GeneralizedT::kQMax && p * q >= 2);
    RadialProfile f;
    f.name = "generalized_t";
    f.parameters = parameter_list({{"p", p}, {"q", q}});
    // log of p / (2 pi q^(2/p) B(2/p, q)), with B from log-gamma (finite for large q).
    const double a = 2 / p;
    const double log_c = std::log(p / (2 * kPi)) - a * std::log(q) -
                         (std::lgamma(a) + std::lgamma(q) - std::lgamma(q + a));
    f.p22 = [p, q, a, log_c](double r2) {
        return std::exp(log_c - (q + a) * std::log1p(std::pow(r2, 0.5 * p) / q));
    };
    f.bulk = std::pow(2 / p, 1 / p);
    if (p > 4) f.kinks = {1.0};
    f.narrow = std::min(1.0, f.bulk);
    f.wide = std::max(1.0, f.bulk);
    return f;
}
} // namespace

GeneralizedT::GeneralizedT(double alpha_x, double alpha_y, double p, double q)
    : RadialNdf(alpha_x, alpha_y, generalized_t_profile(p, q)), p_(p), q_(q) {}

} // namespace gonio

namespace gonio {
namespace {
const Key kP = Key::number("p", {GeneralizedT::kPMin, GeneralizedT::kPMax},
                           "shape p (2 is Beckmann / Student's t)")
                   .cited("R19 section 2.1");
const Key kQ = Key::number("q", {0, GeneralizedT::kQMax, true, false},
                           "tail q (p = 2: Student's t with γ = q + 1; q → ∞: generalised normal)")
                   .noting("p q ≥ 2");
} // namespace
const NdfFamily& generalized_t_family() {
    static const NdfFamily f{"generalized_t", "generalised t slopes [R19 section 2.1]",
                             [] {
                                 std::vector<Key> k{kP, kQ};
                                 k.insert(k.end(), roughness_keys().begin(),
                                          roughness_keys().end());
                                 return k;
                             }(),
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const double p = r.number(kP), q = r.number(kQ);
                                 if (!(p * q >= 2))
                                     r.fail("q", "p q must be >= 2 (below 2, D diverges at the "
                                                 "horizon)");
                                 const Roughness a = read_roughness(r);
                                 return std::make_unique<GeneralizedT>(a.x, a.y, p, q);
                             },
                             true};
    return f;
}
} // namespace gonio
