#pragma once
// `gonio fit`: the analytic microfacet model whose parameters reproduce a case of a result file,
// found by Ceres Solver (bounded trust region, several starts), with the parameters' standard
// errors from Ceres' covariance and from a parametric bootstrap over the data's own errors.
//
// The data are the case's simulated cell averages (L1 or every order) with their standard errors
// (the surfaces' spread included for ensembles), or, for a `gonio model` file, one of its models.
// The model is Model L1 [R19 Eq. 2] with an NDF family of gonio's registry, optionally with a
// multiple-scattering model added (kulla_conty, turquin, heitz16), evaluated as cell averages on
// the same sensor (gonio/model/cell_integrator.h), so data and model are compared like for like.
#include "core/enum_names.h"
#include "gonio/table/result_case.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

// The fitting losses. chi2 is gonio's: sum ((f_data - f_model) / sigma)^2 over the cells. The
// others are the published metrics as the BSDF benchmark (bbm) states them for an (in, out)
// sample, on gonio's equal-area cells (a cell is a solid-angle element, so bbm's sin(theta_out)
// of a uniform (theta, phi) grid is the cells' own weight; Low's metrics, which sample theta_out
// uniformly, weight a cell by 1 / sin(theta_out)):
//   ngan       ((f_m - f_d) cos th_i)^2 sin th_i                       [Ngan et al. 2005]
//   low_l2     ((f_m - f_d) cos th_i)^2 sin th_i / sin th_o            [Low et al. 2012]
//   low_log    (ln(1 + f_m cos th_i) - ln(1 + f_d cos th_i))^2 sin th_i / sin th_o  [Low 2012]
//   bieron_l2  ((f_m - f_d) cos th_i)^2 sin th_i cos th_o              [Bieron & Peers 2020]
//   bieron_log (ln(1 + f_m cos th_i) - ln(1 + f_d cos th_i))^2 sin th_i cos th_o [Bieron 2020]
enum class FitLoss { chi2, ngan, low_l2, low_log, bieron_l2, bieron_log };
template <>
struct EnumNames<FitLoss> {
    static constexpr const char* what = "loss";
    static constexpr const char* names[] = {"chi2",    "ngan",      "low_l2",
                                            "low_log", "bieron_l2", "bieron_log"};
};

enum class FitOrders { l1, linf };
template <>
struct EnumNames<FitOrders> {
    static constexpr const char* what = "orders";
    static constexpr const char* names[] = {"l1", "linf"};
};

enum class FitWith { none, kulla_conty, turquin, heitz16 };
template <>
struct EnumNames<FitWith> {
    static constexpr const char* what = "multiple-scattering model";
    static constexpr const char* names[] = {"none", "kulla_conty", "turquin", "heitz16"};
};

enum class FitFresnel { fixed, fit };
template <>
struct EnumNames<FitFresnel> {
    static constexpr const char* what = "Fresnel";
    static constexpr const char* names[] = {"fixed", "fit"};
};

struct FitOptions {
    std::string case_name;    // empty: the file's only case
    std::string family;       // an NDF family with an `alpha` key (ggx, beckmann, student_t, ...)
    bool anisotropic = false; // alpha_x and alpha_y, not one alpha
    FitOrders orders = FitOrders::l1;
    FitWith with = FitWith::none;
    FitFresnel fresnel = FitFresnel::fixed; // fixed: the case's facets; fit: Schlick F0 per channel
    FitLoss loss = FitLoss::chi2;
    double max_theta_deg = 90; // incidences and cells beyond it are left out
    std::string reference;     // a `gonio model` case: the model fitted to (default: the first)
    int bootstrap = 16;        // replicas of the parametric bootstrap (0: none)
    long long walk_paths = 1 << 16; // heitz16: paths per incidence (common random numbers)
    std::uint64_t seed = 1;
};

struct FitResult {
    std::string file, case_name, family, data; // data: the dataset fitted to
    FitOptions options;
    std::vector<std::string> names; // the parameters
    std::vector<double> value, lower, upper;
    std::vector<double> stderr_covariance; // Ceres' covariance (scaled by chi2/dof unless chi2)
    std::vector<double> stderr_bootstrap;  // the bootstrap's (empty without one)
    double chi2 = 0;                       // sum of squared normalised residuals (d - m) / sigma
    long long points = 0;                  // cells x incidences x channels fitted
    double loss = 0;                       // the chosen loss at the optimum
    int starts = 0, converged = 0;
    std::string ndf_toml; // the fitted distribution as an [ndf] table
    // (d - m) / sigma per [theta_i][phi_i][cell][channel] of the case (NaN where left out).
    std::vector<double> residual_map;
    std::vector<double> theta_i_deg, phi_i_deg;
    int cells = 0, channels = 0;
    double seconds = 0;
    double chi2_per_dof() const {
        const long long dof = points - (long long)value.size();
        return dof > 0 ? chi2 / double(dof) : 0.0;
    }
};

// Fits the case of `file`. Throws std::runtime_error (a bad option for this case, a missing
// dataset) with the reason. `progress(done, total)` is told of the starts and replicas.
FitResult fit_result_case(const std::string& file, const FitOptions& options,
                          const std::function<void(int, int)>& progress = {});

// The fit as a renderer takes it: Mitsuba 3 XML (roughconductor / roughdielectric) and pbrt-v4
// Material lines, or a comment saying why there is none (a family they do not have).
std::string mitsuba_xml(const FitResult& r, const ResultCase& c);
std::string pbrt_material(const FitResult& r, const ResultCase& c);

// The fit as TOML (parameters, errors, renderer lines) or JSON (the same and the residual map).
void write_fit(const FitResult& r, const std::string& path);

} // namespace gonio
