#include "heightfield/generate.h"

#include "core/check.h"
#include "core/math.h"
#include "core/parallel.h"
#include "core/quadrature.h"
#include "core/random.h"
#include "heightfield/constraint_geometry.h"
#include "heightfield/frankot_chellappa.h"
#include "heightfield/slope_marginal.h"
#include "heightfield/surface_generator.h"
#include "heightfield/surface_metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_sort.h>

namespace gonio {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

// Forward differences of h (per unit spacing: the generator works in grid units).
void differentiate(const std::vector<float>& h, int n, std::vector<float>& p,
                   std::vector<float>& q) {
    p.resize(h.size());
    q.resize(h.size());
    parallel_for(0, n, [&](int y) {
        const int y1 = (y + 1) % n;
        for (int x = 0; x < n; ++x) {
            const int x1 = (x + 1) % n;
            const float h0 = h[size_t(y) * n + x];
            p[size_t(y) * n + x] = h[size_t(y) * n + x1] - h0;
            q[size_t(y) * n + x] = h[size_t(y1) * n + x] - h0;
        }
    });
}

// Mean relative Schwarz error and the fraction of cells above the threshold, logged each
// iteration. `row_step` > 1 estimates them on every row_step-th row (a monitor, unbiased).
void log_schwarz(const float* p, const float* q, int n, double threshold, GenerationLog* log,
                 int row_step = 1) {
    if (!log) return;
    // Per-row sums, added in a fixed order: deterministic for any thread count.
    const int rows = (n + row_step - 1) / row_step;
    std::vector<double> row_sum(rows), row_above(rows);
    const float thr = float(threshold);
    parallel_for(0, rows, [&](int r) {
        const int y = r * row_step;
        const float* p0 = &p[size_t(y) * n];
        const float* p1 = &p[size_t((y + 1) % n) * n];
        const float* q0 = &q[size_t(y) * n];
        float s = 0;
        int above = 0;
        for (int x = 0; x < n; ++x) {
            const float a = p0[x], b = q0[x + 1 < n ? x + 1 : 0], c = p1[x], d = q0[x];
            const float sum = std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d);
            const float num = std::abs(a + b - c - d); // R19 Eq. 19
            s += sum > 0 ? num / sum : 0.0f;
            above += num > thr * sum;
        }
        row_sum[r] = s, row_above[r] = above;
    });
    double s = 0, a = 0;
    for (int r = 0; r < rows; ++r) s += row_sum[r], a += row_above[r];
    log->schwarz_mean.push_back(s / (double(rows) * n));
    log->above_threshold.push_back(a / (double(rows) * n));
}

// A uniform grid over slope space holding the unused pool values (R19 Step 2), with swap-removal.
class SlopeGrid {
  public:
    SlopeGrid(const std::vector<float>& pp, const std::vector<float>& pq,
              const std::vector<int>& free_ids)
        : pp_(pp), pq_(pq) {
        const size_t count = free_ids.size();
        g_ = std::max(1, int(std::sqrt(double(count) / 4.0)));
        lo_x_ = lo_y_ = 1e30f, hi_x_ = hi_y_ = -1e30f;
        for (int id : free_ids) {
            lo_x_ = std::min(lo_x_, pp[id]), hi_x_ = std::max(hi_x_, pp[id]);
            lo_y_ = std::min(lo_y_, pq[id]), hi_y_ = std::max(hi_y_, pq[id]);
        }
        wx_ = std::max(1e-12f, (hi_x_ - lo_x_) / g_), wy_ = std::max(1e-12f, (hi_y_ - lo_y_) / g_);
        start_.assign(size_t(g_) * g_ + 1, 0);
        for (int id : free_ids) ++start_[bin(pp[id], pq[id]) + 1];
        for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
        end_.assign(start_.begin(), start_.end() - 1);
        ids_.resize(count);
        for (int id : free_ids) ids_[end_[bin(pp[id], pq[id])]++] = id;
    }

