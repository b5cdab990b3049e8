#pragma once
// A target accuracy instead of a ray count: the run adds rounds of rays to every batch until the
// relative standard error of the chosen quantity is at most `relative_error`, or a budget runs
// out. The quantities: an albedo (L1, L2+ or every order, the worst channel), or the per-cell
// BRDF (L1 or every order) over the cells at least `cell_fraction` of the brightest, the worst
// cell and channel.
#include "core/config_key.h"
#include "core/enum_names.h"
#include "core/table_reader.h"
#include "gonio/trace/trace_result.h"
#include "sensor/beckers_sensor.h"

#include <string>
#include <vector>

namespace gonio {

enum class TargetQuantity { l1_albedo, l2plus_albedo, linf_albedo, l1_cells, linf_cells };
template <>
struct EnumNames<TargetQuantity> {
    static constexpr const char* what = "target quantity";
    static constexpr const char* names[] = {"l1_albedo", "l2plus_albedo", "linf_albedo", "l1_cells",
                                            "linf_cells"};
};

struct AccuracyTarget {
    TargetQuantity quantity = TargetQuantity::l1_albedo;
    double relative_error = 0;  // 0: no target (the ray count is used as given)
    double cell_fraction = 0.1; // cells quantities: the cells that count
    long long max_rays = 10'000'000'000LL;
    double max_seconds = 3600;
    bool active() const { return relative_error > 0; }
};

// The [trace] keys of a target, and their reading; `rays` is one round.
std::vector<Key> accuracy_target_keys();
AccuracyTarget read_accuracy_target(TableReader& r, long long rays);

// The relative standard error of the target's quantity in `r` (0 where a quantity is exactly 0
// in every batch: more rays cannot change it).
double relative_error_of(const TraceResult& r, const AccuracyTarget& target,
                         const BeckersSensor& sensor);

} // namespace gonio
