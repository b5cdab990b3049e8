#include "gonio/cli/stop_signal.h"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace gonio {

namespace {
std::atomic<int> signals{0};
extern "C" void on_stop(int sig) {
    if (signals.fetch_add(1) >= 1) {
        const char msg[] = "\ngonio: stopped at once (second signal)\n";
        [[maybe_unused]] const auto n = ::write(2, msg, sizeof msg - 1);
        ::_exit(128 + sig);
    }
}
} // namespace

void install_stop_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool stop_requested() {
    return signals.load() > 0;
}

} // namespace gonio
