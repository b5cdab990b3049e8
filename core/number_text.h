#pragma once
// Numbers as people read them: the shortest text that reads back as the same double ("0.3", not
// "0.29999999999999999"), for descriptions, messages and listings.
#include <charconv>
#include <string>

namespace gonio {

inline std::string shortest(double v) {
    char buf[40];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

} // namespace gonio
