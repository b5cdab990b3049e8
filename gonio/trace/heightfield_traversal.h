#pragma once
// A traversal made for gonio's one surface, the periodic n x n grid of heights: the same two
// triangles per cell that Embree's grid geometry holds (the same (v0, v1, v3), (v2, v3, v1) split
// and the same float vertices), walked cell by cell along the ray, jumping clear stretches with
// dilated min-max blocks and, for rays that cross many cells within the relief (grazing ones), a
// min-max pyramid over the grid; native wrapping through the side walls. The rays of a beam
// (one direction, one start plane) start where their block of origins is known clear
// (beam_entry), or, a grazing beam along a grid axis, where each ray's own row is.
//
// Watertight by construction: every vertex is projected into the ray's sheared frame once per
// test from the same inputs, and the edge function of a shared edge is computed from the same two
// projected vertices in both triangles, so it is exactly the negation of itself (IEEE subtraction
// is antisymmetric; the file is built without FMA contraction so that this holds). Triangles are
// closed: a ray through a shared edge or vertex (edge function exactly 0) hits every triangle
// that holds it, so no ray passes between two triangles of a cell or of neighbouring cells.
// Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013 (Sec. 3, Fig. 2).
// Between cells, the walk visits every cell the ray crosses; near a cell corner (where rounding
// could pick the wrong order of the two crossings) it tests both cells beside the corner.
#include "core/math.h"
#include "heightfield/heightfield.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

struct TraversalHit {
    enum Kind { hit, escaped_up, escaped_down, lost } kind = lost;
    double t = 0;  // along the ray from its origin (hit only)
    Vec3 position; // o + t d brought into the patch (hit only)
    Vec3 normal;   // the triangle's geometric normal, unnormalised, facing +z (hit only)
    int cell_x = -1, cell_y = -1;
    int triangle = -1; // 0: (v0, v1, v3), 1: (v2, v3, v1), as heightfield.h names them
    int wraps = 0;     // side walls crossed before the hit or the escape
};

// A beam: rays of one direction `d`, going down, that start on the plane z = z_start. Per block of
// 2^shift x 2^shift cells of origins, a distance along the ray that every ray starting over the
// block travels clear of the surface, so that its walk starts there, possibly several periods
// away for grazing beams (built by HeightfieldTraversal::beam_entry; empty, width 0, where it
// would not pay or where the beam has row trees instead).
struct BeamEntry {
    Vec3 d;
    double z_start = 0;
    int shift = 0, width = 0;
    std::vector<float> t; // width^2, row-major
    // A grazing beam along a grid axis (its rays stay within one row of cells, or one column,
    // until they pass below the surface; row_axis 0 for rows, the beam along x, 1 for columns,
    // -1 without): per row, in the order of travel, each cell's reach (its highest corner raised
    // by the rays' fall from the start of the patch's copy to the cell's far side, row_fall a
    // cell), so that a ray meets it only if its reach exceeds its own height at that start; and
    // a max tree of kRowFan-wide nodes over them. Level l holds row_width[l] nodes from
    // row_offset[l] on in its row's row_stride floats, level 0 the cells.
    static constexpr int kRowFan = 16; // a node's children: one cache line of floats
    int row_axis = -1;
    double row_fall = 0;
    std::size_t row_stride = 0;
    std::vector<std::size_t> row_offset;
    std::vector<int> row_width;
    std::vector<float> row_reach;
};

// One ray for HeightfieldTraversal::trace_lanes, as trace() takes it.
struct LaneRay {
    Vec3 o, d;
    int max_wraps = 0;
    const BeamEntry* beam = nullptr;
};

class HeightfieldTraversal {
  public:
    explicit HeightfieldTraversal(const HeightField& surface);

    // Follows the ray from `o` (anywhere: the patch repeats) along `d` to the first triangle it
    // meets at t >= 0, from either side, crossing the side walls natively (at most max_wraps
    // times, else kind = lost, wraps then > max_wraps), or until it passes the plane z_top going
    // up or z_bottom going down (escaped_up / escaped_down).
    // A ray of `beam` (its direction, starting on its plane) starts at its block's clear
    // distance; any other ray ignores it.
    TraversalHit trace(const Vec3& o, const Vec3& d, double z_top, double z_bottom, int max_wraps,
                       const BeamEntry* beam = nullptr) const;

    // trace() of each of `count` rays, out[i] for rays[i]: side by side in SIMD lanes where the
    // walk stays near the surface (heightfield_lanes.cpp), the others one by one. A lane finds
    // what the scalar walk finds but where the scalar walk's jumps over clear blocks would have
    // rounded differently (within a float ulp of a block's bounds).
    void trace_lanes(const LaneRay* rays, std::size_t count, double z_top, double z_bottom,
                     TraversalHit* out) const;
    // The lanes of the widest instruction set the processor has (Highway's run-time dispatch).
    static int native_lanes();
    // The instruction sets the lanes are compiled for that this processor has (name, Highway's
    // target bit, for hwy::SetSupportedTargetsForTest in the tests).
    static std::vector<std::pair<std::string, std::int64_t>> lane_targets();
    // use_lanes(false): trace_lanes walks every ray with the scalar walk (tests, benchmark).
    void use_lanes(bool on) { lanes_ = on ? native_lanes() : 0; }
    bool uses_lanes() const { return lanes_ > 0; }

