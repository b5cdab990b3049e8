#pragma once
// The library's parallel loop: tbb::parallel_for over [first, last), each task computing in the
// result floating-point mode (core/float_mode.h), so that whichever thread runs a piece, and
// whatever it ran before, the bits are the same. Use it, not tbb::parallel_for, for anything
// that ends in a result.
#include "core/float_mode.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gonio {

template <class Index, class Body>
void parallel_for(Index first, Index last, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<Index>(first, last),
                      [&](const tbb::blocked_range<Index>& r) {
                          const ResultFloatMode mode;
                          for (Index i = r.begin(); i != r.end(); ++i) body(i);
                      });
}

// The same over a blocked range with a grain size (the body takes the range).
template <class Index, class Body>
void parallel_for_ranges(Index first, Index last, Index grain, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<Index>(first, last, grain),
                      [&](const tbb::blocked_range<Index>& r) {
                          const ResultFloatMode mode;
                          body(r);
                      });
}

} // namespace gonio
