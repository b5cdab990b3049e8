#pragma once
// Multiple scattering in V-cavities, estimated on the sensor [M18 section 3.3, Eq. 23-24]: the
// microsurface is taken as V-grooves, each made of a facet m and its mirror image
// m' = (-m_x, -m_y, m_z) about the normal, whose cross-section lies in m's azimuthal plane and
// whose openings tile the mean plane. A groove is chosen with the macro-area it covers (m with pdf
// D(m) m.n), the beam enters its opening at a uniform point, and the path is followed in the
// groove's cross-section, with the facets' own scattering (the simulator's materials), until it
// leaves through the opening; its exit direction is binned per bounce order like the simulator's.
// Single scattering in a V-groove is exactly the microfacet BRDF with Torrance-Sparrow's G
// [M18 Eq. 15]: f1 is that model, f2, f3, ... are what V-cavities add.
//
// The groove pairs m with m', so D is taken as symmetric under phi -> phi + pi (every analytic
// NDF of gonio is); opaque materials only.
#include "gonio/material/material.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/ndf/ndf.h"
#include "sensor/beckers_sensor.h"

namespace gonio {

// settings.rays paths (rounded up to a multiple of settings.batches), in batches and blocks with
// their own random streams, merged in block order (gonio/trace/batched_run.h): the result does not
// depend on the thread count. Throws std::invalid_argument for a transmissive material.
TraceResult vcavity_estimate(const Ndf& ndf, const Material& material, const BeckersSensor& sensor,
                             const Vec3& wi, const TraceSettings& settings);

} // namespace gonio
