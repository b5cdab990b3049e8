#pragma once
// A shape-invariant distribution given only by its unit-roughness isotropic slope density
// P22_1(r), r = |slope| [R19 Eq. 6]: D, Lambda and both samplers follow numerically, so a new
// family needs nothing but P22_1. Any isotropic distribution is one (with alpha = 1).
//
// - D(m) = P22_1(r^2) / (alpha_x alpha_y cos^4 theta_m) with the stretched slope radius r.
// - Lambda: from the slope marginal [R19 Eq. 7-8], mu Lambda(mu) = E[(x - mu)+] with mu = cot
//   theta, which for a radial density is the single integral
//   2 int_mu^inf P22_1(r) r (sqrt(r^2 - mu^2) - mu acos(mu / r)) dr,
//   tabulated per instance at 1025 polar angles and interpolated (cubic) between them.
// - D cos sampling: the slope radius by the tabulated inverse CDF of 2 pi r P22_1(r), the azimuth
//   uniform, then stretched.
// - Visible normals: slopes with density proportional to (mu - x)+ P22_1, exactly, by rejection
//   from the mixture mu P22_1 + |x| P22_1 (acceptance >= 1/2). The extra uniforms come from a
//   stream keyed by (u1, u2), so the result is still a function of them.
#include "heightfield/ndf/radial_table.h"
#include "heightfield/ndf/shape_invariant_ndf.h"

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

struct RadialProfile {
    std::string name;       // family name, e.g. "student_t"
    std::string parameters; // shape parameters for describe(), e.g. "gamma=3"
    // Unit-roughness slope density of the squared radius, normalised: 2 pi int P22_1 r dr = 1.
    std::function<double(double)> p22;
    std::vector<double> kinks; // radii where P22_1 is not smooth
    double bulk = 1.0;         // radius holding most of the mass
    double narrow = 1.0;       // angular scale of the narrowest feature at alpha = 1 (rad)
    double wide = 1.0;         // and of the widest
};

// "name=value, ..." at full precision, for RadialProfile::parameters.
std::string parameter_list(std::initializer_list<std::pair<const char*, double>> values);

class RadialNdf : public ShapeInvariantNdf {
  public:
    RadialNdf(double alpha_x, double alpha_y, RadialProfile profile);

    std::string name() const override { return profile_.name; }
    std::string describe() const override;
    double narrowest_feature() const override;
    double widest_feature() const override;
    // The unit-roughness slope density, for tests and for other distributions built on this one.
    double p22_unit(double r2) const { return profile_.p22(r2); }

  protected:
    double d_unit(double r2, double cos2) const override;
    double lambda_unit(double t2) const override;
    double sample_slope_radius2(double u) const override;
    void sample_visible_slope(double c, double u1, double u2, double& x, double& y) const override;

  private:
    double g_of_theta(double theta) const; // E[(x - cot theta)+], interpolated

    RadialProfile profile_;
    std::unique_ptr<RadialTable> radius_;  // density r P22_1(r): slope radius of D cos
    std::unique_ptr<RadialTable> radius2_; // density r^2 P22_1(r): the rejection proposal
    std::vector<double> g_;                // E[(x - mu)+] at theta_j = j (pi/2) / (size - 1)
};

} // namespace gonio
