#pragma once
// The isotropic piecewise-linear NDF of R19 section 3: D_iso(theta) linear between n control
// points 0 = theta_0 < ... < theta_n = pi/2 [R19 Eq. 11], normalised by the closed form of
// R19 Eq. 12. As a radial slope density (alpha = 1), Lambda and both samplers come from
// RadialNdf, with the control points as the density's kinks.
#include "heightfield/ndf/radial_ndf.h"

#include <vector>

namespace gonio {

struct ControlPoints {
    std::vector<double> theta; // radians, from 0 to pi/2, increasing
    std::vector<double> value; // D_iso at theta, >= 0 (any scale: normalised on construction)
};

class PiecewiseLinearNdf : public RadialNdf {
  public:
    // Throws std::invalid_argument naming the problem (too few points, bad order, negative values).
    explicit PiecewiseLinearNdf(ControlPoints points, std::string name = "piecewise_linear",
                                std::string parameters = "");
    // n + 1 control points uniform in theta on [0, pi/2], from D(theta, phi = 0) of `source`.
    static ControlPoints sampled_from(const Ndf& source, int intervals);
    const ControlPoints& points() const { return points_; } // normalised values

  private:
    ControlPoints points_;
};

// 2 pi sum of int (a theta + b) cos theta sin theta over the segments [R19 Eq. 12].
double piecewise_linear_normalisation(const ControlPoints& points);

} // namespace gonio
