#pragma once
// The models a case asks for ([model] models), built once per case and evaluated on the sensor
// cells at each incidence of its sweep. Each result says which simulated quantity it is held
// against: single scattering (L1) or every order (L-infinity).
#include "core/named_array.h"
#include "gonio/config/config.h"
#include "gonio/model/brdf_model.h"
#include "gonio/model/model_comparison.h"
#include "heightfield/heightfield.h"
#include "heightfield/ndf/ndf.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

// One model over a case's sweep: arrays over theta_i, phi_i (theta_i major), cell and channel.
struct ModelResult {
    std::string name;          // "l1", "il", "vcavity", "ashikhmin", "pbrdf"
    std::string compared_with; // "l1" or "linf": the simulated BRDF it models
    std::string description;
    Array brdf;    // [theta_i, phi_i, cell, channel], 1/sr: cell averages
    Array energy;  // [theta_i, phi_i, cell, channel]: fraction of the incident power
    Array albedo;  // [theta_i, phi_i, channel]
    Array seconds; // [theta_i, phi_i]
    // Monte Carlo models (the V-cavity): standard errors of brdf and albedo (batch means), the
    // single-scattering part and the albedos of order 1, 2 and 2 and up.
    Array brdf_stderr, albedo_stderr;
    Array l1, l1_albedo, l2_albedo, l2plus_albedo;
};

class CaseModels {
  public:
    // Keeps references to c and ndf. Builds the analytic models (Ashikhmin's tables take seconds);
    // the P-BRDF is fitted to `surface`, which it needs (c.needs_surface()).
    CaseModels(const CaseConfig& c, const Ndf& ndf, const HeightField* surface = nullptr);
    ~CaseModels();
    // Evaluates every model at the sweep's next incidence wi (theta_i major, as the config lists
    // them) and stores it in results(); the V-cavity paths use (seed, stream) for their random
    // streams. Returns the albedos, [model][channel].
    std::vector<std::vector<double>> evaluate(const Vec3& wi, const BeckersSensor& sensor,
                                              std::uint64_t seed, std::uint64_t stream);
    const std::vector<ModelResult>& results() const { return results_; }
    // Model k at the incidence last evaluated, for compare_model().
    const ModelMap& last(size_t k) const { return last_[k]; }

  private:
    const CaseConfig& c_;
    const Ndf& ndf_;
    std::vector<std::unique_ptr<BrdfModel>> analytic_; // per model; null for the V-cavity
    std::unique_ptr<class Material> facet_;            // the V-cavity's facets
    std::vector<ModelResult> results_;
    std::vector<ModelMap> last_;
    size_t evaluated_ = 0; // incidences so far
};

} // namespace gonio
