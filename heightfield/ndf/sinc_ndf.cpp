#include "heightfield/ndf/sinc_ndf.h"

#include "core/check.h"
#include "core/number_text.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gonio {

ControlPoints SincNdf::curve(double k, double floor, int intervals) {
    GONIO_DCHECK(k > 0 && k <= 200 && floor >= 0 && floor <= 1); // the keys k and floor
    GONIO_DCHECK(intervals >= 8 && intervals <= 4096);           // the key points
    ControlPoints p;
    for (int i = 0; i <= intervals; ++i) {
        const double theta = 0.5 * kPi * i / intervals, x = k * theta;
        const double sinc = x == 0 ? 1.0 : std::sin(x) / x;
        p.theta.push_back(theta);
        p.value.push_back(sinc * sinc + floor);
    }
    return p;
}

namespace {
std::string parameters(double k, double floor, int intervals) {
    std::ostringstream s;
    s << "k=" << shortest(k) << ", floor=" << shortest(floor) << ", points=" << intervals + 1;
    return s.str();
}
} // namespace

SincNdf::SincNdf(double k, double floor, int intervals)
    : PiecewiseLinearNdf(curve(k, floor, intervals), "sinc", parameters(k, floor, intervals)) {}

} // namespace gonio

namespace gonio {
namespace {
const Key kK = Key::number("k", {0, 200, true, false}, "D ∝ sinc²(kθ) + floor")
                   .in_unit("per rad")
                   .cited("R19 section 5.1");
const Key kFloor = Key::number("floor", {0, 1}, "sinc: floor, relative to the peak").fallback(0.0);
const Key kPoints =
    Key::integer("points", {9, 4097}, "sinc: control points of the curve").fallback(129.0);
} // namespace
const NdfFamily& sinc_family() {
    static const NdfFamily f{"sinc",
                             "sinc² multi-lobe curve [R19 section 5.1, Fig. 10]",
                             {kK, kFloor, kPoints},
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const double k = r.number(kK), floor = r.number(kFloor);
                                 return std::make_unique<SincNdf>(k, floor,
                                                                  int(r.integer(kPoints)) - 1);
                             },
                             true};
    return f;
}
} // namespace gonio
