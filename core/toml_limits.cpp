#include "core/toml_limits.h"

#include <vector>

namespace gonio {

std::string toml_limits_problem(const std::string& text) {
    if (text.size() > kMaxTomlBytes)
        return "the text is " + std::to_string(text.size() / 1000) + " kB; at most " +
               std::to_string(kMaxTomlBytes >> 20) + " MB is read";
    std::vector<char> open; // the brackets and braces the scan is inside
    bool key = true;        // in a key (where dots nest): at a line's start, in a header, after {
    int dots = 0;
    size_t line = 1;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '#') { // a comment, to the end of the line
            while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
        } else if (c == '"' || c == '\'') { // a string: skipped whole (triple quotes included)
            const bool triple = text.compare(i, 3, std::string(3, c)) == 0;
            const std::string end = triple ? std::string(3, c) : std::string(1, c);
            size_t j = i + end.size();
            while (j < text.size() && text.compare(j, end.size(), end) != 0) {
                if (c == '"' && text[j] == '\\') ++j; // an escape
                if (!triple && text[j] == '\n') break;
                ++j;
            }
            i = std::min(text.size(), j + end.size()) - 1;
        } else if (c == '[' || c == '{') {
            open.push_back(c);
            if (int(open.size()) > kMaxTomlDepth)
                return "line " + std::to_string(line) + ": tables and arrays nest more than " +
                       std::to_string(kMaxTomlDepth) + " deep";
            if (c == '{' || (c == '[' && key)) key = true, dots = 0;
        } else if (c == ']' || c == '}') {
            if (!open.empty()) open.pop_back();
        } else if (c == '=') {
            key = false;
        } else if (c == ',') {
            if (!open.empty() && open.back() == '{') key = true, dots = 0;
        } else if (c == '\n') {
            ++line;
            if (open.empty()) key = true, dots = 0;
        } else if (c == '.' && key && ++dots >= kMaxTomlDepth) {
            return "line " + std::to_string(line) + ": a key of more than " +
                   std::to_string(kMaxTomlDepth) + " dotted parts nests too deep";
        }
    }
    return "";
}

} // namespace gonio