    // The unused value nearest to (x, y), removed from the grid; -1 if none is left.
    int take_nearest(float x, float y) {
        const int cx = cell(x, lo_x_, wx_), cy = cell(y, lo_y_, wy_);
        int best = -1;
        size_t best_pos = 0, best_bin = 0;
        float best_d = 1e30f;
        int found_ring = -1;
        for (int r = 0; r < 2 * g_; ++r) {
            if (found_ring >= 0 && r > found_ring + 1) break; // one more ring may hold a closer one
            for (int by = cy - r; by <= cy + r; ++by) {
                if (by < 0 || by >= g_) continue;
                const bool edge_row = by == cy - r || by == cy + r;
                for (int bx = cx - r; bx <= cx + r; bx += edge_row ? 1 : 2 * r) {
                    if (bx >= 0 && bx < g_) {
                        const size_t b = size_t(by) * g_ + bx;
                        for (size_t k = start_[b]; k < end_[b]; ++k) {
                            const int id = ids_[k];
                            const float dx = pp_[id] - x, dy = pq_[id] - y, d = dx * dx + dy * dy;
                            if (d < best_d) best_d = d, best = id, best_pos = k, best_bin = b;
                        }
                    }
                    if (r == 0) break;
                }
            }
            if (best >= 0 && found_ring < 0) found_ring = r;
        }
        if (best >= 0) std::swap(ids_[best_pos], ids_[--end_[best_bin]]);
        return best;
    }

  private:
    static int cell(float v, float lo, float w) {
        return std::clamp(int((v - lo) / w), 0, std::numeric_limits<int>::max());
    }
    size_t bin(float x, float y) const {
        return size_t(std::min(cell(y, lo_y_, wy_), g_ - 1)) * g_ +
               std::min(cell(x, lo_x_, wx_), g_ - 1);
    }
    const std::vector<float>& pp_;
    const std::vector<float>& pq_;
    int g_;
    float lo_x_, lo_y_, hi_x_, hi_y_, wx_, wy_;
    std::vector<size_t> start_, end_;
    std::vector<int> ids_;
};

// One iteration of sliced optimal transport towards the target: take one direction e (golden
// angle sequence) in the stretched slope frame, where the target is isotropic, and move every
// gradient of the integrated surface along e so that the projections g.e take the target's 1-D
// marginal, matched by rank (the k-th smallest projection gets the k-th quantile). Over the
// directions this transports the whole 2-D distribution, radius and angle together. Ranks come
// from a fine histogram (2^12 bins, linear inside a bin): O(N), in two parallel passes.
struct SlicedWork {
    std::vector<std::uint32_t> in_bin;
    std::vector<std::vector<std::uint32_t>> part;
    std::vector<float> map;
    float lo = 0, hi = 0;   // histogram range for the next step
    float lo2 = 0, hi2 = 0; // and for its second direction (pairs)
};

// The marginal of the sample pool: a table of 2^17 + 1 quantiles that stays in cache (linear
// interpolation), and the whole sorted marginal for the two outermost intervals, where heavy tails
// (GGX) need every sample.
class Quantiles final : public MarginalQuantile {
  public:
    explicit Quantiles(std::vector<float> sorted) : all_(std::move(sorted)) {
        table_.resize(kSize + 1);
        for (int i = 0; i <= kSize; ++i) table_[i] = at_full(double(i) / kSize);
    }
    float operator()(double u) const override {
        const double t = u * kSize;
        const int i = int(t);
        if (i < 1 || i >= kSize - 1) return at_full(u);
        const float f = float(t - i);
        return table_[i] + f * (table_[i + 1] - table_[i]);
    }

  private:
    static constexpr int kSize = 1 << 17;
    float at_full(double u) const {
        return all_[std::min(all_.size() - 1, size_t(std::max(0.0, u) * double(all_.size())))];
    }
    std::vector<float> all_, table_;
};

