#include "gonio/trace/heightfield_traversal.h"

#include "core/check.h"
#include "core/parallel.h"
#include "gonio/trace/heightfield_cells.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

// The edge functions must be exactly antisymmetric (see the header): no fused multiply-add.
#pragma GCC optimize("fp-contract=off")

namespace gonio {

using namespace walk_cells;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// A vertex in the ray's sheared frame (Woop et al. 2013, Sec. 3): the ray runs along +z' from the
// origin, x' and y' are where the vertex lies across it, z' is its distance along it times 1/d_kz.
struct Projected {
    double x, y, z;
};
[[gnu::always_inline]] inline double edge(const Projected& p, const Projected& q) {
    return p.x * q.y - p.y * q.x;
}

// A clear distance rounded down to float (a start table's entry must not overshoot).
float float_below(double clear) {
    float c = float(clear);
    if (double(c) > clear) c = std::nextafter(c, 0.0f);
    return c;
}
} // namespace

HeightfieldTraversal::HeightfieldTraversal(const HeightField& s)
    : n_(s.n), avx2_(avx2_supported()), lanes_(native_lanes()) {
    if (const char* e = std::getenv("GONIO_HEIGHTFIELD_LANES"); e && e[0] == '0') lanes_ = 0;
    GONIO_CHECK(s.n >= 2); // Scene refuses smaller surfaces
    const int n = n_, v = n + 1;
    inv_spacing_ = 1.0 / s.spacing;
    spacing_ = s.spacing;
    line_.resize(size_t(v));
    for (int i = 0; i < v; ++i) line_[size_t(i)] = double(float(i * s.spacing));
    h_.resize(size_t(v) * size_t(v));
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int y = 0; y < v; ++y)
        for (int x = 0; x < v; ++x) {
            const float z = s.at(x, y);
            h_[size_t(y) * size_t(v) + size_t(x)] = z;
            lo = std::min(lo, z), hi = std::max(hi, z);
        }
    const double extent = std::max({period(), std::abs(double(lo)), std::abs(double(hi))});
    // A float ulp of the coordinates: far above the double rounding of the walk's crossing
    // times, far below any height difference that matters.
    pad_ = extent * std::numeric_limits<float>::epsilon();
    relief_ = double(hi) - double(lo);
    corner_tolerance_ = extent * 1e-10;

    // Level 1 from the vertices, then each level from the one below; a node at level l covers
    // cells [i 2^l, min((i + 1) 2^l, n)) and so the vertices up to the far edge.
    std::vector<std::vector<float>> levels(1); // level 0: the cells themselves
    level_width_.push_back(n);
    for (int l = 1;; ++l) {
        const int w = (n + (1 << l) - 1) >> l;
        std::vector<float> node(2 * size_t(w) * size_t(w));
        if (l == 1) {
            for (int j = 0; j < w; ++j)
                for (int i = 0; i < w; ++i) {
                    float a = std::numeric_limits<float>::max(), b = -a;
                    for (int y = 2 * j; y <= std::min(2 * j + 2, n); ++y)
                        for (int x = 2 * i; x <= std::min(2 * i + 2, n); ++x) {
                            const float z = h_[size_t(y) * size_t(v) + size_t(x)];
                            a = std::min(a, z), b = std::max(b, z);
                        }
                    node[2 * (size_t(j) * w + i)] = a, node[2 * (size_t(j) * w + i) + 1] = b;
                }
        } else {
            const std::vector<float>& below = levels.back();
            const int wb = level_width_.back();
            for (int j = 0; j < w; ++j)
                for (int i = 0; i < w; ++i) {
                    float a = std::numeric_limits<float>::max(), b = -a;
                    for (int y = 2 * j; y < std::min(2 * j + 2, wb); ++y)
                        for (int x = 2 * i; x < std::min(2 * i + 2, wb); ++x) {
                            a = std::min(a, below[2 * (size_t(y) * wb + x)]);
                            b = std::max(b, below[2 * (size_t(y) * wb + x) + 1]);
                        }
                    node[2 * (size_t(j) * w + i)] = a, node[2 * (size_t(j) * w + i) + 1] = b;
                }
        }
        levels.push_back(std::move(node));
        level_width_.push_back(w);
        if (w == 1) {
            top_ = l;
            break;
        }
    }
    for (const std::vector<float>& l : levels) {
        level_offset_.push_back(pyramid_.size());
        pyramid_.insert(pyramid_.end(), l.begin(), l.end());
    }

    // The dilated blocks: each block's vertices widened by r cells on every side (periodic).
    for (int k = 0; k < kJumps; ++k) {
        const int b = 1 << kJumpShift[k];
        if (n < 4 * b) break;
        const int w = (n + b - 1) / b;
        std::vector<float> m(2 * size_t(w) * size_t(w));
        // Per vertex row, the running (min, max) over x in [x0 - b, x1 + b] for each block.
        std::vector<float> rows(2 * size_t(w) * size_t(n));
        for (int y = 0; y < n; ++y)
            for (int i = 0; i < w; ++i) {
                float a = std::numeric_limits<float>::max(), c = -a;
                for (int x = i * b - b; x <= std::min((i + 1) * b, n) + b; ++x) {
                    const float z = h_[size_t(y) * size_t(v) + size_t(((x % n) + n) % n)];
                    a = std::min(a, z), c = std::max(c, z);
                }
                rows[2 * (size_t(y) * w + i)] = a, rows[2 * (size_t(y) * w + i) + 1] = c;
            }
        for (int j = 0; j < w; ++j)
            for (int i = 0; i < w; ++i) {
                float a = std::numeric_limits<float>::max(), c = -a;
                for (int y = j * b - b; y <= std::min((j + 1) * b, n) + b; ++y) {
                    const size_t row = size_t(((y % n) + n) % n);
                    a = std::min(a, rows[2 * (row * w + i)]);
                    c = std::max(c, rows[2 * (row * w + i) + 1]);
                }
                m[2 * (size_t(j) * w + i)] = a, m[2 * (size_t(j) * w + i) + 1] = c;
            }
        dilated_[k] = std::move(m);
        dilated_width_[k] = w;
        jumps_ = k + 1;
    }

    // The beam windows: the maximum along x over each row, then along y over those (periodic),
    // at every other cell.
    {
        const int span = (1 << kBeamShift) + 6; // vertices i - 1 .. i + b + 4
        const int w = (n + 1) / 2;
        std::vector<int> wrapped(size_t(n) + size_t(span)); // (i - 1) mod n, i in [0, n + span)
        for (int i = 0; i < n + span; ++i) wrapped[size_t(i)] = (i - 1 + n) % n;
        std::vector<float> rows(size_t(n) * size_t(w));
        beam_window_.resize(size_t(w) * size_t(w));
        parallel_for(0, n, [&](int y) {
            const float* row = h_.data() + size_t(y) * size_t(v);
            for (int i = 0; i < w; ++i) {
                float c = row[wrapped[size_t(2 * i)]];
                for (int k = 1; k < span; ++k) c = std::max(c, row[wrapped[size_t(2 * i + k)]]);
                rows[size_t(y) * size_t(w) + size_t(i)] = c;
            }
        });
        parallel_for(0, w, [&](int j) {
            float* out = beam_window_.data() + size_t(j) * size_t(w);
            const float* first = rows.data() + size_t(wrapped[size_t(2 * j)]) * size_t(w);
            std::copy(first, first + w, out);
            for (int k = 1; k < span; ++k) {
                const float* r = rows.data() + size_t(wrapped[size_t(2 * j + k)]) * size_t(w);
                for (int i = 0; i < w; ++i) out[i] = std::max(out[i], r[i]);
            }
        });
    }
}