    // The clear distances of a beam of `rays` rays of direction d (d.z < 0) from the plane
    // z = z_start (none when too few rays would use them to pay for them).
    BeamEntry beam_entry(const Vec3& d, double z_start, long long rays) const;

    // The triangulated surface's height at (x, y), from the traversed vertices.
    double height_at(double x, double y) const;

    double period() const { return line_[size_t(n_)]; } // as the float vertices place it
    // Vertex (i, j), i, j in [0, n], as Embree's grid holds it.
    Vec3 vertex(int i, int j) const {
        return {line_[size_t(i)], line_[size_t(j)], h_[size_t(j) * (size_t(n_) + 1) + size_t(i)]};
    }
    std::size_t memory_bytes() const;

    // The walk runs as compiled for AVX2 where the processor has it (the same results bit for
    // bit); use_avx2(false) picks the baseline x86-64 one (for the tests and the benchmark).
    static bool avx2_supported();
    void use_avx2(bool on);
    bool uses_avx2() const { return avx2_; }

  private:
    int n_ = 0;
    double inv_spacing_ = 1, spacing_ = 1;
    double corner_tolerance_ = 0; // distance to a cell corner below which both sides are tested
    double pad_ = 0;              // added to every min-max bound (conservative skipping)
    double relief_ = 0;           // z_max - z_min
    std::vector<double> line_;    // the n + 1 grid lines, float(i * spacing), as Embree's vertices
    std::vector<float> h_;        // (n + 1)^2 heights, the last row and column repeating the first
    // Level l >= 1 of the pyramid: ceil(n / 2^l)^2 nodes of (min, max) heights over their cells'
    // vertices, row-major, from pyramid_[level_offset_[l]]; level 0 is the cell itself (its four
    // corners).
    std::vector<float> pyramid_;
    std::vector<std::size_t> level_offset_;
    std::vector<int> level_width_;
    int top_ = 0; // the level of one node
    // Dilated blocks: for block size b = radius r in kJumpRadius, per block of b x b cells the
    // (min, max) of every height within r cells of the block (periodic). A ray anywhere in the
    // block whose heights over its next r cells of travel miss that range jumps them whole
    // (no alignment to nodes); the tables are small enough to stay in cache.
    static constexpr int kJumps = 2;
    static constexpr int kJumpShift[kJumps] = {2, 4}; // b = r = 4 and 16 cells
    std::vector<float> dilated_[kJumps];
    int dilated_width_[kJumps] = {0, 0};
    int jumps_ = 0; // the sizes that fit the grid
    // For beam_entry, blocks of b = 2^kBeamShift cells: per even cell (i, j) the maximum of the
    // heights of vertices i - 1 .. i + b + 4 by j - 1 .. j + b + 4 (periodic), which hold every
    // cell a block's rays cross over one cell of travel from cell (i, j) or (i + 1, j + 1) on,
    // with a cell to spare; ceil(n / 2)^2 of them.
    static constexpr int kBeamShift = 2;
    static constexpr int kGrazingWindowSteps = 64; // see grazing_entry
    std::vector<float> beam_window_;

    bool avx2_ = false; // the walk compiled for AVX2 (the same results)
    int lanes_ = 0;     // trace_lanes' lanes (0: the scalar walk)

    // beam_entry's clear distances for a grazing beam (e sized, its d and z_start set).
    void grazing_entry(BeamEntry& e) const;
    // beam_entry's row trees for a grazing beam along a grid axis (e's d set; row_axis stays -1
    // where the rays would drift across rows).
    void grazing_rows(BeamEntry& e) const;
    // A distance >= t along a ray of beam e (origin moved to (ox, oy, oz) by whole periods) up
    // to which it is clear of the surface, from e's row trees: t itself when the ray leaves its
    // row before it passes z_bottom.
    double row_clear(const BeamEntry& e, double ox, double oy, double oz, const Vec3& d, double t,
                     double z_bottom) const;

    // The walk for the ray's orientation, in the chosen instruction set.
    template <bool Avx2>
    TraversalHit oriented(const Vec3& o, const Vec3& d, double z_top, double z_bottom,
                          int max_wraps, const BeamEntry* beam) const;
    template <bool Avx2, int KX, int KY, int KZ>
    TraversalHit walk_on(const Vec3& o, const Vec3& d, double z_top, double z_bottom, int max_wraps,
                         const BeamEntry* beam) const;
    // The walk, for one orientation of the ray's sheared frame (kz: the dominant axis), for any
    // x86-64 and for AVX2 (heightfield_walk.inc, compiled twice).
    template <int KX, int KY, int KZ>
    TraversalHit walk(const Vec3& o, const Vec3& d, double z_top, double z_bottom, int max_wraps,
                      const BeamEntry* beam) const;
    template <int KX, int KY, int KZ>
    TraversalHit walk_avx2(const Vec3& o, const Vec3& d, double z_top, double z_bottom,
                           int max_wraps, const BeamEntry* beam) const;
};

} // namespace gonio
