#pragma once
// Messages quote their input: a key, a value, a path. Quoted text is cut to a readable length
// (a 1 MB unknown key is not echoed in full), and a message printed is one line.
#include <string>

namespace gonio {

// `text`, or its first characters and how long it was, when longer than `most`.
inline std::string cut_text(const std::string& text, size_t most = 80) {
    if (text.size() <= most) return text;
    return text.substr(0, most) + "… (" + std::to_string(text.size()) + " characters)";
}

// A message as one line of at most `most` characters (line breaks become "; ").
inline std::string one_line(const std::string& text, size_t most = 900) {
    std::string out;
    for (char c : text) {
        if (c == '\n') {
            if (!out.empty() && out.back() != ' ') out += "; ";
        } else if (c != '\r') {
            out += c;
        }
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
    return cut_text(out, most);
}

} // namespace gonio
