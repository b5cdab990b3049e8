// The streaming reduction of batches (gonio/trace/batch_reducer.h): a batch given sparse (its
// touched rows) or whole reduces to the same bits; the mean is batch_mean's bits; the standard
// error is the two-pass one to round-off, rows missing from most batches included.
#include "core/batch_means.h"
#include "core/buffer_pool.h"
#include "core/random.h"
#include "gonio/trace/batch_reducer.h"

#include <cmath>
#include <cstdint>
#include <doctest/doctest.h>
#include <vector>

using namespace gonio;

TEST_CASE("batch reducer: sparse and whole batches give the same bits, and the two-pass errors") {
    const int B = 16, orders = 3;
    const size_t cells = 50, nc = 4, map = size_t(orders) * cells * nc;
    Rng rng({7, 11});
    std::vector<double> all(size_t(B) * map, 0.0); // [batch][order][cell][channel]
    std::vector<std::vector<std::uint32_t>> touched(B);
    for (int b = 0; b < B; ++b)
        for (size_t row = 0; row < size_t(orders) * cells; ++row) {
            // Rows reached in a few batches only, some channels left at zero.
            const double u = rng.uniform();
            if (u > (row % 7 == 0 ? 0.9 : 0.3)) continue;
            touched[size_t(b)].push_back(std::uint32_t(row));
            for (size_t k = 0; k < nc; ++k)
                if (k != 2 || u < 0.1)
                    all[size_t(b) * map + row * nc + k] = rng.uniform() * (1 + double(row % 5));
        }
    BatchReducer whole(B, orders, cells, nc), sparse(B, orders, cells, nc);
    for (int b = 0; b < B; ++b) {
        whole.add(&all[size_t(b) * map]);
        sparse.add(&all[size_t(b) * map], touched[size_t(b)]);
    }
    std::vector<double> m1, e1, m2, e2;
    OrderSums s1, s2;
    whole.finish(m1, e1, s1);
    sparse.finish(m2, e2, s2);
    CHECK(m1 == m2);
    CHECK(e1 == e2);
    CHECK(s1.l1 == s2.l1);
    CHECK(s1.l2plus == s2.l2plus);
    CHECK(s1.linf == s2.linf);
    CHECK(m1 == batch_mean(all, B)); // the mean's bits: batches summed in order, then / B
    const std::vector<double> two_pass = batch_stderr(all, B);
    double worst = 0;
    for (size_t i = 0; i < map; ++i)
        if (two_pass[i] > 0)
            worst = std::max(worst, std::abs(e1[i] - two_pass[i]) / two_pass[i]);
        else
            CHECK(e1[i] == doctest::Approx(0.0));
    CHECK(worst < 1e-12);
    // The order sums per batch: order 0, orders 1.., all of them.
    for (int b = 0; b < B; ++b)
        for (size_t i = 0; i < cells * nc; ++i) {
            const double* x = &all[size_t(b) * map];
            const size_t at = size_t(b) * cells * nc + i;
            CHECK(s1.l1[at] == x[i]);
            CHECK(s1.l2plus[at] == doctest::Approx(x[cells * nc + i] + x[2 * cells * nc + i]));
            CHECK(s1.linf[at] == doctest::Approx(x[i] + x[cells * nc + i] + x[2 * cells * nc + i]));
        }
}

TEST_CASE(
    "buffer pool: a kept buffer comes back zeroed, and only for a request of about its size") {
    release_buffers();
    std::vector<double> a = take_zeroed(size_t(1) << 18);
    a[5] = 3.0;
    const double* storage = a.data();
    give_back(std::move(a));
    CHECK(a.empty());
    const std::vector<double> small = take_zeroed(size_t(1) << 17); // much smaller: not that one
    CHECK(small.data() != storage);
    const std::vector<double> b = take_zeroed((size_t(1) << 18) - 10);
    CHECK(b.data() == storage);
    CHECK(b.size() == (size_t(1) << 18) - 10);
    CHECK(b[5] == 0.0);
    release_buffers();
}
