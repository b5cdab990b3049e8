#include "gonio/material/fresnel_term.h"

#include "gonio/material/fresnel.h"

#include <sstream>

namespace gonio {

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
    case Kind::conductor:
        for (int c = 0; c < channels_; ++c) weight[c] *= fresnel_conductor(cos_i, complex_[c]);
        return;
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
