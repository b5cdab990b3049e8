#pragma once
// The virtual gonioreflectometer (R19 section 5; DESIGN section 4): a collimated beam from
// direction i falls on the periodic microsurface; every ray is followed bounce by bounce with the
// facets' own scattering, and its exit direction is binned on the equal-area sensor, per bounce
// order, on the upper sensor if it leaves upwards or on the lower one if it crossed a transmissive
// surface. Each ray carries power 1/N_rays: with the patch wrapped, the beam's footprint is the
// whole patch and no cos(theta_i) factor appears. An energy ledger accounts for every ray.
#include "gonio/material/material.h"
#include "gonio/trace/scene.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <vector>

namespace gonio {

struct TraceSettings {
    long long rays = 1 << 20; // rounded up to a square S^2 (an S x S stratified beam)
    int orders = 10;          // bounce orders stored separately: 1..orders, then one overflow bin
    int max_bounces = 1000;   // a ray still bouncing after this is cut (ledger: capped)
    int block = 4096;         // rays per block: the unit of threading and of random streams
    std::uint64_t seed = 1;
    std::uint64_t stream = 0; // distinguishes cases and incidences (mixed into every block's key)
};

// Fractions of the incident power, per channel.
struct EnergyLedger {
    std::vector<double> reflected;   // [order][channel]: orders 1..K, then the overflow order
    std::vector<double> transmitted; // [order][channel]: transmissive materials only, else empty
    std::vector<double> absorbed;    // [channel]
    std::vector<double> capped;      // [channel]: still bouncing at max_bounces
    std::vector<double> lost;        // [channel]: crossed an opaque surface, or wrapped without
                                     // end (a crack or a numerical failure)
    // 1 - everything above, per channel: zero up to round-off when nothing is lost.
    std::vector<double> unaccounted;
};

struct TraceResult {
    int orders = 0; // K + 1 (the last is the overflow order)
    int cells = 0, channels = 0;
    long long rays = 0;
    long long segments = 0;     // rtcIntersect1 calls
    std::vector<double> energy; // [order][cell][channel]: fraction of the incident power
    // The same on the lower sensor, for transmissive materials (empty otherwise). The order of a
    // transmitted ray is its number of scattering events, refractions included.
    std::vector<double> transmitted;
    EnergyLedger ledger;
    double seconds = 0;
};

TraceResult trace_incidence(const Scene& scene, const Material& material,
                            const BeckersSensor& sensor, const Vec3& wi,
                            const TraceSettings& settings);

// A material whose channels scatter differently (a dispersive dielectric refracts each wavelength
// its own way) is traced once per part, each with its own random streams; the parts' channels are
// concatenated in order. With one part this is trace_incidence.
TraceResult trace_incidence(const Scene& scene, const std::vector<const Material*>& parts,
                            const BeckersSensor& sensor, const Vec3& wi,
                            const TraceSettings& settings);

} // namespace gonio
