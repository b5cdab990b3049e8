#pragma once
// What gonio hands its TOML parser: at most 1 MiB, tables and arrays nested at most 64 deep,
// keys of at most 64 dotted parts. Checked on the text before parsing (the parser recurses:
// a header of 50 000 dotted parts overflowed its stack); a config never comes near.
#include <string>

namespace gonio {

inline constexpr size_t kMaxTomlBytes = size_t(1) << 20;
inline constexpr int kMaxTomlDepth = 64;

// What is wrong with the text's size or nesting, or "" when it is within the limits.
std::string toml_limits_problem(const std::string& text);

} // namespace gonio
