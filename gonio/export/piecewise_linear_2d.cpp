#include "gonio/export/piecewise_linear_2d.h"

#include "gonio/table/sensor_lobe.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

PiecewiseLinear2D::PiecewiseLinear2D(std::vector<double> data, int width, int height,
                                     bool normalize)
    : d_(std::move(data)), w_(width), h_(height) {
    if (w_ < 2 || h_ < 2 || d_.size() != size_t(w_) * size_t(h_))
        throw std::invalid_argument("PiecewiseLinear2D: need an H x W grid with W, H >= 2");
    const double dx = 1.0 / (w_ - 1), dy = 1.0 / (h_ - 1);
    conditional_cdf_.assign(d_.size(), 0.0);
    for (int y = 0; y < h_; ++y)
        for (int x = 1; x < w_; ++x)
            conditional_cdf_[size_t(y) * w_ + x] =
                conditional_cdf_[size_t(y) * w_ + x - 1] + 0.5 * dx * (at(x - 1, y) + at(x, y));
    marginal_cdf_.assign(size_t(h_), 0.0);
    auto row = [&](int y) { return conditional_cdf_[size_t(y) * w_ + w_ - 1]; };
    for (int y = 1; y < h_; ++y)
        marginal_cdf_[y] = marginal_cdf_[y - 1] + 0.5 * dy * (row(y - 1) + row(y));
    integral_ = marginal_cdf_.back();
    if (normalize) {
        if (!(integral_ > 0))
            throw std::invalid_argument("PiecewiseLinear2D: a density with zero integral");
        scale_ = 1 / integral_;
    }
}

namespace {
// Patch index and fraction of a coordinate in [0, 1] on n vertices.
void locate(double p, int n, int& i, double& f) {
    const double pos = std::clamp(p, 0.0, 1.0) * (n - 1);
    i = std::min(static_cast<int>(pos), n - 2);
    f = pos - i;
}
double lerp(double a, double b, double t) {
    return a + (b - a) * t;
}
} // namespace

double PiecewiseLinear2D::eval(Point p) const {
    int x, y;
    double fx, fy;
    locate(p[0], w_, x, fx);
    locate(p[1], h_, y, fy);
    return scale_ *
           lerp(lerp(at(x, y), at(x + 1, y), fx), lerp(at(x, y + 1), at(x + 1, y + 1), fx), fy);
}

PiecewiseLinear2D::Point PiecewiseLinear2D::sample(Point u, double* pdf) const {
    const double dx = 1.0 / (w_ - 1), dy = 1.0 / (h_ - 1);
    auto row = [&](int y) { return conditional_cdf_[size_t(y) * w_ + w_ - 1]; };
    // Rows: the marginal's patch, then the linear density between the two rows' integrals.
    double target = std::clamp(u[1], 0.0, 1.0) * integral_;
    int y = int(std::upper_bound(marginal_cdf_.begin(), marginal_cdf_.end(), target) -
                marginal_cdf_.begin()) -
            1;
    y = std::clamp(y, 0, h_ - 2);
    const double r0 = row(y), r1 = row(y + 1);
    const double patch_y = 0.5 * dy * (r0 + r1);
    const double ty =
        patch_y > 0
            ? sample_linear(std::clamp((target - marginal_cdf_[y]) / patch_y, 0.0, 1.0), r0, r1)
            : 0.0;
    // Columns: the conditional at that height, lerped between the two rows.
    auto ccdf = [&](int x) {
        return lerp(conditional_cdf_[size_t(y) * w_ + x], conditional_cdf_[size_t(y + 1) * w_ + x],
                    ty);
    };
    target = std::clamp(u[0], 0.0, 1.0) * lerp(r0, r1, ty);
    int lo = 0, hi = w_ - 1; // largest x with ccdf(x) <= target, in [0, W - 2]
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        (ccdf(mid) <= target ? lo : hi) = mid;
    }
    const int x = lo;
    const double c0 = lerp(at(x, y), at(x, y + 1), ty),
                 c1 = lerp(at(x + 1, y), at(x + 1, y + 1), ty);
    const double patch_x = 0.5 * dx * (c0 + c1);
    const double tx =
        patch_x > 0 ? sample_linear(std::clamp((target - ccdf(x)) / patch_x, 0.0, 1.0), c0, c1)
                    : 0.0;
    const Point p{(x + tx) * dx, (y + ty) * dy};
    if (pdf) *pdf = lerp(c0, c1, tx) / integral_;
    return p;
}

PiecewiseLinear2D::Point PiecewiseLinear2D::invert(Point p, double* pdf) const {
    const double dx = 1.0 / (w_ - 1), dy = 1.0 / (h_ - 1);
    auto row = [&](int y) { return conditional_cdf_[size_t(y) * w_ + w_ - 1]; };
    int x, y;
    double tx, ty;
    locate(p[0], w_, x, tx);
    locate(p[1], h_, y, ty);
    const double r0 = row(y), r1 = row(y + 1);
    const double uy = (marginal_cdf_[y] + dy * (r0 * ty + 0.5 * (r1 - r0) * ty * ty)) / integral_;
    const double c0 = lerp(at(x, y), at(x, y + 1), ty),
                 c1 = lerp(at(x + 1, y), at(x + 1, y + 1), ty);
    const double before =
        lerp(conditional_cdf_[size_t(y) * w_ + x], conditional_cdf_[size_t(y + 1) * w_ + x], ty);
    const double row_total = lerp(r0, r1, ty);
    const double ux =
        row_total > 0 ? (before + dx * (c0 * tx + 0.5 * (c1 - c0) * tx * tx)) / row_total : 0.0;
    if (pdf) *pdf = lerp(c0, c1, tx) / integral_;
    return {ux, uy};
}

} // namespace gonio
