#pragma once
// A configuration error: printed as one line naming the file, the line, the key and what is
// allowed; the program exits with code 2 before doing any work.
#include <stdexcept>
#include <string>

namespace gonio {

class ConfigError : public std::runtime_error {
  public:
    // line 0: the value came from the command line (--set); line < 0: the whole file.
    ConfigError(const std::string& file, int line, const std::string& key,
                const std::string& problem);
    const std::string& file() const { return file_; }
    int line() const { return line_; }
    const std::string& key() const { return key_; }

  private:
    std::string file_;
    int line_;
    std::string key_;
};

// Closest candidate by edit distance, or "" if none is close enough to be a likely typo.
std::string closest_name(const std::string& word, const std::string* candidates, size_t count);

} // namespace gonio