// The same from sorted values that need not be kept: the table, and the values of the two
// outermost intervals only (for the pool's marginals along fixed directions, 64 of them).
class CompactQuantiles final : public MarginalQuantile {
  public:
    explicit CompactQuantiles(const std::vector<float>& sorted) : count_(sorted.size()) {
        table_.resize(kSize + 1);
        for (int i = 0; i <= kSize; ++i) table_[i] = at(sorted, double(i) / kSize);
        const size_t outer = std::min(count_, count_ / kSize + 2);
        low_.assign(sorted.begin(), sorted.begin() + long(outer));
        high_.assign(sorted.end() - long(outer), sorted.end());
    }
    float operator()(double u) const override {
        const double t = u * kSize;
        const int i = int(t);
        if (i < 1 || i >= kSize - 1) { // as Quantiles: every sample there
            const size_t k = std::min(count_ - 1, size_t(std::max(0.0, u) * double(count_)));
            if (k < low_.size()) return low_[k];
            return high_[std::min(high_.size() - 1, k - (count_ - high_.size()))];
        }
        const float f = float(t - i);
        return table_[i] + f * (table_[i + 1] - table_[i]);
    }

  private:
    static constexpr int kSize = 1 << 17;
    static float at(const std::vector<float>& sorted, double u) {
        return sorted[std::min(sorted.size() - 1,
                               size_t(std::max(0.0, u) * double(sorted.size())))];
    }
    size_t count_;
    std::vector<float> table_, low_, high_;
};

// One row of the sliced step's move: the gradient (forward differences of h) moves along e to the
// image of its projection under the piecewise-linear map. A plain loop that compilers vectorise;
// an AVX2 clone is chosen at run time where the processor has it (the result is the same).
__attribute__((target_clones("avx2", "default"))) void
move_row(const float* __restrict row, const float* __restrict next, int n, float ex, float ey,
         float lo, float inv_width, int bins, const float* __restrict map, float dx, float dy,
         float* __restrict po, float* __restrict qo) {
    auto move = [&](int x, float gx, float gy) {
        const float v = gx * ex + gy * ey;
        const float t = (v - lo) * inv_width;
        const int b = std::min(bins - 1, int(t));
        const float frac = std::min(1.0f, t - float(b));
        const float d = map[b] + frac * (map[b + 1] - map[b]) - v;
        po[x] = gx + dx * d;
        qo[x] = gy + dy * d;
    };
    for (int x = 0; x < n - 1; ++x) move(x, row[x + 1] - row[x], next[x] - row[x]);
    move(n - 1, row[0] - row[n - 1], next[n - 1] - row[n - 1]); // wraps
}

// The transport map at the bin edges: the target quantile of each edge's rank. Inside a bin values
// are taken as evenly spread, so the map is linear there.
void transport_map(const std::vector<std::vector<std::uint32_t>>& part, size_t cells,
                   const MarginalQuantile& quantile, std::vector<std::uint32_t>& in_bin,
                   std::vector<float>& map) {
    const size_t bins = part[0].size();
    in_bin.assign(bins, 0);
    for (const std::vector<std::uint32_t>& h : part)
        for (size_t b = 0; b < bins; ++b) in_bin[b] += h[b];
    map.resize(bins + 1);
    std::uint64_t below = 0;
    const double inv_cells = 1.0 / double(cells);
    for (size_t b = 0; b <= bins; ++b) {
        map[b] = quantile(double(below) * inv_cells);
        if (b < bins) below += in_bin[b];
    }
}

// The move along a second direction e2, in place: (p, q) moves along e2 to its projection's
// image under the second map (the first direction's projection does not change: e2 is orthogonal
// to it in the stretched frame).
__attribute__((target_clones("avx2", "default"))) void
move_in_place(float* __restrict p, float* __restrict q, size_t count, float ex, float ey, float lo,
              float inv_width, int bins, const float* __restrict map, float dx, float dy) {
    for (size_t k = 0; k < count; ++k) {
        const float v = p[k] * ex + q[k] * ey;
        const float t = (v - lo) * inv_width;
        const int b = std::min(bins - 1, int(t));
        const float frac = std::min(1.0f, t - float(b));
        const float d = map[b] + frac * (map[b + 1] - map[b]) - v;
        p[k] += dx * d;
        q[k] += dy * d;
    }
}

