#pragma once
// An analytic BRDF that gonio can integrate over its sensor cells and hold against the simulated
// surface: Model L1 (the specular microfacet BRDF), the interfaced Lambertian model, Ashikhmin's
// generated BRDF, Chermain's P-BRDF. Directions are unit vectors with n = +z.
#include "core/math.h"

#include <cmath>
#include <vector>

namespace gonio {

// The half vector of reflection h = (i + o) / |i + o|; false when i or o is at or below the horizon
// (the model is then 0).
inline bool reflection_half_vector(const Vec3& i, const Vec3& o, Vec3& h) {
    const Vec3 s = i + o;
    const double len2 = dot(s, s);
    if (i.z <= 0 || o.z <= 0 || len2 <= 0) return false;
    h = s / std::sqrt(len2);
    return true;
}

class BrdfModel {
  public:
    virtual ~BrdfModel() = default;
    virtual int channels() const = 0;
    // f(i, o) cos(theta_o) per channel into out[0..channels): the integrand of the albedo, finite
    // up to the horizon; 0 when i or o is at or below it.
    virtual void eval_cosine(const Vec3& i, const Vec3& o, double* out) const = 0;
    // Angular widths (radians) of the narrowest and widest features of the lobe around the mirror
    // direction: the cell integrator refines down to the first within reach of the second.
    // Infinity: a smooth term with no lobe there (refined by its error estimate alone).
    virtual double narrowest_feature() const = 0;
    virtual double widest_feature() const = 0;
    // The terms whose sum the model is, each integrated over the cells on its own: a sharp
    // lobe and a smooth but costly term (the interfaced Lambertian body) are refined each as it
    // needs, not both as the sharper needs. By default the model is one term.
    virtual std::vector<const BrdfModel*> terms() const { return {this}; }

    // f(i, o) in sr^-1 per channel.
    void eval(const Vec3& i, const Vec3& o, double* f) const {
        eval_cosine(i, o, f);
        for (int c = 0; c < channels(); ++c) f[c] = o.z > 0 ? f[c] / o.z : 0.0;
    }
};

} // namespace gonio
