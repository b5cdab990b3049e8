#pragma once
// A one-line progress display on a terminal (stderr); silent when stderr is not a terminal or
// when quiet, so logs stay clean.
#include <chrono>
#include <string>

namespace gonio {

class Progress {
  public:
    Progress(long long total, bool quiet);
    ~Progress();
    void update(long long done, const std::string& label);
    void finish();
    bool enabled() const { return enabled_; }

  private:
    long long total_;
    bool enabled_;
    bool open_ = false;
    std::chrono::steady_clock::time_point start_, last_;
};

} // namespace gonio