// One sliced step towards the target along psi, and with a `second` quantile function along
// psi + pi/2 as well (in the stretched frame: both marginals matched before the next integration).
void sliced_step(const float* h, int n, double ax, double ay, double psi,
                 const MarginalQuantile& quantile, const MarginalQuantile* second, SlicedWork& w,
                 float* p, float* q) {
    const size_t cells = size_t(n) * n;
    const float ex = float(std::cos(psi) / ax), ey = float(std::sin(psi) / ay);
    const int bins = 1 << 12, chunks = 4;
    w.part.resize(chunks);
    // Pass 1 (row blocks): gradient of h, its projection, the projections' range, and their
    // histogram over the previous iteration's range widened by 5 % (known before the pass).
    float lo = w.lo, hi = w.hi;
    float inv_width = float(bins) / std::max(hi - lo, 1e-30f);
    std::vector<float> block_lo(chunks), block_hi(chunks);
    auto bin_projections = [&] {
        parallel_for(0, chunks, [&](int c) {
            auto& hist = w.part[c];
            hist.assign(bins, 0);
            float blo = std::numeric_limits<float>::max(), bhi = -blo;
            for (int y = n * c / chunks; y < n * (c + 1) / chunks; ++y) {
                const float* row = &h[size_t(y) * n];
                const float* next = &h[size_t((y + 1) % n) * n];
                auto bin = [&](float v) {
                    blo = std::min(blo, v), bhi = std::max(bhi, v);
                    ++hist[std::clamp(int((v - lo) * inv_width), 0, bins - 1)];
                };
                for (int x = 0; x + 1 < n; ++x)
                    bin((row[x + 1] - row[x]) * ex + (next[x] - row[x]) * ey);
                bin((row[0] - row[n - 1]) * ex + (next[n - 1] - row[n - 1]) * ey); // wraps
            }
            block_lo[c] = blo, block_hi[c] = bhi;
        });
    };
    bin_projections();
    const float actual_lo = *std::min_element(block_lo.begin(), block_lo.end());
    const float actual_hi = *std::max_element(block_hi.begin(), block_hi.end());
    if (actual_lo < lo || actual_hi > hi) { // the guess was too narrow: histogram again
        lo = actual_lo, hi = actual_hi;
        inv_width = float(bins) / std::max(hi - lo, 1e-30f);
        bin_projections();
    }
    const float margin = 0.05f * (actual_hi - actual_lo);
    w.lo = actual_lo - margin, w.hi = actual_hi + margin;
    transport_map(w.part, cells, quantile, w.in_bin, w.map);
    // Pass 2: each gradient moves along e to its projection's image under the map.
    const float dx = float(std::cos(psi) * ax), dy = float(std::sin(psi) * ay);
    if (!second) {
        parallel_for_ranges<int>(0, n, 1, [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y < rows.end(); ++y)
                move_row(&h[size_t(y) * n], &h[size_t((y + 1) % n) * n], n, ex, ey, lo, inv_width,
                         bins, w.map.data(), dx, dy, &p[size_t(y) * n], &q[size_t(y) * n]);
        });
        return;
    }
    // With a pair, pass 2 also bins the moved gradients' projections on e2 (the rows just
    // written, in cache), over the previous pair's range; a third pass moves them along e2.
    const double psi2 = psi + kPi / 2;
    const float ex2 = float(std::cos(psi2) / ax), ey2 = float(std::sin(psi2) / ay);
    float lo2 = w.lo2, hi2 = w.hi2;
    float inv_width2 = float(bins) / std::max(hi2 - lo2, 1e-30f);
    auto bin_rows = [&](int c) {
        auto& hist = w.part[c];
        hist.assign(bins, 0);
        float blo = std::numeric_limits<float>::max(), bhi = -blo;
        for (size_t k = size_t(n) * size_t(n * c / chunks);
             k < size_t(n) * size_t(n * (c + 1) / chunks); ++k) {
            const float v = p[k] * ex2 + q[k] * ey2;
            blo = std::min(blo, v), bhi = std::max(bhi, v);
            ++hist[std::clamp(int((v - lo2) * inv_width2), 0, bins - 1)];
        }
        block_lo[c] = blo, block_hi[c] = bhi;
    };
    parallel_for(0, chunks, [&](int c) {
        for (int y = n * c / chunks; y < n * (c + 1) / chunks; ++y)
            move_row(&h[size_t(y) * n], &h[size_t((y + 1) % n) * n], n, ex, ey, lo, inv_width, bins,
                     w.map.data(), dx, dy, &p[size_t(y) * n], &q[size_t(y) * n]);
        bin_rows(c);
    });
    const float lo2_actual = *std::min_element(block_lo.begin(), block_lo.end());
    const float hi2_actual = *std::max_element(block_hi.begin(), block_hi.end());
    if (lo2_actual < lo2 || hi2_actual > hi2) {
        lo2 = lo2_actual, hi2 = hi2_actual;
        inv_width2 = float(bins) / std::max(hi2 - lo2, 1e-30f);
        parallel_for(0, chunks, bin_rows);
    }
    const float margin2 = 0.05f * (hi2_actual - lo2_actual);
    w.lo2 = lo2_actual - margin2, w.hi2 = hi2_actual + margin2;
    transport_map(w.part, cells, *second, w.in_bin, w.map);
    const float dx2 = float(std::cos(psi2) * ax), dy2 = float(std::sin(psi2) * ay);
    parallel_for(0, chunks, [&](int c) {
        const size_t first = size_t(n) * size_t(n * c / chunks);
        const size_t last = size_t(n) * size_t(n * (c + 1) / chunks);
        move_in_place(p + first, q + first, last - first, ex2, ey2, lo2, inv_width2, bins,
                      w.map.data(), dx2, dy2);
    });
}

} // namespace

