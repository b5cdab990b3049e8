// core/named_array.h: layout, checked indexing, blocks.
#include "check_death.h"
#include "core/named_array.h"

#include <doctest/doctest.h>
#include <stdexcept>

using gonio::Array;
using gonio::test::fails_check;

TEST_CASE("named array: row-major layout, checked indices and blocks") {
    Array a({"theta_i", "phi_i", "channel"}, {2, 3, 4}, "1", "test");
    CHECK(a.size() == 24);
    CHECK(a.rank() == 3);
    CHECK(a.axis("phi_i") == 1);
    CHECK(a.extent("channel") == 4);
    CHECK(a.has("channel"));
    CHECK(!a.has("cell"));
    CHECK(fails_check([&] { (void)a.axis("cell"); }));
    a.at({1, 2, 3}) = 5;
    CHECK(a.data[((1 * 3) + 2) * 4 + 3] == 5);
    CHECK(a.offset({1, 2}) == 20);
    CHECK(fails_check([&] { (void)a.at({2, 0, 0}); }));
    CHECK(fails_check([&] { (void)a.at({0, 0}); })); // a block, not an element
    a.put({0, 1}, {1, 2, 3, 4});
    CHECK(a.block({0, 1}) == std::vector<double>{1, 2, 3, 4});
    CHECK(a.at({0, 1, 2}) == 3);
    CHECK(fails_check([&] { a.put({0, 1}, {1, 2}); }));
    const Array b = a.like("1/sr", "other");
    CHECK(b.dims == a.dims);
    CHECK(b.shape == a.shape);
    CHECK(b.units == "1/sr");
    CHECK(b.at({1, 2, 3}) == 0);
    CHECK(fails_check([] { Array({"a"}, {1, 2}); }));
}
