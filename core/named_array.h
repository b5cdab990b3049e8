#pragma once
// A small N-D array of doubles with named dimensions, row-major (the last dimension varies
// fastest), with the units and long name it is stored under. Results are held in these so that
// their layout is data, not a comment: the writer maps each dimension name to the file's scale of
// that name. Every index is checked (GONIO_CHECK: a wrong index is a bug).
#include "core/check.h"

#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

namespace gonio {

struct Array {
    std::vector<std::string> dims;
    std::vector<size_t> shape;
    std::vector<double> data;
    std::string units, long_name;

    Array() = default;
    // Zero-filled.
    Array(std::vector<std::string> dims_, std::vector<size_t> shape_, std::string units_ = "",
          std::string long_name_ = "")
        : dims(std::move(dims_)), shape(std::move(shape_)), units(std::move(units_)),
          long_name(std::move(long_name_)) {
        GONIO_CHECK(dims.size() == shape.size());
        data.assign(count(0), 0.0);
    }

    bool empty() const { return data.empty(); }
    size_t rank() const { return shape.size(); }
    size_t size() const { return data.size(); }
    bool has(const std::string& dim) const {
        for (const auto& d : dims)
            if (d == dim) return true;
        return false;
    }
    size_t axis(const std::string& dim) const {
        for (size_t k = 0; k < dims.size(); ++k)
            if (dims[k] == dim) return k;
        GONIO_CHECK_MSG(false, "no dimension " + dim);
        return 0;
    }
    size_t extent(const std::string& dim) const { return shape[axis(dim)]; }
    // Elements in one index of dimension `from - 1`: the product of the extents from `from` on.
    size_t count(size_t from) const {
        size_t n = 1;
        for (size_t k = from; k < shape.size(); ++k) n *= shape[k];
        return n;
    }

    // The flat offset of the leading indices (fewer than rank: the start of that block).
    size_t offset(std::initializer_list<size_t> index) const {
        GONIO_CHECK(index.size() <= shape.size());
        size_t at = 0, k = 0;
        for (size_t i : index) {
            GONIO_CHECK_MSG(i < shape[k], "index " + std::to_string(i) + " of " + dims[k] +
                                              " out of [0, " + std::to_string(shape[k]) + ")");
            at = at * shape[k] + i;
            ++k;
        }
        return at * count(k);
    }
    double& at(std::initializer_list<size_t> index) { return data[element(index)]; }
    double at(std::initializer_list<size_t> index) const { return data[element(index)]; }

    // The block at the leading indices, as a flat copy ...
    std::vector<double> block(std::initializer_list<size_t> leading) const {
        const size_t from = offset(leading);
        return {data.begin() + long(from), data.begin() + long(from + count(leading.size()))};
    }
    // ... and overwritten (its size must match).
    void put(std::initializer_list<size_t> leading, const std::vector<double>& values) {
        const size_t from = offset(leading), n = count(leading.size());
        GONIO_CHECK_MSG(values.size() == n, "a block of " + std::to_string(values.size()) +
                                                " values where " + std::to_string(n) + " belong");
        for (size_t k = 0; k < n; ++k) data[from + k] = values[k];
    }

    // The same layout under another name and units, zero-filled.
    Array like(std::string units_, std::string long_name_) const {
        return Array(dims, shape, std::move(units_), std::move(long_name_));
    }

  private:
    size_t element(std::initializer_list<size_t> index) const {
        GONIO_CHECK(index.size() == shape.size()); // an element, not a block
        return offset(index);
    }
};

} // namespace gonio
