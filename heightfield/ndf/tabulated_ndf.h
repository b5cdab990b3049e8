#pragma once
// A distribution given by a (theta, phi) table (heightfield/ndf/ndf_table.h), bilinear between the
// nodes and normalised exactly: measured NDFs and the facet NDF of a height map.
//
// - Normalisation: the phi-average of a bilinear table is linear in theta between rows, so
//   int D cos dw is the closed form of R19 Eq. 12 on the row means.
// - D cos sampling (and D sin, for visible normals): a cell by its exact mass, then in the cell
//   theta from the weight (sin^2 theta uniform for cos sin), phi uniform, accepted with the
//   bilinear value over the cell's largest corner: exact.
// - Lambda from the projected area I(o) = int <o.m> D dw [R19 Eq. 13] = o.M + int max(0, -o.m) D dw
//   with M = int m D dw: the second term (exactly 0 until o sees the table's support from behind,
//   so Lambda has no round-off near the pole) is, for each theta_m, a circular convolution of
//   D(theta_m, .) with max(0, -(a + b cos psi)), done on Fourier series (the piecewise-linear
//   rows' spectra by FFTW, damped by sinc^2; the kernel's in closed form on the split domain of
//   R19 Eq. 14), then Gauss-Legendre over theta_m. That term is tabulated on a fine
//   (theta_o, phi_o) grid and interpolated bicubically.
// - Visible normals: rejection from the envelope (cos theta_v cos theta_m + sin theta_v
//   sin theta_m) D >= <v.m> D, a mixture of D cos and D sin.
#include "heightfield/ndf/ndf.h"
#include "heightfield/ndf/ndf_table.h"

#include <string>
#include <vector>

namespace gonio {

class TabulatedNdf final : public Ndf {
  public:
    // source: where the table came from (file name), for describe(). Throws
    // std::invalid_argument if the table is zero everywhere.
    TabulatedNdf(NdfTable table, std::string source, std::string kind = "tabulated");

    double D(const Vec3& m) const override;
    double lambda(const Vec3& v) const override;
    Vec3 sample_m(double u1, double u2) const override;
    bool continuous_sampler() const override { return false; } // picks a part or rejects
    Vec3 sample_visible(const Vec3& v, double u1, double u2) const override;
    std::string name() const override { return kind_; }
    std::string describe() const override;
    double narrowest_feature() const override;
    double widest_feature() const override;

    const NdfTable& table() const { return t_; } // normalised

  private:
    // A normal with density proportional to D times w(theta) (cos sin if cos_weight, else sin^2),
    // using u1 for the cell and the rest from a stream keyed by (u1, u2).
    Vec3 sample_weighted(bool cos_weight, double u1, double u2) const;
    double bilinear(double theta, double phi) const;

    NdfTable t_;
    std::string source_, kind_;
    double dt_, dp_;
    std::vector<double> cdf_cos_, cdf_sin_; // cumulative cell masses, per cell j * phi_count + k
    double sin_mass_ = 0;                   // int D sin theta_m dw
    int it_, ip_;                           // I table: theta_o intervals, phi_o samples
    std::vector<double> projected_;         // back-facing part of I(theta_o, phi_o), row-major
    double mean_x_ = 0, mean_y_ = 0;        // x and y of M = int m D dw
};

} // namespace gonio
