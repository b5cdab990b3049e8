#pragma once
// The models a case asks for ([model] models), built once per case and evaluated on the sensor
// cells at each incidence of its sweep. Each result says which simulated quantity it is held
// against: single scattering (L1) or every order (L-infinity).
#include "gonio/config/config.h"
#include "gonio/io/model_result.h"
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
