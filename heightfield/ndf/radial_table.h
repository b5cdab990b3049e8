#pragma once
// Tabulated inverse-CDF sampling of a radial density g(r) = r^k f(r) on [0, infinity), for
// distributions whose radial CDF has no usable closed form. The half-line is mapped to
// w = r / (s + r) in [0, 1), so heavy tails need no cut-off; the CDF is integrated exactly
// (adaptive Gauss-Kronrod) between nodes uniform in w and at the density's kinks, and inverted
// inside a node interval on the cubic Hermite interpolant of (CDF, density), which is accurate to
// O(h^4) where the density is smooth.
#include <functional>
#include <vector>

namespace gonio {

class RadialTable {
  public:
    // f >= 0 with a finite integral of r^k f(r); `scale` s is the radius of the bulk (nodes
    // cluster within a few s); `kinks` are radii where f is not smooth.
    RadialTable(std::function<double(double)> f, int k, double scale,
                const std::vector<double>& kinks = {}, int nodes = 2048);

    // Integral of r^k f(r) over [0, infinity).
    double total() const { return total_; }
    // A radius with density r^k f(r) / total(), from u in [0, 1).
    double sample(double u) const;

  private:
    double radius(double w) const { return scale_ * w / (1.0 - w); }
    double density_w(double w) const; // r^k f(r) dr/dw

    std::function<double(double)> f_;
    int k_;
    double scale_;
    std::vector<double> w_, cdf_;             // nodes in w and the CDF at them
    std::vector<double> pdf_start_, pdf_end_; // density (in w) inside interval j at its two ends
    double total_ = 0;
};

} // namespace gonio
