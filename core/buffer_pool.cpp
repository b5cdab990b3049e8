#include "core/buffer_pool.h"

#include <algorithm>
#include <mutex>

namespace gonio {

namespace {
constexpr size_t kSmallest = size_t(1) << 17;  // doubles (1 MiB): below, malloc reuses well
constexpr size_t kMostKept = size_t(16) << 20; // doubles (128 MiB) kept at most

struct Pool {
    std::mutex mutex;
    std::vector<std::vector<double>> kept;
    size_t doubles = 0;
};
Pool& pool() {
    static Pool p;
    return p;
}
} // namespace

std::vector<double> take_zeroed(size_t n) {
    std::vector<double> v;
    if (n >= kSmallest) {
        Pool& p = pool();
        std::lock_guard<std::mutex> lock(p.mutex);
        // The smallest kept buffer that holds n, if it is not much larger: a buffer may end up
        // held for long (an ensemble's means), and should not hold more than it was asked for.
        auto best = p.kept.end();
        for (auto it = p.kept.begin(); it != p.kept.end(); ++it)
            if (it->capacity() >= n && it->capacity() <= n + n / 8 &&
                (best == p.kept.end() || it->capacity() < best->capacity()))
                best = it;
        if (best != p.kept.end()) {
            p.doubles -= best->capacity();
            v = std::move(*best);
            p.kept.erase(best);
        }
    }
    v.assign(n, 0.0);
    return v;
}

void give_back(std::vector<double>&& v) {
    std::vector<double> gone = std::move(v); // v is empty from here whatever happens
    v.clear();
    if (gone.capacity() < kSmallest) return;
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.doubles + gone.capacity() > kMostKept) return;
    p.doubles += gone.capacity();
    p.kept.push_back(std::move(gone));
}

void release_buffers() {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    p.kept.clear();
    p.doubles = 0;
}

} // namespace gonio
