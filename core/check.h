#pragma once
// Invariants, in the manner of pbrt-v4's util/check.h: GONIO_CHECK holds in every build,
// GONIO_DCHECK in debug and sanitizer builds only (it costs nothing in Release). A failed check is
// a bug in gonio, not a mistake of the user's: it prints the condition and where it failed and
// aborts. User input is validated once, where it is read (the config keys, ConfigError), and
// never re-checked deep inside the library.
#include <string>

namespace gonio::detail {
[[noreturn]] void check_failed(const char* file, int line, const char* condition,
                               const std::string& detail);
} // namespace gonio::detail

#define GONIO_CHECK(cond)                                                                          \
    ((cond) ? (void)0 : ::gonio::detail::check_failed(__FILE__, __LINE__, #cond, std::string()))
// With a message (built only when the check fails).
#define GONIO_CHECK_MSG(cond, message)                                                             \
    ((cond) ? (void)0 : ::gonio::detail::check_failed(__FILE__, __LINE__, #cond, (message)))

#if defined(NDEBUG) && !defined(GONIO_DEBUG_CHECKS)
#define GONIO_DCHECK(cond) ((void)sizeof(bool(cond)))
#else
#define GONIO_DCHECK(cond) GONIO_CHECK(cond)
#endif
