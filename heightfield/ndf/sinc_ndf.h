#pragma once
// A multi-lobe isotropic NDF built on a cardinal sine, as the seed paper's cases 7 and 8
// [R19 section 5.1, Fig. 10]: D(theta) proportional to sinc^2(k theta) + floor (sinc x =
// sin x / x; lobes at k theta = (j + 1/2) pi, zeros at j pi), handled through the piecewise-linear
// machinery with n + 1 control points uniform in theta [R19 Eq. 11-12].
#include "heightfield/ndf/piecewise_linear.h"

namespace gonio {

class SincNdf final : public PiecewiseLinearNdf {
  public:
    // k in (0, 200] per radian, floor in [0, 1] (relative to the peak), intervals in [8, 4096].
    SincNdf(double k, double floor, int intervals);
    static ControlPoints curve(double k, double floor, int intervals);
};

} // namespace gonio
