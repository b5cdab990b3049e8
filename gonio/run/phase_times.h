#pragma once
// Wall time per phase of a run, in the order the phases first ran; stored in the result file so
// that a slow run says where it went. A case's phases: ndf (its distribution and tables),
// surface, scene, models_setup, trace, model_<name> (each model's evaluation), compare (folding
// each incidence into the result), checkpoint; the run's: config, checkpoint, writing, wall.
#include "core/enum_names.h"

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

enum class Phase {
    config,
    ndf,
    surface,
    scene,
    models_setup,
    trace,
    compare,
    checkpoint,
    writing,
    wall
};
template <>
struct EnumNames<Phase> {
    static constexpr const char* what = "phase";
    static constexpr const char* names[] = {"config",       "ndf",   "surface", "scene",
                                            "models_setup", "trace", "compare", "checkpoint",
                                            "writing",      "wall"};
};

class PhaseTimes {
  public:
    using Clock = std::chrono::steady_clock;
    void add(Phase phase, double seconds) { add(name_of(phase), seconds); }
    // A model's evaluation: the phase model_<name>.
    void add_model(const std::string& model, double seconds) { add("model_" + model, seconds); }
    // Adds the time since `start` to `phase` and returns now (to chain phases).
    Clock::time_point add_since(Phase phase, Clock::time_point start);
    void merge(const PhaseTimes& other); // adds every phase of `other`
    double total() const;
    double seconds(Phase phase) const;
    const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }

  private:
    void add(const std::string& name, double seconds);
    std::vector<std::pair<std::string, double>> phases_;
};

// Adds its lifetime to a phase (or the time until stop()).
class ScopedPhase {
  public:
    ScopedPhase(PhaseTimes& times, Phase phase)
        : times_(times), phase_(phase), start_(PhaseTimes::Clock::now()) {}
    ~ScopedPhase() { stop(); }
    ScopedPhase(const ScopedPhase&) = delete;
    ScopedPhase& operator=(const ScopedPhase&) = delete;
    void stop() {
        if (running_) times_.add_since(phase_, start_);
        running_ = false;
    }

  private:
    PhaseTimes& times_;
    Phase phase_;
    PhaseTimes::Clock::time_point start_;
    bool running_ = true;
};

inline void PhaseTimes::add(const std::string& name, double seconds) {
    for (auto& p : phases_)
        if (p.first == name) {
            p.second += seconds;
            return;
        }
    phases_.emplace_back(name, seconds);
}

inline PhaseTimes::Clock::time_point PhaseTimes::add_since(Phase phase, Clock::time_point start) {
    const auto now = Clock::now();
    add(phase, std::chrono::duration<double>(now - start).count());
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

inline double PhaseTimes::seconds(Phase phase) const {
    for (const auto& p : phases_)
        if (p.first == name_of(phase)) return p.second;
    return 0;
}

} // namespace gonio
