#pragma once
// A reader of RGL measured-BSDF tensor files written in the tests from the format's specification
// (Dupuy & Jakob 2018; the layout and evaluation rule of Mitsuba 3's src/bsdfs/measured.cpp and
// pbrt-v4's MeasuredBxDF, summarised in docs/tabulated-bsdf.md): it parses the container
// itself and evaluates f cos = spectra(vndf^-1(u_m)) ndf(u_m) / (4 sigma(w_p)), samples through
// luminance then vndf, and returns the readers' pdf. Incidences must be swept ones (the slices are
// used as they are: no interpolation between parameter slices).
#include "core/math.h"
#include "gonio/export/piecewise_linear_2d.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio::test {

struct TensorField {
    int dtype = 0;
    std::vector<std::uint64_t> shape;
    std::vector<double> values; // every dtype as doubles
    std::string text() const { return std::string(values.begin(), values.end()); }
};

inline std::map<std::string, TensorField> read_tensor_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string bytes = ss.str();
    if (bytes.size() < 18 || std::memcmp(bytes.data(), "tensor_file\0", 12) != 0)
        throw std::runtime_error(path + ": not a tensor file");
    if (bytes[12] != 1 || bytes[13] != 0) throw std::runtime_error(path + ": version is not 1.0");
    size_t at = 14;
    auto take = [&](auto& v) {
        if (at + sizeof(v) > bytes.size()) throw std::runtime_error(path + ": truncated header");
        std::memcpy(&v, bytes.data() + at, sizeof(v)); // little-endian host (x86, ARM)
        at += sizeof(v);
    };
    std::uint32_t count = 0;
    take(count);
    std::map<std::string, TensorField> fields;
    for (std::uint32_t k = 0; k < count; ++k) {
        std::uint16_t name_length = 0, rank = 0;
        take(name_length);
        const std::string name = bytes.substr(at, name_length);
        at += name_length;
        take(rank);
        std::uint8_t dtype = 0;
        take(dtype);
        std::uint64_t offset = 0;
        take(offset);
        TensorField f;
        f.dtype = dtype;
        std::uint64_t n = 1;
        for (std::uint16_t r = 0; r < rank; ++r) {
            std::uint64_t s = 0;
            take(s);
            f.shape.push_back(s);
            n *= s;
        }
        const size_t size = dtype == 1 ? 1 : dtype == 10 ? 4 : 0;
        if (size == 0) throw std::runtime_error(path + ": " + name + " has an unexpected dtype");
        if (offset + n * size > bytes.size())
            throw std::runtime_error(path + ": " + name + " truncated");
        for (std::uint64_t e = 0; e < n; ++e) {
            if (dtype == 1) {
                f.values.push_back(static_cast<unsigned char>(bytes[offset + e]));
            } else {
                float v;
                std::memcpy(&v, bytes.data() + offset + e * 4, 4);
                f.values.push_back(v);
            }
        }
        fields[name] = std::move(f);
    }
    return fields;
}

class RglBsdf {
  public:
    explicit RglBsdf(const std::string& path) : fields_(read_tensor_file(path)) {
        const auto& theta = field("theta_i");
        const auto& phi = field("phi_i");
        theta_ = theta.values;
        phi_ = phi.values;
        isotropic_ = phi_.size() <= 2;
        spectral_ = fields_.count("wavelengths") > 0;
        const TensorField& values = field(spectral_ ? "spectra" : "rgb");
        channels_ = int(values.shape[2]);
        res_ = int(values.shape[3]);
        ndf_ = grid("ndf", 0, false);
        sigma_ = grid("sigma", 0, false);
    }
    bool isotropic() const { return isotropic_; }
    int channels() const { return channels_; }
    const TensorField& field(const std::string& name) const {
        const auto it = fields_.find(name);
        if (it == fields_.end()) throw std::runtime_error("tensor file has no field " + name);
        return it->second;
    }

