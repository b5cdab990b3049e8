#pragma once
// Large zeroed buffers of doubles kept between traces. A trace's tallies are a hundred megabytes
// or so of fresh pages (a 32-channel case: its reducer's sums); taken from the kernel anew each
// time, their page faults cost more than the rays they hold. Buffers handed back are kept (up to
// a bound) and handed out again zeroed: the same values, without the faults.
#include <cstddef>
#include <vector>

namespace gonio {

// n zeros, in a kept buffer when one is large enough.
std::vector<double> take_zeroed(size_t n);
// Keeps v's storage for the next take_zeroed (small ones, and beyond the bound, are freed).
void give_back(std::vector<double>&& v);
// Frees every kept buffer (between cases: their sizes change).
void release_buffers();

} // namespace gonio
