#pragma once
// A gonio run as described by a TOML file: the cases, each with its NDF, material, spectral
// channels, incidence sweep, sensor and model settings. load_config validates everything before
// any work starts; the README's "Configuration" section is the manual of every key.
#include "gonio/material/fresnel_term.h"
#include "gonio/model/ashikhmin_model.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/trace/accuracy_target.h"
#include "heightfield/ndf/make_ndf.h"
#include "heightfield/surface_spec.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

struct CaseConfig {
    std::string name;
    NdfSpec ndf;
    std::string material_type;   // "mirror" | "dielectric" | "conductor" | "schlick"
    std::string material_source; // where the optical constants came from (table path), or ""
    FresnelTerm fresnel;         // specular facets
    std::vector<double> albedo;  // lambertian and interfaced_lambertian facets: K_d per channel
    std::vector<double> interface_eta; // interfaced_lambertian: n_i per channel (or one)
    bool diffuse() const {
        return material_type == "lambertian" || material_type == "interfaced_lambertian";
    }
    int channels() const {
        if (material_type == "interfaced_lambertian")
            return int(std::max(albedo.size(), interface_eta.size()));
        return material_type == "lambertian" ? int(albedo.size()) : fresnel.channels();
    }
    std::string material_description() const;
    std::vector<double> wavelengths_nm; // one per channel; empty when the material is achromatic
    std::vector<double> theta_i_deg;    // incidence sweep, each in [0, 90)
    std::vector<double> phi_i_deg;      // each in [0, 360]
    int sensor_cells = 3240;
    MaskingForm masking = MaskingForm::height_correlated;
    CellQuadrature quadrature;
    SurfaceSpec surface; // [surface]: how the microsurface is made (defaults if absent)
    // [trace]: the simulation.
    long long rays = 1 << 20; // per incidence
    int orders = 10;          // bounce orders stored separately (then one overflow order)
    int max_bounces = 1000;   // rays still bouncing then are cut (ledger: capped); 1 = L1 only
    int batches = 32;         // independent batches of the beam, for the standard errors
    AccuracyTarget target;    // target_error etc.: rounds of `rays` until met or out of budget
    // [model]: the models evaluated on the sensor cells, by name: "l1" (Model L1, the specular
    // microfacet BRDF), "il" (interfaced Lambertian, M18), "vcavity" (V-cavity multiple
    // scattering, M18), "ashikhmin" (A00), "pbrdf" (C19, fitted to the traced surface's slopes).
    // Empty with evaluate = false.
    std::vector<std::string> models;
    int body_points = 32;       // il: Gauss-Legendre nodes per axis of the body integral
    long long vcavity_rays = 0; // vcavity: paths per incidence (default: trace.rays)
    std::string ashikhmin_distribution = "ndf"; // "ndf" | "satin" | "velvet"
    double ashikhmin_sigma = 0.5;               // velvet's width [A00 Eq. 35]
    AshikhminSettings ashikhmin;
    double pbrdf_sigma_eps = 0.01; // C19's floor on the lobes' slope deviations
    bool needs_surface() const {
        return std::find(models.begin(), models.end(), "pbrdf") != models.end();
    }
};

struct Config {
    std::string path;                   // the config file as given
    std::string text;                   // its text, as read
    std::vector<std::string> overrides; // --set assignments, in order
    std::string effective_toml;         // the document after overrides, re-serialised
    std::uint64_t seed = 1;
    std::vector<CaseConfig> cases;
};

// Reads, applies `overrides` ("key.path=value"), validates. Throws ConfigError.
Config load_config(const std::string& path, const std::vector<std::string>& overrides = {});
// The same from a string (tests); `path` is only used in messages.
Config parse_config(const std::string& text, const std::string& path,
                    const std::vector<std::string>& overrides = {});

const char* masking_name(MaskingForm form);

} // namespace gonio