BeamEntry HeightfieldTraversal::beam_entry(const Vec3& d, double z_start, long long rays) const {
    BeamEntry e;
    e.d = d, e.z_start = z_start, e.shift = kBeamShift;
    const double speed_xy = std::max(std::abs(d.x), std::abs(d.y));
    if (!(d.z < 0)) return e;
    const int b = 1 << kBeamShift, w = (n_ + b - 1) >> kBeamShift;
    // A block costs about what 1.5 rays save (1024^2, theta_i 60 deg: 520 instructions against
    // 340 per beam ray, callgrind).
    if (rays < 2 * (long long)w * w) return e;
    // The cells a ray crosses within the relief; none for a ray that would cross it over more
    // than 2^10 periods (within ~10^-4 rad of the horizon, beyond beam.theta_i's range), whose
    // leap would cross as many walls.
    const double slab_cells = relief_ * inv_spacing_ * speed_xy / -d.z;
    if (!(slab_cells <= 1024.0 * n_)) return e;
    e.width = w;
    e.t.resize(size_t(w) * size_t(w));
    // Rays that cross many cells within the relief (grazing ones) march far: a march of their
    // own.
    if (slab_cells > 128) {
        // Along a grid axis, each ray's own row beats any block of them (1024^2, theta_i
        // 89.9 deg: 45 pyramid nodes and 13 cells a beam ray from the block's distance before).
        grazing_rows(e);
        if (e.row_axis >= 0) {
            e.width = 0, e.t.clear();
            return e;
        }
        grazing_entry(e);
        return e;
    }
    // Steps of just under one cell of travel, up to a quarter of the patch (so that the walk's
    // leap there crosses at most one side wall per axis).
    const double step = speed_xy > 0 ? 0.99 * spacing_ / speed_xy : kInf;
    const int steps = speed_xy > 0 ? std::max(1, n_ / 4) : 1;
    const int n = n_;
    const size_t window = size_t(n + 1) / 2; // beam_window_ per row
    const double inv_dz = 1.0 / d.z;
    // The cell of coordinate v (v within a quarter period of the patch), periodic; truncation
    // with a correction is the floor (std::floor is a library call without SSE4.1).
    auto cell = [n, inv = inv_spacing_](double v) {
        const double g = v * inv;
        int i = int(g);
        i -= int(g < double(i));
        return i < 0 ? i + n : i >= n ? i - n : i;
    };
    parallel_for(0, w, [&](int bj) {
        for (int bi = 0; bi < w; ++bi) {
            const double x0 = bi * b * spacing_, y0 = bj * b * spacing_;
            double clear = 0;
            for (int k = 0; k < steps; ++k) {
                const double ta = k == 0 ? 0.0 : k * step, tb = (k + 1) * step;
                // The cells the block's rays cross in [ta, tb] start at (i, j) (a cell to spare).
                const double xa = speed_xy > 0 ? x0 + std::min(ta * d.x, tb * d.x) : x0;
                const double ya = speed_xy > 0 ? y0 + std::min(ta * d.y, tb * d.y) : y0;
                const double bound =
                    double(beam_window_[size_t(cell(ya) >> 1) * window + size_t(cell(xa) >> 1)]) +
                    2 * pad_;
                // Clear while the ray's height (falling) stays above the bound.
                const double t_reach = (bound - z_start) * inv_dz;
                if (!(t_reach > tb)) {
                    clear = std::max(ta, t_reach);
                    break;
                }
                clear = tb;
            }
            e.t[size_t(bj) * size_t(w) + size_t(bi)] = float_below(clear);
        }
    });
    return e;
}

