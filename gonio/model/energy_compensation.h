#pragma once
// What renderers add to the single-scattering microfacet BRDF for the energy it loses, both built
// from E(mu), the directional albedo of Model L1 with white facets (F = 1):
//   - Kulla & Conty 2017 (Revisiting Physically Based Shading at Imageworks, "energy
//     compensation"): a lobe f_ms = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)), E_avg =
//     2 int E(mu) mu dmu, scaled for coloured facets by F_ms = F_avg^2 E_avg / (1 - F_avg (1 -
//     E_avg)), F_avg = 2 int F(mu) mu dmu;
//   - Turquin 2019 (Practical multiple scattering compensation for microfacet models):
//     f_ss scaled by 1 + F0 (1 - E) / E, E at the direction held fixed (gonio's incidence; a
//     renderer's view direction), F0 the facets' reflectance at normal incidence.
// E comes from Smith's model for the case's NDF, or (as an option) from the explicit surface: the
// single-scattering albedo its traced facets give with a perfect mirror.
#include "gonio/material/fresnel_term.h"
#include "gonio/model/cell_model.h"
#include "gonio/trace/trace_backend.h"
#include "heightfield/heightfield.h"
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <vector>

namespace gonio {

// E(mu) on nodes theta_k = k pi / (2 (n - 1)), k = 0 .. n - 1, averaged over the azimuth (both
// compensations assume an isotropic E; an anisotropic NDF gives its azimuthal mean).
struct AlbedoTable {
    std::vector<double> e; // E at the nodes
    double average = 0;    // E_avg = 2 int E(mu) mu dmu over the interpolant
    // Cubic (Catmull-Rom) in theta between the nodes.
    double at(double mu) const;

    static constexpr int kNodes = 91; // one degree apart
    // Smith's: Model L1 with F = 1 and the case's masking, integrated over the cells of a
    // 577-cell sensor at each node.
    static AlbedoTable smith(const Ndf& ndf, MaskingForm masking, const CellQuadrature& q);
    // The explicit surface's: order-1 reflected albedo of the surface traced with a perfect
    // mirror, `rays` per node over four azimuths, on fixed random streams.
    static AlbedoTable surface(const HeightField& surface, const TraceBackendKind& backend,
                               long long rays);
    // The table of E at the nodes (kNodes values) and its average.
    static AlbedoTable of_nodes(std::vector<double> e);

  private:
    std::vector<double> padded_; // e with a ghost node in front (theta = -step, mirroring node 1)
};

// F_avg = 2 int F(mu) mu dmu per channel (Gauss-Legendre, 64 points).
std::vector<double> average_fresnel(const FresnelTerm& fresnel);

enum class Compensation { kulla_conty, turquin };

// Model L1 plus a compensation, as a model of every order that knows its single scattering.
std::unique_ptr<CellModel> compensated_model(Compensation kind, std::shared_ptr<const Ndf> ndf,
                                             const FresnelTerm& fresnel, MaskingForm masking,
                                             const CellQuadrature& quadrature,
                                             std::shared_ptr<const AlbedoTable> albedo);

} // namespace gonio
