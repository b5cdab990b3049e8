#pragma once
// gonio masking as a library call: every case's surfaces (its ensemble, from the cache like a run)
// measured (masking_measurement.h), estimated against Smith (masking_estimates.h) and written to
// an HDF5 file, format "gonio-masking 1": one group per case, named dimensions as dimension
// scales (theta_o, phi_o, normal_bin, height_bin, theta_i, phi_i, g2_theta_o, g2_dphi), every
// dataset with units and long_name, checksummed and sealed like a result file.
#include "gonio/config/config.h"
#include "gonio/masking/masking_estimates.h"
#include "heightfield/surface_cache.h"

#include <functional>
#include <string>
#include <vector>

namespace gonio {

struct MaskingOptions {
    long long points = 1 << 17;    // per surface
    long long g2_points = 1 << 14; // of them, those G2 is measured on
    int normal_bins = 145;
    int height_bins = 8;
    int threads = 0;
    const SurfaceCache* cache = nullptr;
    std::function<void(const std::string& label, double fraction)> progress;
};

struct CaseMasking {
    std::string name, ndf, surface;
    MaskingEstimates estimates;
};

// The grid gonio masking uses for a case: theta_o 0-80 by 10, 85 and 89 degrees; one azimuth for
// an isotropic case, eight for an anisotropic one; G2 at the case's incidences, wo every 10
// degrees of polar angle (and theta_i itself) and every 30 degrees of azimuth from phi_i.
MaskingGrid masking_grid(const CaseConfig& c, const MaskingOptions& o);
// The same grid for any surface: G2 at these incidences (every pair), eight azimuths of w unless
// `isotropic`.
MaskingGrid masking_grid(const std::vector<double>& theta_i_deg,
                         const std::vector<double>& phi_i_deg, bool isotropic,
                         const MaskingOptions& o);

std::vector<CaseMasking> run_masking(const Config& cfg, const MaskingOptions& o);

void write_masking_file(const std::string& path, bool overwrite, const Config& cfg,
                        const std::string& command_line, const MaskingOptions& o,
                        const std::vector<CaseMasking>& cases);

} // namespace gonio
