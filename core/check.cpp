#include "core/check.h"

#include <cstdio>
#include <cstdlib>

namespace gonio::detail {

void check_failed(const char* file, int line, const char* condition, const std::string& detail) {
    std::fprintf(stderr, "gonio: internal error: %s:%d: CHECK(%s) failed%s%s\n", file, line,
                 condition, detail.empty() ? "" : ": ", detail.c_str());
    std::fflush(stderr);
    std::abort();
}

} // namespace gonio::detail
