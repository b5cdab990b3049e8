#pragma once
// Hit for hit: the same recorded segments (origin, direction as the pipeline gives Embree)
// through two scenes of one surface, each segment's first hit compared. Two hits agree when
// they are on the same triangle, or on triangles sharing the edge or vertex the hit lies on (a
// point on a shared edge belongs to both), and their t agree within a relative tolerance.
#include "gonio/trace/scene.h"

#include <cstddef>
#include <string>
#include <vector>

namespace gonio {

struct BackendComparison {
    long long segments = 0;
    long long both_missed = 0;    // neither hit anything in the patch (the ray wraps or leaves)
    long long agree = 0;          // same triangle (or shared edge), t within tolerance (hits)
    long long on_shared_edge = 0; // of which: different triangles holding the hit's edge
    long long only_reference = 0; // the reference hit, the other missed
    long long only_other = 0;     // the other hit, the reference missed
    long long other_triangle = 0; // both hit, on triangles that do not share the point
    long long t_differs = 0;      // same triangle, t beyond the tolerance, the other's t wrong
    // Disagreements the exact test (the ray against the triangles' float vertices, in long
    // double) settles for the other backend: Embree's single-precision t on a short segment, or
    // its inside / outside call on a crease the ray grazes within 1e-6 of a cell. Not counted
    // as mismatches.
    long long reference_rounding = 0;
    double max_t_relative = 0;         // over the agreeing hits
    std::vector<std::string> examples; // the first few mismatches, described
    long long mismatches() const {
        return only_reference + only_other + other_triangle + t_differs;
    }
    void add(const BackendComparison& o);
};

// `segments`: 6 floats per segment (origin, direction), as Scene::record_segments writes them.
// Segments [first, last).
BackendComparison compare_backends(const Scene& reference, const Scene& other,
                                   const std::vector<float>& segments, double t_tolerance = 1e-5,
                                   std::size_t first = 0, std::size_t last = std::size_t(-1));

} // namespace gonio