    // f cos theta_q per channel at a swept incidence w_p.
    std::vector<double> eval(const Vec3& wp, const Vec3& wq) const {
        std::vector<double> out(size_t(channels_), 0.0);
        if (wp.z <= 0 || wq.z <= 0) return out;
        const Slice s = slice(wp);
        const Vec3 m = normalize(wp + wq);
        const PiecewiseLinear2D::Point um = u_of(m, s.phi_p);
        const auto sample = s.vndf.invert(um);
        const double factor = ndf_.eval(um) / (4 * sigma_.eval(u_p(wp)));
        for (int c = 0; c < channels_; ++c) out[c] = s.values[c].eval(sample) * factor;
        return out;
    }
    // The readers' sampling chain: luminance, then vndf, then the mirror direction.
    struct Sample {
        Vec3 wq;
        double pdf = 0;
        std::vector<double> weight; // f cos / pdf per channel (0 below the horizon)
    };
    Sample sample(const Vec3& wp, double u1, double u2) const {
        const Slice s = slice(wp);
        Sample out;
        out.weight.assign(size_t(channels_), 0.0);
        double lum_pdf = 0, vndf_pdf = 0;
        const auto sample = s.luminance.sample({u1, u2}, &lum_pdf);
        const auto um = s.vndf.sample(sample, &vndf_pdf);
        const double theta_m = um[0] * um[0] * kPi / 2;
        const double phi_m = (2 * um[1] - 1) * kPi + (isotropic_ ? s.phi_p : 0.0);
        const Vec3 m = spherical_direction(theta_m, phi_m);
        out.wq = reflect(wp, m);
        if (out.wq.z <= 0) return out;
        const double jac =
            std::max(2 * kPi * kPi * um[0] * std::sin(theta_m), 1e-6) * 4 * dot(wp, m);
        out.pdf = vndf_pdf * lum_pdf / jac;
        const double factor = ndf_.eval(um) / (4 * sigma_.eval(u_p(wp)));
        for (int c = 0; c < channels_; ++c)
            out.weight[c] = s.values[c].eval(sample) * factor / out.pdf;
        return out;
    }

  private:
    struct Slice {
        PiecewiseLinear2D vndf, luminance;
        std::vector<PiecewiseLinear2D> values;
        double phi_p;
    };
    PiecewiseLinear2D grid(const std::string& name, size_t slice, bool normalize) const {
        const TensorField& f = field(name);
        const size_t h = f.shape[f.shape.size() - 2], w = f.shape.back();
        std::vector<double> d(f.values.begin() + slice * w * h,
                              f.values.begin() + (slice + 1) * w * h);
        return PiecewiseLinear2D(d, int(w), int(h), normalize);
    }
    static PiecewiseLinear2D::Point u_p(const Vec3& w) {
        return {std::sqrt(spherical_theta(w) * 2 / kPi), (std::atan2(w.y, w.x) + kPi) / kTwoPi};
    }
    PiecewiseLinear2D::Point u_of(const Vec3& m, double phi_p) const {
        const double phi_m = std::atan2(m.y, m.x);
        double uy = ((isotropic_ ? phi_m - phi_p : phi_m) + kPi) / kTwoPi;
        uy -= std::floor(uy);
        return {std::sqrt(spherical_theta(m) * 2 / kPi), uy};
    }
    Slice slice(const Vec3& wp) const {
        const double theta = spherical_theta(wp), phi = std::atan2(wp.y, wp.x);
        size_t ti = theta_.size(), pj = 0;
        for (size_t k = 0; k < theta_.size(); ++k)
            if (std::abs(theta_[k] - theta) < 1e-5) ti = k;
        if (ti == theta_.size()) throw std::runtime_error("not a swept theta_i");
        if (!isotropic_) {
            pj = phi_.size();
            for (size_t k = 0; k < phi_.size(); ++k)
                if (std::abs(std::remainder(phi_[k] - phi, kTwoPi)) < 1e-5 || theta < 1e-9) {
                    pj = k;
                    break;
                }
            if (pj == phi_.size()) throw std::runtime_error("not a swept phi_i");
        }
        const size_t index = pj * theta_.size() + ti;
        Slice s{grid("vndf", index, true), grid("luminance", index, true), {}, phi};
        for (int c = 0; c < channels_; ++c)
            s.values.push_back(grid(spectral_ ? "spectra" : "rgb", index * channels_ + c, false));
        return s;
    }

    std::map<std::string, TensorField> fields_;
    std::vector<double> theta_, phi_;
    bool isotropic_ = true, spectral_ = true;
    int channels_ = 0, res_ = 0;
    PiecewiseLinear2D ndf_{std::vector<double>(4, 1.0), 2, 2, false};
    PiecewiseLinear2D sigma_{std::vector<double>(4, 1.0), 2, 2, false};
};

} // namespace gonio::test
