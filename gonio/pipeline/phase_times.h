#pragma once
// Wall time per phase of a run (NDF and tables, surface, scene, trace, each model, writing), in
// the order the phases ran; stored in the result file so that a slow run says where it went.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

class PhaseTimes {
  public:
    using Clock = std::chrono::steady_clock;
    // Adds `seconds` to phase `name` (created at the end on first use).
    void add(const std::string& name, double seconds);
    // Adds the time since `start` to `name` and returns now (to chain phases).
    Clock::time_point add_since(const std::string& name, Clock::time_point start);
    void merge(const PhaseTimes& other); // adds every phase of `other`
    double total() const;
    const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }

  private:
    std::vector<std::pair<std::string, double>> phases_;
};

inline void PhaseTimes::add(const std::string& name, double seconds) {
    for (auto& p : phases_)
        if (p.first == name) {
            p.second += seconds;
            return;
        }
    phases_.emplace_back(name, seconds);
}

inline PhaseTimes::Clock::time_point PhaseTimes::add_since(const std::string& name,
                                                           Clock::time_point start) {
    const auto now = Clock::now();
    add(name, std::chrono::duration<double>(now - start).count());
    return now;
}

inline void PhaseTimes::merge(const PhaseTimes& other) {
    for (const auto& [name, s] : other.phases_) add(name, s);
}

inline double PhaseTimes::total() const {
    double t = 0;
    for (const auto& p : phases_) t += p.second;
    return t;
}

} // namespace gonio
