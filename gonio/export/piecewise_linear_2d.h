#pragma once
// The continuous 2-D warp of the RGL measured-BSDF readers (Mitsuba 3 Marginal2D, pbrt-v4
// PiecewiseLinear2D, rgl-epfl/brdf-loader), for one parameter slice: a density bilinear between
// the vertices of an H x W grid over [0, 1]^2 (vertex [y][x] at (x / (W - 1), y / (H - 1))),
// sampled by inverting the marginal over rows (y) first, then the conditional along x. The
// exporter warps with it exactly as the readers will; sample and invert are exact inverses.
#include <array>
#include <cstddef>
#include <vector>

namespace gonio {

class PiecewiseLinear2D {
  public:
    using Point = std::array<double, 2>; // (x, y)
    // `data` holds H rows of W non-negative values; W, H >= 2. With `normalize`, eval returns the
    // density (the interpolant divided by its integral); otherwise the raw interpolant.
    PiecewiseLinear2D(std::vector<double> data, int width, int height, bool normalize);

    int width() const { return w_; }
    int height() const { return h_; }
    double integral() const { return integral_; } // of the raw interpolant
    double eval(Point p) const;
    // A point with pdf eval(p) (normalised density); u in [0, 1]^2.
    Point sample(Point u, double* pdf = nullptr) const;
    // The inverse of sample: the u that maps to p.
    Point invert(Point p, double* pdf = nullptr) const;

  private:
    double at(int x, int y) const { return d_[std::size_t(y) * w_ + x]; }
    std::vector<double> d_;
    std::vector<double> conditional_cdf_; // [y][x]: mass of row y's curve in [0, x / (W-1)]
    std::vector<double> marginal_cdf_;    // [y]: mass of the rows' integrals in [0, y / (H-1)]
    int w_, h_;
    double integral_ = 0, scale_ = 1;
};

} // namespace gonio
