#include "heightfield/measured/map_preparation.h"

#include "core/config_error.h"
#include "heightfield/measured/gaussian_filter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <stdexcept>

namespace gonio {

namespace {
std::string percent(double share) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g %%", 100 * share);
    return text;
}

double rms(const std::vector<double>& z) {
    double mean = 0, square = 0;
    for (double v : z) mean += v;
    mean /= double(z.size());
    for (double v : z) square += (v - mean) * (v - mean);
    return std::sqrt(square / double(z.size()));
}

double median(std::vector<double>& v) {
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + long(mid), v.end());
    double m = v[mid];
    if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + long(mid)));
    return m;
}

// Spikes: a point whose distance to the median of its 3 x 3 neighbourhood exceeds `threshold`
// robust sigmas (1.4826 x the median absolute distance over the map) -- the median filter's
// residual, robust to tilt and form (Gwyddion's and surfalize's outlier rules are of this kind).
size_t remove_spikes(MeasuredMap& m, double threshold) {
    std::vector<double> residual(m.z.size(), NAN), window;
    for (int y = 0; y < m.ny; ++y)
        for (int x = 0; x < m.nx; ++x) {
            if (std::isnan(m.at(x, y))) continue;
            window.clear();
            for (int j = std::max(0, y - 1); j <= std::min(m.ny - 1, y + 1); ++j)
                for (int i = std::max(0, x - 1); i <= std::min(m.nx - 1, x + 1); ++i)
                    if (!std::isnan(m.at(i, j))) window.push_back(m.at(i, j));
            residual[size_t(y) * m.nx + x] = m.at(x, y) - median(window);
        }
    std::vector<double> spread;
    for (double r : residual)
        if (!std::isnan(r)) spread.push_back(std::abs(r));
    if (spread.empty()) return 0;
    // 1.4826 MAD is sigma for normal residuals; where more than half of them are 0 (a smooth or
    // synthetic map) the mean absolute residual stands in (sqrt(pi / 2) of it, likewise).
    double sigma = 1.4826 * median(spread);
    if (!(sigma > 0)) {
        double mean = 0;
        for (double r : spread) mean += r;
        sigma = std::sqrt(M_PI / 2) * mean / double(spread.size());
    }
    if (!(sigma > 0)) return 0;
    size_t removed = 0;
    for (size_t k = 0; k < m.z.size(); ++k)
        if (std::abs(residual[k]) > threshold * sigma) m.z[k] = NAN, ++removed;
    return removed;
}

// Least-squares polynomial of total degree `degree` in centred, scaled coordinates, subtracted.
void level(MeasuredMap& m, int degree) {
    std::vector<std::pair<int, int>> terms;
    for (int d = 0; d <= degree; ++d)
        for (int i = d; i >= 0; --i) terms.push_back({i, d - i});
    const size_t t = terms.size();
    std::vector<double> a(t * t, 0.0), b(t, 0.0), f(t);
    auto basis = [&](int x, int y) {
        const double u = (2.0 * x - (m.nx - 1)) / std::max(1, m.nx - 1);
        const double v = (2.0 * y - (m.ny - 1)) / std::max(1, m.ny - 1);
        for (size_t k = 0; k < t; ++k)
            f[k] = std::pow(u, terms[k].first) * std::pow(v, terms[k].second);
    };
    for (int y = 0; y < m.ny; ++y)
        for (int x = 0; x < m.nx; ++x) {
            const double z = m.at(x, y);
            if (std::isnan(z)) continue;
            basis(x, y);
            for (size_t i = 0; i < t; ++i) {
                b[i] += f[i] * z;
                for (size_t j = 0; j < t; ++j) a[i * t + j] += f[i] * f[j];
            }
        }
    // Gaussian elimination with partial pivoting (at most 10 unknowns).
    std::vector<size_t> order(t);
    for (size_t i = 0; i < t; ++i) {
        size_t pivot = i;
        for (size_t r = i + 1; r < t; ++r)
            if (std::abs(a[r * t + i]) > std::abs(a[pivot * t + i])) pivot = r;
        if (!(std::abs(a[pivot * t + i]) > 0))
            throw std::runtime_error("too few valid points to level the map");
        for (size_t c = 0; c < t; ++c) std::swap(a[i * t + c], a[pivot * t + c]);
        std::swap(b[i], b[pivot]);
        for (size_t r = i + 1; r < t; ++r) {
            const double k = a[r * t + i] / a[i * t + i];
            for (size_t c = i; c < t; ++c) a[r * t + c] -= k * a[i * t + c];
            b[r] -= k * b[i];
        }
    }
    std::vector<double> coef(t);
    for (size_t i = t; i-- > 0;) {
        double s = b[i];
        for (size_t c = i + 1; c < t; ++c) s -= a[i * t + c] * coef[c];
        coef[i] = s / a[i * t + i];
    }
    for (int y = 0; y < m.ny; ++y)
        for (int x = 0; x < m.nx; ++x) {
            double& z = m.at(x, y);
            if (std::isnan(z)) continue;
            basis(x, y);
            for (size_t k = 0; k < t; ++k) z -= coef[k] * f[k];
        }
}

