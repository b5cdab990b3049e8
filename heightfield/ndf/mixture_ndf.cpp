#include "heightfield/ndf/mixture_ndf.h"

#include "core/check.h"
#include "core/number_text.h"
#include "heightfield/ndf/ndf_family.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
// Index chosen by u among `w` (summing to total), and u rescaled to [0, 1) within its share.
size_t pick(const std::vector<double>& w, double total, double& u) {
    double x = u * total;
    for (size_t k = 0; k + 1 < w.size(); ++k) {
        if (x < w[k]) {
            u = std::min(x / w[k], std::nextafter(1.0, 0.0));
            return k;
        }
        x -= w[k];
    }
    u = std::clamp(x / w.back(), 0.0, std::nextafter(1.0, 0.0));
    return w.size() - 1;
}
} // namespace

MixtureNdf::MixtureNdf(std::vector<std::unique_ptr<Ndf>> components, std::vector<double> weights)
    : components_(std::move(components)), weights_(std::move(weights)) {
    // The keys components and weights, checked where they are read.
    GONIO_DCHECK(!components_.empty() && weights_.size() == components_.size());
    double total = 0;
    for (double w : weights_) {
        GONIO_DCHECK(w > 0 && std::isfinite(w));
        total += w;
    }
    for (double& w : weights_) w /= total;
    for (const auto& c : components_) GONIO_CHECK(c);
}

double MixtureNdf::D(const Vec3& m) const {
    double d = 0;
    for (size_t k = 0; k < components_.size(); ++k) d += weights_[k] * components_[k]->D(m);
    return d;
}

double MixtureNdf::lambda(const Vec3& v) const {
    double area = 0; // I(v) / cos theta_v = 1 + Lambda [R19 section 3.1]
    for (size_t k = 0; k < components_.size(); ++k) {
        const double l = components_[k]->lambda(v);
        if (std::isinf(l)) return std::numeric_limits<double>::infinity();
        area += weights_[k] * (1 + l);
    }
    return std::max(0.0, area - 1.0);
}

Vec3 MixtureNdf::sample_m(double u1, double u2) const {
    const size_t k = pick(weights_, 1.0, u1);
    return components_[k]->sample_m(u1, u2);
}

Vec3 MixtureNdf::sample_visible(const Vec3& v, double u1, double u2) const {
    std::vector<double> share(components_.size());
    double total = 0;
    for (size_t k = 0; k < components_.size(); ++k)
        total += share[k] = weights_[k] * (1 + components_[k]->lambda(v));
    const size_t k = pick(share, total, u1);
    return components_[k]->sample_visible(v, u1, u2);
}

std::string MixtureNdf::describe() const {
    std::ostringstream s;
    s << "mixture(";
    for (size_t k = 0; k < components_.size(); ++k)
        s << (k ? "; " : "") << shortest(weights_[k]) << " x " << components_[k]->describe();
    s << ")";
    return s.str();
}

double MixtureNdf::narrowest_feature() const {
    double n = std::numeric_limits<double>::infinity();
    for (const auto& c : components_) n = std::min(n, c->narrowest_feature());
    return n;
}

double MixtureNdf::widest_feature() const {
    double w = 0;
    for (const auto& c : components_) w = std::max(w, c->widest_feature());
    return w;
}

} // namespace gonio

namespace gonio {
namespace {
const Key kComponents = Key::tables("components", "the distributions mixed, Σ w_k D_k");
const Key kWeights =
    Key::numbers("weights", {0, 1e300, true, false}, "one per component, normalised")
        .note_default("equal");
} // namespace
const NdfFamily& mixture_family() {
    static const NdfFamily f{"mixture",
                             "weighted mixture of distributions",
                             {kComponents, kWeights},
                             [](TableReader& r, int depth) -> std::unique_ptr<Ndf> {
                                 std::vector<std::unique_ptr<Ndf>> parts;
                                 for (TableReader& part : r.table_list(kComponents))
                                     parts.push_back(read_ndf(part, depth + 1));
                                 std::vector<double> weights(parts.size(), 1.0);
                                 if (r.has(kWeights.name)) weights = r.number_list(kWeights);
                                 if (weights.size() != parts.size())
                                     r.fail("weights", "has " + std::to_string(weights.size()) +
                                                           " values; give one per component (" +
                                                           std::to_string(parts.size()) + ")");
                                 return std::make_unique<MixtureNdf>(std::move(parts), weights);
                             }};
    return f;
}
} // namespace gonio