void HeightfieldTraversal::grazing_entry(BeamEntry& e) const {
    // Per block of origins, steps along the ray that double while the rectangle the block's rays
    // sweep over the step is clear of the surface and halve where it is not, down to a cell of
    // travel: each rectangle bounded by the few pyramid nodes of the level that cover it. The
    // rays may travel several periods before they come down to the surface: the walk's leap
    // crosses the walls.
    const Vec3 d = e.d;
    const int n = n_, b = 1 << e.shift;
    const double speed_xy = std::max(std::abs(d.x), std::abs(d.y));
    const double unit = spacing_ / speed_xy; // one cell of travel
    const double inv_dz = 1.0 / d.z;
    const float global_max = pyramid_[level_offset_[size_t(top_)] + 1];
    const double fine = 0.99 * unit; // a window's step (see beam_entry)
    const size_t window = size_t(n + 1) / 2;
    // The cell of coordinate v, periodic.
    auto cell = [n, inv = inv_spacing_](double v) {
        long long i = (long long)std::floor(v * inv);
        i %= n;
        return int(i < 0 ? i + n : i);
    };
    // The largest vertex height of the cells in [i0, i0 + wx) x [j0, j0 + wy) (periodic; the
    // indices may lie outside [0, n)).
    auto rectangle_max = [&](long long i0, long long j0, long long wx, long long wy) {
        const long long wide = std::max(wx, wy);
        if (wide >= n) return global_max;
        int level = 1;
        while ((1LL << level) < wide) ++level;
        if (level >= top_) return global_max;
        const int width = level_width_[size_t(level)];
        const float* nodes = pyramid_.data() + level_offset_[size_t(level)];
        // The nodes that hold the cells [c0, c0 + count) along one axis (at most 3: every node
        // but the last holds 2^level cells).
        auto covering = [&](long long c0, long long count, int out[3]) {
            long long c = ((c0 % n) + n) % n;
            int k = 0;
            while (count > 0) {
                const int node = int(c >> level);
                out[k++] = node;
                const long long end = std::min<long long>((long long)(node + 1) << level, n);
                count -= end - c;
                c = end == n ? 0 : end;
            }
            return k;
        };
        int xs[3], ys[3];
        const int kx = covering(i0, wx, xs), ky = covering(j0, wy, ys);
        float m = -std::numeric_limits<float>::max();
        for (int y = 0; y < ky; ++y)
            for (int x = 0; x < kx; ++x)
                m = std::max(m, nodes[2 * (size_t(ys[y]) * size_t(width) + size_t(xs[x])) + 1]);
        return m;
    };
    parallel_for(0, e.width, [&](int bj) {
        for (int bi = 0; bi < e.width; ++bi) {
            // The block's origins lie in cells [bi b, bi b + b) x [bj b, bj b + b).
            const double x0 = double(bi * b), y0 = double(bj * b); // in cells
            // The cells its rays cross over [ta, tb], a cell to spare on every side.
            auto bound = [&](double ta, double tb) {
                const double xa = std::min(ta * d.x, tb * d.x) * inv_spacing_;
                const double xb = std::max(ta * d.x, tb * d.x) * inv_spacing_;
                const double ya = std::min(ta * d.y, tb * d.y) * inv_spacing_;
                const double yb = std::max(ta * d.y, tb * d.y) * inv_spacing_;
                const long long i0 = (long long)std::floor(x0 + xa) - 1;
                const long long i1 = (long long)std::floor(x0 + b + xb) + 1;
                const long long j0 = (long long)std::floor(y0 + ya) - 1;
                const long long j1 = (long long)std::floor(y0 + b + yb) + 1;
                return double(rectangle_max(i0, j0, i1 - i0 + 1, j1 - j0 + 1)) + 2 * pad_;
            };
            double t = 0, step = unit, clear = 0;
            for (;;) {
                const double tb = t + step;
                // Clear while the ray's height (falling) stays above the bound.
                const double t_reach = (bound(t, tb) - e.z_start) * inv_dz;
                if (t_reach > tb) {
                    t = tb, step *= 2;
                    continue;
                }
                if (step > unit) {
                    step = std::max(unit, 0.5 * step);
                    continue;
                }
                clear = std::max(t, t_reach);
                break;
            }
            // Then steps of just under a cell with the tighter beam windows (as for steeper
            // beams), while they stay clear.
            for (int k = 0; k < kGrazingWindowSteps; ++k) {
                const double tb = clear + fine;
                const double xa = (x0 * spacing_) + std::min(clear * d.x, tb * d.x);
                const double ya = (y0 * spacing_) + std::min(clear * d.y, tb * d.y);
                const double w_bound =
                    double(beam_window_[size_t(cell(ya) >> 1) * window + size_t(cell(xa) >> 1)]) +
                    2 * pad_;
                const double t_reach = (w_bound - e.z_start) * inv_dz;
                if (!(t_reach > tb)) {
                    clear = std::max(clear, t_reach);
                    break;
                }
                clear = tb;
            }
            e.t[size_t(bj) * size_t(e.width) + size_t(bi)] = float_below(clear);
        }
    });
}

