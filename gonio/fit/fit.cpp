#include "gonio/fit/fit.h"

#include "core/float_mode.h"
#include "core/random.h"
#include "gonio/fit/fit_problem.h"

#include <ceres/ceres.h>
#include <chrono>
#include <cmath>
#include <limits>

namespace gonio {

namespace {

// The loss's residuals for the data `data` (the case's, or a bootstrap replica's).
struct LossResiduals {
    const FitProblem* problem;
    const std::vector<double>* data;
    bool coarse;
    bool operator()(double const* const* p, double* residuals) const {
        problem->residuals(problem->predict(p[0], coarse), *data, residuals);
        return true;
    }
};

struct Solved {
    std::vector<double> p;
    double cost = std::numeric_limits<double>::infinity();
    bool converged = false;
    std::vector<double> covariance; // p x p, empty when Ceres could not compute it
};

Solved solve(const FitProblem& problem, const std::vector<double>& data,
             const std::vector<double>& start, bool coarse, bool covariance, double step) {
    const int n = int(problem.parameters().size());
    Solved s;
    s.p = start;
    ceres::NumericDiffOptions diff;
    diff.relative_step_size = step;
    auto* cost = new ceres::DynamicNumericDiffCostFunction<LossResiduals, ceres::CENTRAL>(
        new LossResiduals{&problem, &data, coarse}, ceres::TAKE_OWNERSHIP, diff);
    cost->AddParameterBlock(n);
    cost->SetNumResiduals(int(problem.residual_count()));
    ceres::Problem pb;
    pb.AddResidualBlock(cost, nullptr, s.p.data());
    for (int k = 0; k < n; ++k) {
        pb.SetParameterLowerBound(s.p.data(), k, problem.parameters()[size_t(k)].lower);
        pb.SetParameterUpperBound(s.p.data(), k, problem.parameters()[size_t(k)].upper);
    }
    ceres::Solver::Options o;
    o.linear_solver_type = ceres::DENSE_QR;
    o.max_num_iterations = 60;
    o.function_tolerance = 1e-10;
    o.parameter_tolerance = 1e-9;
    o.logging_type = ceres::SILENT;
    o.num_threads = 1; // the model's cells are evaluated in parallel already
    ceres::Solver::Summary summary;
    ceres::Solve(o, &pb, &summary);
    s.cost = summary.final_cost;
    s.converged = summary.termination_type == ceres::CONVERGENCE;
    if (covariance) {
        ceres::Covariance::Options co;
        co.algorithm_type = ceres::DENSE_SVD;
        co.null_space_rank = -1; // a parameter at its bound leaves J^T J singular: pseudo-inverse
        ceres::Covariance cov(co);
        std::vector<std::pair<const double*, const double*>> blocks{{s.p.data(), s.p.data()}};
        if (cov.Compute(blocks, &pb)) {
            s.covariance.assign(size_t(n * n), 0.0);
            cov.GetCovarianceBlock(s.p.data(), s.p.data(), s.covariance.data());
        }
    }
    return s;
}

// Starts spread over the roughness (log-spaced), every other parameter at its own start.
std::vector<std::vector<double>> starts(const FitProblem& problem) {
    std::vector<std::vector<double>> out;
    for (double a : {0.05, 0.25, 1.0}) {
        std::vector<double> p;
        for (const FitParameter& q : problem.parameters()) {
            const bool rough = q.name.rfind("alpha", 0) == 0;
            p.push_back(std::clamp(rough ? a : q.start, q.lower, q.upper));
        }
        out.push_back(p);
    }
    return out;
}

double gaussian(Rng& rng) { // Box-Muller
    const double u1 = 1 - rng.uniform(), u2 = rng.uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}

} // namespace

FitResult fit_result_case(const std::string& file, const FitOptions& options,
                          const std::function<void(int, int)>& progress) {
    const ResultFloatMode mode;
    const auto start_time = std::chrono::steady_clock::now();
    const ResultCase c = read_result_case(file, options.case_name);
    const FitProblem problem(c, options);
    const std::vector<std::vector<double>> from = starts(problem);
    const int replicas =
        problem.data_has_errors() && options.bootstrap > 0 ? std::max(2, options.bootstrap) : 0;
    const int total = int(from.size()) + replicas;
    // Common random numbers make a random walk's albedo piecewise constant at a fine scale:
    // differences over 1 % of a parameter see its slope, not its steps.
    const double step = options.with == FitWith::heitz16 ? 1e-2 : 1e-6;

    Solved best;
    int done = 0, converged = 0;
    for (const std::vector<double>& p0 : from) {
        Solved s = solve(problem, problem.data(), p0, true, false, step);
        converged += s.converged;
        if (s.cost < best.cost) best = std::move(s);
        if (progress) progress(++done, total);
    }
    // The best start polished at the full quadrature, with the covariance.
    best = solve(problem, problem.data(), best.p, false, true, step);

    FitResult r;
    r.file = file;
    r.case_name = c.name;
    r.family = options.family;
    r.data = problem.dataset();
    r.options = options;
    r.starts = int(from.size());
    r.converged = converged;
    for (const FitParameter& q : problem.parameters()) {
        r.names.push_back(q.name);
        r.lower.push_back(q.lower);
        r.upper.push_back(q.upper);
    }
    r.value = best.p;
    r.ndf_toml = problem.ndf_toml(best.p.data());
    const std::vector<double> m = problem.predict(best.p.data());
    const std::vector<double> z = problem.normalised(m);
    r.points = (long long)z.size();
    for (double v : z) r.chi2 += v * v;
    r.loss = 2 * best.cost;
    // Ceres' covariance is (J^T J)^-1: the parameters' covariance for normalised residuals
    // (chi2); for another loss, scaled by its residual variance.
    const size_t n = r.value.size();
    const double dof = double(r.points) - double(n);
    const double scale = options.loss == FitLoss::chi2 ? 1.0 : (dof > 0 ? r.loss / dof : 0.0);
    for (size_t k = 0; k < n; ++k)
        r.stderr_covariance.push_back(
            best.covariance.empty() ? std::numeric_limits<double>::quiet_NaN()
                                    : std::sqrt(std::max(0.0, best.covariance[k * n + k] * scale)));

    // Parametric bootstrap: the data redrawn cell by cell from their own errors (the batches
    // behind the file's standard errors are not in it), refitted from the optimum.
    if (replicas > 0) {
        std::vector<std::vector<double>> fits;
        for (int b = 0; b < replicas; ++b) {
            Rng rng{options.seed, 0x424f4f54 /* "BOOT" */, std::uint64_t(b), 0};
            std::vector<double> d = problem.data();
            for (size_t k = 0; k < d.size(); ++k) d[k] += problem.sigma()[k] * gaussian(rng);
            fits.push_back(solve(problem, d, best.p, false, false, step).p);
            if (progress) progress(++done, total);
        }
        for (size_t k = 0; k < n; ++k) {
            double mean = 0, ss = 0;
            for (const auto& f : fits) mean += f[k] / double(fits.size());
            for (const auto& f : fits) ss += (f[k] - mean) * (f[k] - mean);
            r.stderr_bootstrap.push_back(std::sqrt(ss / double(fits.size() - 1)));
        }
    }

    r.theta_i_deg = c.theta_i_deg;
    r.phi_i_deg = c.phi_i_deg;
    r.cells = c.cells;
    r.channels = c.channels;
    r.residual_map.assign(problem.map_size(), std::numeric_limits<double>::quiet_NaN());
    for (size_t k = 0; k < z.size(); ++k) r.residual_map[problem.map_index(k)] = z[k];
    r.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return r;
}

} // namespace gonio