// Missing points: harmonic (Laplace) interpolation from the valid ones -- each filled point the
// mean of its neighbours -- started from the mean of the valid neighbours in order of distance
// to the valid region, then relaxed by Gauss-Seidel sweeps until it settles.
void fill(MeasuredMap& m) {
    std::vector<char> missing(m.z.size(), 0);
    std::deque<size_t> queue;
    for (size_t k = 0; k < m.z.size(); ++k) missing[k] = std::isnan(m.z[k]);
    std::vector<char> known(m.z.size());
    for (size_t k = 0; k < m.z.size(); ++k) known[k] = !missing[k];
    auto neighbours = [&](size_t k, auto&& each) {
        const int x = int(k % m.nx), y = int(k / m.nx);
        if (x > 0) each(k - 1);
        if (x + 1 < m.nx) each(k + 1);
        if (y > 0) each(k - m.nx);
        if (y + 1 < m.ny) each(k + m.nx);
    };
    for (size_t k = 0; k < m.z.size(); ++k)
        if (missing[k]) {
            bool edge = false;
            neighbours(k, [&](size_t j) { edge = edge || known[j]; });
            if (edge) queue.push_back(k);
        }
    std::vector<char> queued(missing);
    for (size_t k : queue) queued[k] = 2;
    while (!queue.empty()) {
        const size_t k = queue.front();
        queue.pop_front();
        double sum = 0;
        int count = 0;
        neighbours(k, [&](size_t j) {
            if (known[j]) sum += m.z[j], ++count;
        });
        m.z[k] = sum / count;
        known[k] = 1;
        neighbours(k, [&](size_t j) {
            if (!known[j] && queued[j] != 2) queued[j] = 2, queue.push_back(j);
        });
    }
    double lo = INFINITY, hi = -INFINITY;
    for (double z : m.z) lo = std::min(lo, z), hi = std::max(hi, z);
    const double tolerance = 1e-9 * std::max(hi - lo, 1e-300);
    for (int sweep = 0; sweep < 10000; ++sweep) {
        double change = 0;
        for (size_t k = 0; k < m.z.size(); ++k) {
            if (!missing[k]) continue;
            double sum = 0;
            int count = 0;
            neighbours(k, [&](size_t j) { sum += m.z[j], ++count; });
            const double v = sum / count;
            change = std::max(change, std::abs(v - m.z[k]));
            m.z[k] = v;
        }
        if (change <= tolerance) break;
    }
}
} // namespace

PreparedMap prepare_measured_map(const MeasuredMap& map, const MapPreparation& p,
                                 const std::string& path) {
    MeasuredMap m = map;
    PreparedMap out;
    const double n = double(m.z.size());
    size_t missing = 0;
    for (double z : m.z) missing += std::isnan(z);
    out.missing_share = missing / n;
    if (missing == m.z.size()) throw std::runtime_error(path + ": every point is missing");
    if (p.spikes > 0) {
        const size_t spikes = remove_spikes(m, p.spikes);
        out.spike_share = spikes / n;
        out.report.push_back("spikes: " + std::to_string(spikes) + " points (" +
                             percent(out.spike_share) + ") beyond " +
                             std::to_string(p.spikes).substr(0, 4) +
                             " robust sigmas of the 3x3 median removed");
    }
    const double share = out.missing_share + out.spike_share;
    if (share > p.max_missing)
        throw std::runtime_error(path + ": " + percent(out.missing_share) + " of the points are " +
                                 "missing and " + percent(out.spike_share) +
                                 " are spikes; surface.max_missing allows " +
                                 percent(p.max_missing));
    if (p.level != Levelling::none) {
        level(m, p.level == Levelling::plane ? 1 : p.level == Levelling::quadratic ? 2 : 3);
        out.report.push_back(std::string("levelled: least-squares ") + name_of(p.level) +
                             " removed");
    }
    if (share > 0) {
        fill(m);
        out.report.push_back("filled: " + percent(share) +
                             " of the points (missing and spikes) by harmonic interpolation");
    }
    if (std::abs(m.dx - m.dy) > 1e-3 * std::max(m.dx, m.dy))
        throw std::runtime_error(path + ": its cells are not square (spacing " +
                                 std::to_string(m.dx) + " along x, " + std::to_string(m.dy) +
                                 " along y): gonio's height fields need one spacing");
    if (p.high_pass > 0) {
        // Before the square cut, so that the whole map (not the cut's edges) holds the form.
        char text[240];
        if (p.high_pass < 2 * m.dx) {
            // A value the config gave that this map cannot take: a configuration error (exit 2).
            std::snprintf(
                text, sizeof text,
                "%g is under two samples of the map's spacing %g; allowed: 0 (none) or at "
                "least %g, in %s",
                p.high_pass, m.dx, 2 * m.dx,
                m.unit.empty() ? "the map's own length unit"
                               : "micrometres (whatever surface.input_unit)");
            throw ConfigError(path, -1, "surface.high_pass", text);
        }
        const double before = rms(m.z);
        gaussian_high_pass(m.z, m.nx, m.ny, m.dx, p.high_pass);
        std::snprintf(text, sizeof text,
                      "high-pass: Gaussian, cut-off %.4g (%.3g samples): RMS height %.4g -> %.4g",
                      p.high_pass, p.high_pass / m.dx, before, rms(m.z));
        out.report.push_back(text);
    }
    const int side = std::min(m.nx, m.ny);
    const int x0 = (m.nx - side) / 2, y0 = (m.ny - side) / 2;
    if (m.nx != m.ny)
        out.report.push_back("cropped: the centred " + std::to_string(side) + " x " +
                             std::to_string(side) + " square of the " + std::to_string(m.nx) +
                             " x " + std::to_string(m.ny) + " map");
    out.surface = HeightField(side, m.dx);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            out.surface.h[size_t(y) * side + x] = float(m.at(x0 + x, y0 + y));
    return out;
}

} // namespace gonio