void HeightfieldTraversal::grazing_rows(BeamEntry& e) const {
    const Vec3 d = e.d;
    const int axis = std::abs(d.x) >= std::abs(d.y) ? 0 : 1;
    const double along = axis == 0 ? d.x : d.y, across = axis == 0 ? d.y : d.x;
    // The cells a ray crosses within the relief, and how far across the beam it drifts meanwhile
    // (a quarter of a cell: most rays stay within their row).
    const double cells = relief_ * inv_spacing_ * std::abs(along) / -d.z;
    if (!(std::abs(across) / std::abs(along) * cells < 0.25)) return;
    const int n = n_;
    const size_t v = size_t(n) + 1;
    const bool forward = along > 0;
    // The height of vertex (i along the beam, j across it).
    auto height = [&](int i, int j) {
        return axis == 0 ? h_[size_t(j) * v + size_t(i)] : h_[size_t(i) * v + size_t(j)];
    };
    e.row_fall = spacing_ / std::abs(along) * -d.z;
    e.row_offset.assign(1, 0);
    e.row_width.assign(1, n);
    size_t floats = size_t(n);
    for (int w = n; w > 1;) {
        w = (w + BeamEntry::kRowFan - 1) / BeamEntry::kRowFan;
        e.row_offset.push_back(floats);
        e.row_width.push_back(w);
        floats += size_t(w);
    }
    e.row_stride = floats;
    e.row_reach.resize(size_t(n) * floats);
    parallel_for(0, n, [&](int j) {
        float* reach = e.row_reach.data() + size_t(j) * floats;
        // Level 0, in the order of travel: the cell's highest corner, raised by the rays' fall
        // from the copy's start to the cell's far side (rounded up to float).
        for (int k = 0; k < n; ++k) {
            const int i = forward ? k : n - 1 - k;
            const float top =
                std::max({height(i, j), height(i + 1, j), height(i, j + 1), height(i + 1, j + 1)});
            const double g = double(top) + double(k + 1) * e.row_fall;
            float f = float(g);
            if (double(f) < g) f = std::nextafter(f, std::numeric_limits<float>::max());
            reach[k] = f;
        }
        for (size_t l = 1; l < e.row_width.size(); ++l) {
            const size_t wb = size_t(e.row_width[l - 1]), w = size_t(e.row_width[l]);
            const float* below = reach + e.row_offset[l - 1];
            float* up = reach + e.row_offset[l];
            for (size_t k = 0; k < w; ++k) {
                float m = below[k * BeamEntry::kRowFan];
                for (size_t c = k * BeamEntry::kRowFan + 1;
                     c < std::min(wb, (k + 1) * BeamEntry::kRowFan); ++c)
                    m = std::max(m, below[c]);
                up[k] = m;
            }
        }
    });
    e.row_axis = axis;
}

