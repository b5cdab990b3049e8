#include "core/config_error.h"

#include "core/message.h"

#include <algorithm>
#include <vector>

namespace gonio {

namespace {
std::string format(const std::string& file, int line, const std::string& key,
                   const std::string& problem) {
    std::string where = file;
    if (line > 0)
        where += ":" + std::to_string(line);
    else if (line == 0)
        where += " (--set)";
    if (key.empty()) return where + ": " + problem;
    return where + ": key '" + cut_text(key) + "': " + problem;
}

size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        cur[0] = i;
        for (size_t j = 1; j <= b.size(); ++j)
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
        std::swap(prev, cur);
    }
    return prev[b.size()];
}
} // namespace

ConfigError::ConfigError(const std::string& file, int line, const std::string& key,
                         const std::string& problem)
    : std::runtime_error(format(file, line, key, problem)), file_(file), line_(line), key_(key) {}

std::string closest_name(const std::string& word, const std::string* candidates, size_t count) {
    std::string best;
    if (word.size() > 64) return best; // no key is that long: not a typo of one
    size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
    for (size_t i = 0; i < count; ++i) {
        const size_t d = edit_distance(word, candidates[i]);
        if (d < best_d) best_d = d, best = candidates[i];
    }
    return best;
}

} // namespace gonio
