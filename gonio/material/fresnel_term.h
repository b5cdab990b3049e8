#pragma once
// The Fresnel reflectance of one microfacet, per spectral channel: what the specular models and
// (later) the simulator's materials multiply a reflected ray by. Only as many channels as the
// material needs: a perfect mirror or a dielectric with one index is achromatic (one channel).
#include <complex>
#include <string>
#include <vector>

namespace gonio {

class FresnelTerm {
  public:
    enum class Kind { mirror, dielectric, conductor, schlick };

    static FresnelTerm mirror();
    static FresnelTerm dielectric(std::vector<double> eta);
    static FresnelTerm conductor(std::vector<std::complex<double>> eta);
    static FresnelTerm schlick(std::vector<double> f0);

    Kind kind() const { return kind_; }
    int channels() const { return channels_; }
    // The real relative index of channel c (dielectric only).
    double dielectric_eta(int c) const { return real_.at(size_t(c)); }
    // The complex relative index of channel c (conductor only).
    std::complex<double> conductor_eta(int c) const { return complex_.at(size_t(c)); }
    // The reflectance at normal incidence of channel c (Schlick only).
    double schlick_f0(int c) const { return real_.at(size_t(c)); }
    // Reflectance for cos_i = i.m in [0, 1], one value per channel into out[0..channels).
    void eval(double cos_i, double* out) const;
    // weight[c] *= reflectance of channel c: eval without a buffer (a traced ray's bounce, where
    // a buffer per bounce cost an allocation for more than 16 channels).
    void scale(double cos_i, double* weight) const;
    std::string describe() const;

  private:
    Kind kind_ = Kind::mirror;
    int channels_ = 1;
    std::vector<double> real_;
    std::vector<std::complex<double>> complex_;
    std::vector<double> conductor_u0_, conductor_w_; // n^2 - k^2 and 4 n^2 k^2 per channel
};

} // namespace gonio
