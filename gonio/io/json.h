#pragma once
// A minimal JSON writer for `gonio info --json` (objects, arrays, strings, numbers).
#include <ostream>
#include <string>
#include <vector>

namespace gonio::json {

std::string quote(const std::string& s); // a JSON string literal, escaped
std::string number(double v);            // shortest round-trip form; null for NaN/Inf
std::string array(const std::vector<double>& v);

} // namespace gonio::json
