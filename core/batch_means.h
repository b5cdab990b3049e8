#pragma once
// Standard errors by batch means: an estimate that is the mean of B independent, identically
// distributed batch estimates x_b has the standard error sqrt(sum_b (x_b - mean)^2 / (B (B-1))),
// an unbiased variance estimate whatever the distribution of one ray's contribution. A statistic
// that is not linear in the batches (a distance between maps, a ratio) gets the delete-one
// jackknife's standard error (Efron & Stein 1981) instead.
#include <cmath>
#include <cstddef>
#include <vector>

namespace gonio {

// Batches stored [batch][n]: the n means.
inline std::vector<double> batch_mean(const std::vector<double>& batches, int B) {
    const size_t n = batches.size() / size_t(B);
    std::vector<double> mean(n, 0.0);
    for (int b = 0; b < B; ++b)
        for (size_t i = 0; i < n; ++i) mean[i] += batches[size_t(b) * n + i];
    for (double& m : mean) m /= B;
    return mean;
}

// The standard error of the mean of value(b), b = 0..B-1 (0 for one batch: nothing to say).
template <class Value>
double batch_stderr(int B, const Value& value) {
    if (B < 2) return 0.0;
    std::vector<double> x(static_cast<size_t>(B)); // each batch's value once: it may be a sum
    double mean = 0;
    for (int b = 0; b < B; ++b) mean += (x[size_t(b)] = value(b));
    mean /= B;
    double ss = 0;
    for (double v : x) ss += (v - mean) * (v - mean);
    return std::sqrt(ss / (double(B) * double(B - 1)));
}

// Element-wise standard errors of batches stored [batch][n]: what batch_stderr(B, value) gives
// for each element, the same sums in the same order, taken a batch row at a time (in cache).
inline std::vector<double> batch_stderr(const std::vector<double>& batches, int B) {
    const size_t n = batches.size() / size_t(B);
    if (B < 2) return std::vector<double>(n, 0.0);
    const std::vector<double> mean = batch_mean(batches, B);
    std::vector<double> ss(n, 0.0);
    for (int b = 0; b < B; ++b)
        for (size_t i = 0; i < n; ++i) {
            const double v = batches[size_t(b) * n + i] - mean[i];
            ss[i] += v * v;
        }
    for (double& e : ss) e = std::sqrt(e / (double(B) * double(B - 1)));
    return ss;
}

// Batches stored [batch][order][n]: per batch, the sum of orders from..to-1, stored [batch][n]
// (L1, L2+, every order; of maps or of albedos).
inline std::vector<double> sum_orders(const std::vector<double>& batches, int B, int orders,
                                      int from, int to) {
    const size_t n = batches.size() / (size_t(B) * size_t(orders));
    std::vector<double> out(size_t(B) * n, 0.0);
    for (size_t b = 0; b < size_t(B); ++b)
        for (size_t o = size_t(from); o < size_t(to); ++o)
            for (size_t i = 0; i < n; ++i)
                out[b * n + i] += batches[(b * size_t(orders) + o) * n + i];
    return out;
}

// The jackknife standard error of a statistic: without(b) is the statistic computed from every
// batch but b.
template <class Without>
double jackknife_stderr(int B, const Without& without) {
    if (B < 2) return 0.0;
    std::vector<double> t(size_t(B), 0.0);
    double mean = 0;
    for (int b = 0; b < B; ++b) mean += (t[size_t(b)] = without(b));
    mean /= B;
    double ss = 0;
    for (double v : t) ss += (v - mean) * (v - mean);
    return std::sqrt(ss * double(B - 1) / double(B));
}

// The mean of every batch but `without`, from the mean of all and that batch's value.
inline double mean_without(double mean, double batch, int B) {
    return (double(B) * mean - batch) / double(B - 1);
}

} // namespace gonio