double schwarz_error(const float* p, const float* q, int n, int x, int y) {
    const int x1 = (x + 1) % n, y1 = (y + 1) % n;
    const double a = p[size_t(y) * n + x], b = q[size_t(y) * n + x1];
    const double c = p[size_t(y1) * n + x], d = q[size_t(y) * n + x];
    const double sum = std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d);
    return sum > 0 ? std::abs(a + b - c - d) / sum : 0.0; // R19 Eq. 19, relative
}

void sample_slope_pool(const Ndf& ndf, int n, std::uint64_t seed, std::vector<float>& p,
                       std::vector<float>& q) {
    p.resize(size_t(n) * n);
    q.resize(size_t(n) * n);
    sample_slope_pool(ndf, n, seed, p.data(), q.data());
}

void sample_slope_pool(const Ndf& ndf, int n, std::uint64_t seed, float* p, float* q) {
    parallel_for(0, n, [&](int y) {
        Rng rng{seed, 0x706f6f6cull /* "pool" */, std::uint64_t(y)};
        for (int x = 0; x < n; ++x) {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            const Vec3 m = ndf.sample_m(u1, u2);
            const double z = std::max(m.z, 1e-6); // keep slopes finite at grazing normals
            p[size_t(y) * n + x] = float(-m.x / z);
            q[size_t(y) * n + x] = float(-m.y / z);
        }
    });
}

namespace {
// R19 Algorithm 1, or its sliced-matching variant, on forward-difference Frankot-Chellappa.
HeightField generate_matching(const Ndf& ndf, const SurfaceSpec& spec, int threads,
                              GenerationLog* lg, const ProgressFn& progress, bool sliced) {
    const int n = spec.size;
    FrankotChellappa fc(n, threads);

    const size_t cells = size_t(n) * n;
    // The gradient field is written straight into the integrator's FFTW buffers.
    float* p = fc.gradient_x();
    float* q = fc.gradient_y();
    const bool constrained = spec.constraint != Constraint::none;
    double ax = 1, ay = 1;
    const bool shape_invariant = ndf.slope_stretch(ax, ay);
    // Matching the NDF's exact marginal needs no pool but the start: drawn straight into the
    // gradient buffers (the same values the pool holds).
    const bool exact = sliced && spec.target == MatchTarget::quantiles && shape_invariant;
    std::vector<float> pool_p, pool_q;
    if (exact && !constrained)
        sample_slope_pool(ndf, n, spec.seed, p, q);
    else
        sample_slope_pool(ndf, n, spec.seed, pool_p, pool_q);
    HeightField geometry;
    if (exact && !constrained) {
        // started above
    } else if (constrained) {
        // R19 5.3.2: the gradient field starts from a geometry; the pool still follows D.
        geometry = constraint_geometry(spec.constraint, n, spec.lattice, spec.relief);
        // Flat regions would give ties that rank matching can never separate: dither the
        // geometry by a thousandth of a sample step (deterministic for the seed).
        for (int y = 0; y < n; ++y) {
            Rng rng{spec.seed, 0x646974686572ull /* "dither" */, std::uint64_t(y)};
            for (int x = 0; x < n; ++x)
                geometry.h[size_t(y) * n + x] += float(1e-3 * (rng.uniform() - 0.5));
        }
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                p[size_t(y) * n + x] = float(geometry.p(x, y));
                q[size_t(y) * n + x] = float(geometry.q(x, y));
            }
    } else {
        std::copy(pool_p.begin(), pool_p.end(), p);
        std::copy(pool_q.begin(), pool_q.end(), q);
    }
    auto integrate = [&]() {
        const auto t = Clock::now();
        fc.integrate();
        lg->integrate_seconds += since(t);
    };
    log_schwarz(p, q, n, spec.threshold, lg);
    integrate();

