#pragma once
// What `gonio fit` minimises: the case's data (cell averages with their standard errors, on the
// included incidences and cells), the model's parameters with their bounds, the model's cell
// averages for a parameter vector, and the residuals of each loss (gonio/fit/fit.h).
#include "gonio/fit/fit.h"
#include "heightfield/ndf/ndf_family.h"
#include "sensor/beckers_sensor.h"

#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct FitParameter {
    std::string name; // alpha, alpha_x, alpha_y, a family key (gamma, p, ...), f0 or f0_<nm>
    double lower = 0, upper = 0, start = 0;
};

class FitProblem {
  public:
    // Throws std::runtime_error naming what does not fit the case (a family without `alpha`,
    // diffuse facets, --with and --orders l1, no incidence left by --max-theta, ...).
    FitProblem(const ResultCase& c, const FitOptions& options);

    const std::vector<FitParameter>& parameters() const { return params_; }
    size_t residual_count() const { return index_.size(); }
    const std::string& dataset() const { return dataset_; }
    bool data_has_errors() const { return has_errors_; }
    const std::vector<double>& data() const { return data_; }   // per residual
    const std::vector<double>& sigma() const { return sigma_; } // per residual

    // The model's cell averages (1/sr) per residual, for parameters p (clamped to their bounds:
    // numerical derivatives may step past them). `coarse`: the cells at a relative tolerance of
    // 1e-3, for the search from several starts (the polish and every reported figure use 1e-5).
    std::vector<double> predict(const double* p, bool coarse = false) const;
    // The residuals of the chosen loss for model values m against data d.
    void residuals(const std::vector<double>& m, const std::vector<double>& d, double* out) const;
    // (d - m) / sigma per residual.
    std::vector<double> normalised(const std::vector<double>& m) const;
    // Where residual k sits in the case's [theta_i][phi_i][cell][channel] maps.
    size_t map_index(size_t k) const { return index_[k]; }
    size_t map_size() const { return map_size_; }
    // The fitted distribution as an [ndf] table, for parameters p.
    std::string ndf_toml(const double* p) const;

  private:
    std::vector<double> clamped(const double* p) const;

    const ResultCase& c_;
    FitOptions o_;
    BeckersSensor sensor_;
    std::vector<FitParameter> params_;
    std::vector<std::string> extra_keys_; // family keys fitted beside the roughness
    std::vector<std::string> fixed_keys_; // "key = value" lines of the family's other keys
    int first_f0_ = -1;                   // index of the first F0 parameter, or -1
    std::vector<size_t> incidences_;      // theta_i-major indices of the included incidences
    std::vector<double> data_, sigma_, weight_, cos_i_;
    std::vector<size_t> index_; // per residual: its place in the case's maps
    size_t map_size_ = 0;
    std::string dataset_;
    bool has_errors_ = false;
};

} // namespace gonio