double HeightfieldTraversal::row_clear(const BeamEntry& e, double ox, double oy, double oz,
                                       const Vec3& d, double t, double z_bottom) const {
    const int axis = e.row_axis, n = n_;
    const double along = axis == 0 ? d.x : d.y, across = axis == 0 ? d.y : d.x;
    const double oa = axis == 0 ? ox : oy, ob = axis == 0 ? oy : ox;
    const double L = period();
    // Where the ray passes below the surface's bottom: its row must hold it until there.
    const double t_end = (z_bottom - oz) / d.z;
    if (!(t_end > t) || along == 0) return t;
    double b0 = ob + t * across, b1 = ob + t_end * across;
    const double shift = std::floor(b0 / L) * L;
    b0 -= shift, b1 -= shift;
    const double lo = std::min(b0, b1), hi = std::max(b0, b1);
    int j = std::clamp(int(lo * inv_spacing_), 0, n - 1);
    while (j > 0 && lo < line_[size_t(j)]) --j;
    while (j < n - 1 && lo >= line_[size_t(j) + 1]) ++j;
    if (!(line_[size_t(j)] <= lo && hi <= line_[size_t(j) + 1])) return t;
    const float* reach = e.row_reach.data() + size_t(j) * e.row_stride;
    const size_t levels = e.row_width.size();
    constexpr int fan = BeamEntry::kRowFan;
    // In the order of travel, cell k of the copy of the patch the ray is in is entered at
    // t_base + k cell_t, and may be met when its reach is >= a: the ray's height where the copy
    // starts, less a cell of its fall and the pad (the float grid lines lie within an ulp of
    // i * spacing). The next copy: a period later, a period's fall lower.
    const bool forward = along > 0;
    const double cell_t = spacing_ / std::abs(along);
    const double x = (oa + t * along) * inv_spacing_;
    const double copy = std::floor(x / n);
    const int c = std::clamp(int(x - copy * n), 0, n - 1);
    double t_base = ((copy * n + (forward ? 0 : n)) * spacing_ - oa) / along;
    double a = oz + t_base * d.z - e.row_fall - 2 * pad_;
    const double period_t = n * cell_t, period_fall = n * e.row_fall;
    const float row_top = reach[e.row_offset[levels - 1]];
    int start = forward ? c : n - 1 - c;
    for (;;) {
        if (t_base + start * cell_t >= t_end) return t_end;
        // The first cell from `start` on that may be met: up the levels while a fan of nodes
        // holds none, down into the first node that holds one.
        if (double(row_top) >= a) {
            size_t level = 0;
            long long at = start;
            for (;;) {
                const float* nodes = reach + e.row_offset[level];
                const long long w = e.row_width[level];
                const long long end = std::min((at / fan + 1) * fan, w);
                while (at < end && double(nodes[at]) < a) ++at;
                if (at < end) {
                    if (level == 0) {
                        // The walk takes over a cell before it.
                        return std::clamp(t_base + double(at - 1) * cell_t, t, t_end);
                    }
                    --level, at *= fan;
                    continue;
                }
                if (end == w) break; // none further in this copy
                ++level, at = end / fan;
            }
        }
        // On to the copy where the ray comes down to the row's top.
        const double copies = std::max(1.0, std::ceil((a - double(row_top)) / period_fall));
        t_base += copies * period_t, a -= copies * period_fall, start = 0;
    }
}