    std::unique_ptr<MarginalQuantile> quantile;
    SlicedWork work;
    std::vector<int> assigned;
    std::vector<float> h, gp, gq;
    // A shape-invariant target is isotropic once stretched: one projected marginal for every
    // direction (the exact one, or the pool's sorted once). Any other (blends, mixtures, tables)
    // is matched in plain slope space to the pool's projections along each direction: along 64
    // fixed directions k pi / 64, sorted once, taken in orthogonal pairs (quantiles), or along each
    // iteration's golden-angle direction, sorted every iteration (pool).
    const bool per_direction = sliced && !shape_invariant;
    const bool fixed_directions = per_direction && spec.target == MatchTarget::quantiles;
    constexpr int kDirections = 64;
    std::vector<std::unique_ptr<MarginalQuantile>> fixed;
    auto direction_quantiles = [&](double psi) {
        std::vector<float> proj(cells);
        const float c = float(std::cos(psi)), sn = float(std::sin(psi));
        parallel_for(size_t(0), cells, [&](size_t k) { proj[k] = pool_p[k] * c + pool_q[k] * sn; });
        tbb::parallel_sort(proj.begin(), proj.end());
        return std::make_unique<Quantiles>(std::move(proj));
    };
    if (fixed_directions) {
        std::vector<float> proj(cells);
        for (int k = 0; k < kDirections; ++k) {
            const double psi = k * kPi / kDirections;
            const float c = float(std::cos(psi)), sn = float(std::sin(psi));
            parallel_for(size_t(0), cells,
                         [&](size_t i) { proj[i] = pool_p[i] * c + pool_q[i] * sn; });
            tbb::parallel_sort(proj.begin(), proj.end());
            fixed.push_back(std::make_unique<CompactQuantiles>(proj));
        }
    } else if (per_direction) {
        // quantile is made per iteration
    } else if (exact) {
        quantile = std::make_unique<TargetQuantiles>(ndf, cells);
        if (ax != ay) fc.set_metric(1 / (ax * ax), 1 / (ay * ay)); // as below
    } else if (sliced) {
        // The target's 1-D marginal in the stretched frame, where it is isotropic: both stretched
        // components of the pool sample it, 2 n^2 values.
        std::vector<float> marginal;
        marginal.reserve(2 * cells);
        for (size_t k = 0; k < cells; ++k)
            marginal.push_back(float(pool_p[k] / ax)), marginal.push_back(float(pool_q[k] / ay));
        tbb::parallel_sort(marginal.begin(), marginal.end());
        quantile = std::make_unique<Quantiles>(std::move(marginal));
        // Project onto integrable fields in the same stretched metric the transport works in:
        // with the plain metric, a strongly anisotropic target (alpha_y / alpha_x ~ 7) leaks the
        // wide axis's residual into the narrow one, which the stretch amplifies, and the
        // iteration diverges.
        if (ax != ay) fc.set_metric(1 / (ax * ax), 1 / (ay * ay));
    } else {
        assigned.resize(cells);
        for (size_t k = 0; k < cells; ++k) assigned[k] = int(k);
        if (constrained) {
            // Each cell takes the unused pool value nearest to the geometry's gradient.
            SlopeGrid grid(pool_p, pool_q, assigned);
            for (size_t c = 0; c < cells; ++c) {
                const int id = grid.take_nearest(p[c], q[c]);
                assigned[c] = id;
                p[c] = pool_p[id];
                q[c] = pool_q[id];
            }
            integrate();
        }
    }

