#include "heightfield/ndf/sinc_ndf.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gonio {

ControlPoints SincNdf::curve(double k, double floor, int intervals) {
    if (!(k > 0 && k <= 200)) throw std::invalid_argument("sinc: k must be in (0, 200] per radian");
    if (!(floor >= 0 && floor <= 1)) throw std::invalid_argument("sinc: floor must be in [0, 1]");
    if (intervals < 8 || intervals > 4096)
        throw std::invalid_argument("sinc: points must be in [9, 4097]");
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
    s.precision(17);
    s << "k=" << k << ", floor=" << floor << ", points=" << intervals + 1;
    return s.str();
}
} // namespace

SincNdf::SincNdf(double k, double floor, int intervals)
    : PiecewiseLinearNdf(curve(k, floor, intervals), "sinc", parameters(k, floor, intervals)) {}

} // namespace gonio
