#include "gonio/cli/progress.h"

#include <cstdio>
#include <unistd.h>

namespace gonio {

Progress::Progress(long long total, bool quiet)
    : total_(total), enabled_(!quiet && ::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()), last_(start_ - std::chrono::seconds(1)) {}

Progress::~Progress() {
    finish();
}

void Progress::update(long long done, const std::string& label) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const int width = 24;
    const int filled = total_ > 0 ? static_cast<int>(width * done / total_) : width;
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r\033[K[%s] %lld/%lld %.1fs %s", bar.c_str(), done, total_, elapsed,
                 label.c_str());
    std::fflush(stderr);
    open_ = true;
}

void Progress::finish() {
    if (enabled_ && open_) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
        open_ = false;
    }
}

} // namespace gonio