    double best_distance = 1e30;
    int stale = 0;
    for (int it = 0; it < spec.iterations; ++it) {
        const auto t = Clock::now();
        if (sliced) {
            if (fixed_directions) {
                // The 32 orthogonal pairs in the order 13 k mod 32 (consecutive pairs ~37 deg
                // apart; all of them every 32 iterations).
                const int k = (it * 13) % (kDirections / 2);
                sliced_step(fc.heights(), n, ax, ay, k * kPi / kDirections, *fixed[size_t(k)],
                            fixed[size_t(k + kDirections / 2)].get(), work, p, q);
            } else {
                const double psi = it * 2.39996322972865332; // golden angle
                if (per_direction) quantile = direction_quantiles(psi);
                sliced_step(fc.heights(), n, ax, ay, psi, *quantile,
                            exact ? quantile.get() : nullptr, work, p, q);
            }
        } else {
            h.assign(fc.heights(), fc.heights() + cells);
            differentiate(h, n, gp, gq); // the integrated surface's gradient, grad h+
            // R19 Algorithm 1: cells whose assigned gradient breaks Schwarz's theorem (Eq. 19) give
            // their pool values back; each then takes the unused pool value nearest to grad h+.
            std::vector<int> bad;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    if (schwarz_error(p, q, n, x, y) > spec.threshold) bad.push_back(y * n + x);
            // Greedy matching in row-major order would leave the last rows the worst leftovers
            // (a visible band at the wrap); a seeded random order spreads them evenly.
            Rng order{spec.seed, 0x6f72646572ull /* "order" */, std::uint64_t(it)};
            for (size_t k = bad.size(); k > 1; --k)
                std::swap(bad[k - 1], bad[size_t(order.uniform() * double(k))]);
            std::vector<int> free_ids;
            free_ids.reserve(bad.size());
            for (int c : bad) free_ids.push_back(assigned[c]);
            if (!bad.empty()) {
                SlopeGrid grid(pool_p, pool_q, free_ids);
                for (int c : bad) {
                    const int id = grid.take_nearest(gp[c], gq[c]);
                    assigned[c] = id;
                    p[c] = pool_p[id];
                    q[c] = pool_q[id];
                }
            }
        }
        lg->match_seconds += since(t);
        // The last iteration is measured on every row; the others on every 8th (a monitor).
        const auto ts = Clock::now();
        log_schwarz(p, q, n, spec.threshold, lg, it + 1 == spec.iterations ? 1 : 8);
        lg->schwarz_seconds += since(ts);
        integrate();
        lg->iterations = it + 1;
        if (progress) progress(it + 1, spec.iterations);
        if (spec.stop_when_converged && (it + 1) % 10 == 0) {
            HeightField probe(n, 1.0);
            probe.h.assign(fc.heights(), fc.heights() + cells);
            const double d = ndf_distance(probe, ndf, 512);
            lg->ndf_distance.push_back(d);
            if (d < best_distance * (1 - 1e-3))
                best_distance = d, stale = 0;
            else if (++stale >= 3) {
                lg->converged_early = true;
                break;
            }
        }
    }
    HeightField out(n, 1.0); // in grid units: generate_surface scales it
    out.h.assign(fc.heights(), fc.heights() + cells);
    lg->fft_seconds = fc.fft_seconds();
    return out;
}

const Key kIterations =
    Key::integer("iterations", {0, 1e6}, "iterations of the generator (R19: 500)").fallback(500.0);
const Key kThreshold =
    Key::number("threshold", {0, 1, true, false}, "Schwarz threshold of Algorithm 1 (R19: 0.02)")
        .fallback(0.02)
        .cited("R19 Eq. 19");
const Key kStop = Key::boolean("stop_when_converged",
                               "stop when the NDF distance (checked every 10 iterations) stops "
                               "improving")
                      .fallback(false);
const Key kConstraint = Key::string("constraint", enum_names<Constraint>(),
                                    "constrained generation: start from a lattice")
                            .fallback("none")
                            .cited("R19 section 5.3.2");
