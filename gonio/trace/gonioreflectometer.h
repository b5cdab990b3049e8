#pragma once
// The virtual gonioreflectometer (R19 section 5; docs/gonioreflectometer.md): a
// collimated beam from direction i falls on the periodic microsurface; every ray is followed bounce
// by bounce with the facets' own scattering, and its exit direction is binned on the equal-area
// sensor, per bounce order, on the upper sensor if it leaves upwards or on the lower one if it
// crossed a transmissive surface. Each ray carries power 1/N_rays: with the patch wrapped, the
// beam's footprint is the whole patch and no cos(theta_i) factor appears. An energy ledger accounts
// for every ray. The beam is B independent stratified beams (batches), whose spread gives every
// tally its standard error; a target-accuracy run adds rounds of rays to every batch until it is
// met.
#include "gonio/material/material.h"
#include "gonio/trace/accuracy_target.h"
#include "gonio/trace/scene.h"
#include "gonio/trace/trace_result.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <vector>

namespace gonio {

struct TraceSettings {
    long long rays = 1 << 20; // rounded up to batches x S^2 (each batch an S x S stratified beam)
    int orders = 10;          // bounce orders stored separately: 1..orders, then one overflow bin
    int max_bounces = 1000;   // a ray still bouncing after this is cut (ledger: capped)
    int block = 4096;         // rays per block: the unit of threading and of random streams
    int batches = 32;         // independent beams, for the standard errors (batch means)
    std::uint64_t seed = 1;
    std::uint64_t stream = 0; // distinguishes cases and incidences (mixed into every block's key)
    AccuracyTarget target;    // when active, `rays` is one round and rounds are added
    const TraceBackendKind* backend = &default_trace_backend(); // what the Scene is built with
    // A shard of a single-incidence job traces only the batches b with b mod count = index (the
    // others stay empty); combine_batch_shards puts the parts back together exactly.
    int batch_shard_index = 0, batch_shard_count = 1;
};

// The [trace] table: everything above but the seed, the stream and the block size.
TraceSettings read_trace(TableReader& r);
std::vector<KeyGroup> trace_key_groups();

TraceResult trace_incidence(const Scene& scene, const Material& material,
                            const BeckersSensor& sensor, const Vec3& wi,
                            const TraceSettings& settings);

// A material whose channels scatter differently (a dispersive dielectric refracts each wavelength
// its own way) is traced once per part, each with its own random streams; the parts' channels are
// concatenated in order. With one part this is trace_incidence.
TraceResult trace_incidence(const Scene& scene, const std::vector<const Material*>& parts,
                            const BeckersSensor& sensor, const Vec3& wi,
                            const TraceSettings& settings);

// The traces of the parts of a material (same rays, orders, cells and batches), one result whose
// channels are theirs in order.
TraceResult concatenate_channels(const std::vector<TraceResult>& parts);

// The trace of every batch from parts that each traced a share of them (batch b from
// parts[b mod parts.size()]), with the means and errors recomputed over all: what one process
// tracing every batch gives, bit for bit.
TraceResult combine_batch_shards(const std::vector<TraceResult>& parts);

} // namespace gonio
