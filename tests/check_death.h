#pragma once
// Whether a call fails a GONIO_CHECK: it runs in a child process (fork), whose abort is the
// expected outcome; the parent sees the signal. For the invariants of core/check.h.
#include <csignal>
#include <cstdio>
#include <functional>
#include <sys/wait.h>
#include <unistd.h>

namespace gonio::test {

inline bool fails_check(const std::function<void()>& call) {
    std::fflush(nullptr);
    const pid_t child = ::fork();
    if (child == 0) {
        std::signal(SIGABRT, SIG_DFL); // not the test framework's handler: just die
        if (!std::freopen("/dev/null", "w", stderr)) ::_exit(3); // the message is expected
        call();
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT;
}

} // namespace gonio::test
