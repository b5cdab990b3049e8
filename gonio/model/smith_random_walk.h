#pragma once
// Multiple scattering on the Smith microsurface, estimated by the random walk of Heitz, Hanika,
// d'Eon and Dachsbacher 2016 (H16, "Multiple-Scattering Microfacet BSDFs with the Smith Model").
// The microsurface is a random medium of heights: a path at height h going in direction w meets
// the surface again with the Smith statistics of uncorrelated heights and slopes (H16 section 4),
// at a normal drawn from the distribution of normals visible from -w (H16 section 5), where the
// facet scatters it with its own material (the simulator's materials: mirror, conductor, Schlick,
// dielectric with transmission, Lambertian, interfaced Lambertian). Its single scattering is Model
// L1 with the height-correlated G2 (H16 section 6), orders 2 and up are what Smith's model misses.
//
// The heights are uniform on [-1, 1] (H16 shows that the result does not depend on their
// distribution; tests/test_smith_random_walk.cpp holds it against a walk on Gaussian heights).
// Any NDF of gonio: normals visible from below the horizon (a path going up meets facets from
// underneath) are drawn by rejection from those visible from its mirror image above.
#include "gonio/material/material.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/ndf/ndf.h"
#include "sensor/beckers_sensor.h"

namespace gonio {

// A normal m (m.z > 0) with pdf proportional to max(0, v.m) D(m), for any unit v: the normals a
// path arriving from v sees (v.z > 0: Ndf::sample_visible; v.z <= 0: the facets' undersides).
Vec3 sample_visible_any(const Ndf& ndf, const Vec3& v, Rng& rng);

// settings.rays paths binned by order (settings.orders + 1 bins) on the upper sensor and, for a
// transmissive material, on the lower one; batches and blocks as the simulator's
// (gonio/trace/batched_run.h): the result does not depend on the thread count.
TraceResult smith_random_walk(const Ndf& ndf, const Material& material, const BeckersSensor& sensor,
                              const Vec3& wi, const TraceSettings& settings);

} // namespace gonio