std::size_t HeightfieldTraversal::memory_bytes() const {
    std::size_t bytes = line_.size() * sizeof(double) + h_.size() * sizeof(float);
    bytes += pyramid_.size() * sizeof(float) + beam_window_.size() * sizeof(float);
    for (const std::vector<float>& m : dilated_) bytes += m.size() * sizeof(float);
    return bytes;
}

double HeightfieldTraversal::height_at(double x, double y) const {
    const size_t stride = size_t(n_) + 1;
    return HeightField::triangulated_height(
        x * inv_spacing_, y * inv_spacing_, n_, nullptr, nullptr,
        [&](int i, int j) { return h_[size_t(j) * stride + size_t(i)]; });
}

bool HeightfieldTraversal::avx2_supported() {
#if defined(__x86_64__)
    return __builtin_cpu_supports("avx2");
#else
    return false; // walk_avx2 is then the baseline walk again
#endif
}

void HeightfieldTraversal::use_avx2(bool on) {
    avx2_ = on && avx2_supported();
}

TraversalHit HeightfieldTraversal::trace(const Vec3& o, const Vec3& d, double z_top,
                                         double z_bottom, int max_wraps,
                                         const BeamEntry* beam) const {
    return avx2_ ? oriented<true>(o, d, z_top, z_bottom, max_wraps, beam)
                 : oriented<false>(o, d, z_top, z_bottom, max_wraps, beam);
}

template <bool Avx2>
TraversalHit HeightfieldTraversal::oriented(const Vec3& o, const Vec3& d, double z_top,
                                            double z_bottom, int max_wraps,
                                            const BeamEntry* beam) const {
    // The dominant axis becomes z' of the sheared frame; the other two keep the winding.
    const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
    const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    const double dz = kz == 0 ? d.x : kz == 1 ? d.y : d.z;
    // Conditional branches, not a jump table: a beam's rays alternate between a few of these,
    // which the branch predictor follows and an indirect jump did not (callgrind, 1024^2,
    // theta_i 60 deg: 0.7 mispredicted jumps per call before).
    if (kz == 2)
        return dz < 0 ? walk_on<Avx2, 1, 0, 2>(o, d, z_top, z_bottom, max_wraps, beam)
                      : walk_on<Avx2, 0, 1, 2>(o, d, z_top, z_bottom, max_wraps, beam);
    if (kz == 0)
        return dz < 0 ? walk_on<Avx2, 2, 1, 0>(o, d, z_top, z_bottom, max_wraps, beam)
                      : walk_on<Avx2, 1, 2, 0>(o, d, z_top, z_bottom, max_wraps, beam);
    return dz < 0 ? walk_on<Avx2, 0, 2, 1>(o, d, z_top, z_bottom, max_wraps, beam)
                  : walk_on<Avx2, 2, 0, 1>(o, d, z_top, z_bottom, max_wraps, beam);
}

template <bool Avx2, int KX, int KY, int KZ>
TraversalHit HeightfieldTraversal::walk_on(const Vec3& o, const Vec3& d, double z_top,
                                           double z_bottom, int max_wraps,
                                           const BeamEntry* beam) const {
    if constexpr (Avx2)
        return walk_avx2<KX, KY, KZ>(o, d, z_top, z_bottom, max_wraps, beam);
    else
        return walk<KX, KY, KZ>(o, d, z_top, z_bottom, max_wraps, beam);
}

#define GONIO_WALK walk
#include "gonio/trace/heightfield_walk.inc"
#undef GONIO_WALK

// The same walk for AVX2 (three-operand instructions, inline rounding): without FMA, the same
// operations, so the same results bit for bit; chosen at run time where the processor has it.
#if defined(__x86_64__)
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
#define GONIO_WALK walk_avx2
#include "gonio/trace/heightfield_walk.inc"
#undef GONIO_WALK
#if defined(__x86_64__)
#pragma GCC pop_options
#endif

} // namespace gonio
