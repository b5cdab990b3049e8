#pragma once
// The two-shape generalisation of Student's t and the generalised normal (the radial
// generalised-t of McDonald & Newey; the symmetric core of R19's SGTD, section 2.1):
//   P22(s) = p / (2 pi alpha^2 q^(2/p) B(2/p, q)) (1 + (|s| / alpha)^p / q)^(-(q + 2/p)).
// p = 2 gives Student's t with gamma = q + 1; q -> infinity gives the generalised normal of the
// same p. D(m) ~ tan^(2 - p q) theta_m near the horizon: it diverges for p q < 2 (and Lambda is
// infinite for p q <= 1). gonio accepts p in [0.5, 20], q in (0, 1e6] with p q >= 2.
#include "heightfield/ndf/radial_ndf.h"

namespace gonio {

class GeneralizedT final : public RadialNdf {
  public:
    static constexpr double kPMin = 0.5, kPMax = 20, kQMax = 1e6;
    GeneralizedT(double alpha_x, double alpha_y, double p, double q);
    double p() const { return p_; }
    double q() const { return q_; }

  private:
    double p_, q_;
};

} // namespace gonio