const Key kLattice = Key::integer("lattice", {1, 8192}, "domes/holes: features per side")
                         .fallback(8.0)
                         .noting("at most size/2");
const Key kRelief =
    Key::number("relief", {1e-6, 100}, "domes/holes: height over radius").fallback(0.5);
const std::vector<Key> kMatchingKeys{kIterations, kThreshold, kStop,
                                     kConstraint, kLattice,   kRelief};
const Key kTarget = Key::string("target", enum_names<MatchTarget>(),
                                "what each direction's projections are matched to: the NDF's "
                                "exact marginal, two orthogonal directions per iteration "
                                "(quantiles), or the sample pool's, one (pool: the surfaces of "
                                "gonio before issue 35)")
                        .fallback("quantiles")
                        .noting("quantiles for shape-invariant NDFs; the others use the pool's "
                                "marginal per direction either way");
// Matching the exact marginal two directions at a time converges in a fifth of the iterations
// (docs/performance.md: surface generation).
constexpr int kQuantileIterations = 100;
const Key kSlicedIterations = Key::integer("iterations", {0, 1e6}, "iterations of the generator")
                                  .note_default("100; 500 with `target = \"pool\"` (R19)");
const std::vector<Key> kSlicedKeys{kSlicedIterations, kThreshold, kStop,  kConstraint,
                                   kLattice,          kRelief,    kTarget};

// The settings both matching generators share (iterations are read by each).
void read_matching(TableReader& r, const Ndf&, SurfaceSpec& s) {
    s.threshold = r.number(kThreshold);
    s.stop_when_converged = r.boolean(kStop);
    s.constraint = enum_named<Constraint>(r.string(kConstraint));
    if (s.constraint != Constraint::none) {
        s.lattice = static_cast<int>(
            r.integer(kLattice.name, {1, double(s.size / 2)}, (long long)*kLattice.number_default));
        s.relief = r.number(kRelief);
    }
}
void read_algorithm1(TableReader& r, const Ndf& ndf, SurfaceSpec& s) {
    s.iterations = static_cast<int>(r.integer(kIterations));
    read_matching(r, ndf, s);
}
void read_sliced(TableReader& r, const Ndf& ndf, SurfaceSpec& s) {
    s.target = enum_named<MatchTarget>(r.string(kTarget));
    s.iterations =
        static_cast<int>(r.integer(kSlicedIterations.name, kSlicedIterations.range,
                                   s.target == MatchTarget::pool ? 500 : kQuantileIterations));
    read_matching(r, ndf, s);
}
// The common identity already holds the matching settings (iterations, threshold, ...).
void no_more_identity(const SurfaceSpec&, std::ostream&) {}
// The target, where it is not the pool (so that the pool's surfaces keep their identities).
void sliced_identity(const SurfaceSpec& s, std::ostream& out) {
    if (s.target != MatchTarget::pool) out << "|target=" << name_of(s.target);
}
bool follows_unless_constrained(const SurfaceSpec& s) {
    return s.constraint == Constraint::none;
}
} // namespace

const SurfaceGenerator& sliced_matching_generator() {
    static const SurfaceGenerator g{
        "sliced-matching",
        "iterative Frankot-Chellappa with sliced optimal-transport matching (the default)",
        &kSlicedKeys,
        read_sliced,
        [](const Ndf& ndf, const SurfaceSpec& s, int threads, GenerationLog* log,
           const ProgressFn& progress) {
            return generate_matching(ndf, s, threads, log, progress, true);
        },
        sliced_identity,
        follows_unless_constrained};
    return g;
}

const SurfaceGenerator& algorithm1_generator() {
    static const SurfaceGenerator g{
        "algorithm1",
        "iterative Frankot-Chellappa with Schwarz-error rematching [R19 Algorithm 1]",
        &kMatchingKeys,
        read_algorithm1,
        [](const Ndf& ndf, const SurfaceSpec& s, int threads, GenerationLog* log,
           const ProgressFn& progress) {
            return generate_matching(ndf, s, threads, log, progress, false);
        },
        no_more_identity,
        follows_unless_constrained};
    return g;
}

} // namespace gonio
