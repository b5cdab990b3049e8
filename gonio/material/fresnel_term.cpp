#include "gonio/material/fresnel_term.h"

#include "gonio/material/fresnel.h"

#include <algorithm>
#include <sstream>

namespace gonio {

namespace {
// Compiled for AVX2 as well and chosen at run time (GCC's function multi-versioning): the same
// IEEE operations in wider lanes, so the same bits. (No FMA: it would round differently.)
__attribute__((target_clones("avx2", "default"))) void
scale_conductor(double c, double s2, const double* u0, const double* w, int channels,
                double* weight) {
    for (int k = 0; k < channels; ++k) weight[k] *= fresnel_conductor(c, s2, u0[k], w[k]);
}
} // namespace

FresnelTerm FresnelTerm::mirror() {
    return FresnelTerm();
}

FresnelTerm FresnelTerm::dielectric(std::vector<double> eta) {
    FresnelTerm f;
    f.kind_ = Kind::dielectric;
    f.channels_ = static_cast<int>(eta.size());
    f.real_ = std::move(eta);
    return f;
}

FresnelTerm FresnelTerm::conductor(std::vector<std::complex<double>> eta) {
    FresnelTerm f;
    f.kind_ = Kind::conductor;
    f.channels_ = static_cast<int>(eta.size());
    f.complex_ = std::move(eta);
    for (const std::complex<double>& e : f.complex_) {
        const double n = e.real(), k = e.imag();
        f.conductor_u0_.push_back(n * n - k * k), f.conductor_w_.push_back(4.0 * n * n * k * k);
    }
    return f;
}

FresnelTerm FresnelTerm::schlick(std::vector<double> f0) {
    FresnelTerm f;
    f.kind_ = Kind::schlick;
    f.channels_ = static_cast<int>(f0.size());
    f.real_ = std::move(f0);
    return f;
}

void FresnelTerm::eval(double cos_i, double* out) const {
    switch (kind_) {
    case Kind::mirror:
        out[0] = 1.0;
        return;
    case Kind::dielectric:
        for (int c = 0; c < channels_; ++c) out[c] = fresnel_dielectric(cos_i, real_[c]);
        return;
    case Kind::conductor:
        for (int c = 0; c < channels_; ++c) out[c] = fresnel_conductor(cos_i, complex_[c]);
        return;
    case Kind::schlick:
        for (int c = 0; c < channels_; ++c) out[c] = fresnel_schlick(cos_i, real_[c]);
        return;
    }
}

void FresnelTerm::scale(double cos_i, double* weight) const {
    switch (kind_) {
    case Kind::mirror:
        return;
    case Kind::dielectric:
        for (int c = 0; c < channels_; ++c) weight[c] *= fresnel_dielectric(cos_i, real_[c]);
        return;
    case Kind::conductor: {
        // One loop the compiler vectorises: the index's terms precomputed, the angle's hoisted.
        const double c = std::clamp(cos_i, 0.0, 1.0), s2 = 1.0 - c * c;
        if (c == 0.0) return; // grazing: every conductor reflects all
        scale_conductor(c, s2, conductor_u0_.data(), conductor_w_.data(), channels_, weight);
        return;
    }
    case Kind::schlick:
        for (int c = 0; c < channels_; ++c) weight[c] *= fresnel_schlick(cos_i, real_[c]);
        return;
    }
}

std::string FresnelTerm::describe() const {
    std::ostringstream s;
    s.precision(10);
    switch (kind_) {
    case Kind::mirror:
        return "mirror(F=1)";
    case Kind::dielectric:
        s << "dielectric(eta=";
        break;
    case Kind::schlick:
        s << "schlick(f0=";
        break;
    case Kind::conductor:
        s << "conductor(eta=";
        break;
    }
    for (int c = 0; c < channels_; ++c) {
        if (c) s << ", ";
        if (kind_ == Kind::conductor)
            s << complex_[c].real() << "+" << complex_[c].imag() << "i";
        else
            s << real_[c];
    }
    s << ")";
    return s.str();
}

} // namespace gonio
