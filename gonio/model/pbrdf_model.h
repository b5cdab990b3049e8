#pragma once
// Chermain, Claux and Merillou's P-BRDF [C19]: the microsurface a normal map describes, as a
// mixture of non-centred anisotropic Beckmann lobes, one per texel (C19 section 3), seen through a
// footprint (section 4; for the gonioreflectometer the whole periodic patch, every lobe weighted
// alike):
//   D_P(m)   = sum_i W_i P22_i(m~) / cos^4 theta_m                      [C19 Eq. 2, 4, 9]
//   A_P(v)   = sum_i W_i <v, n_i> / (n_i . n)                           [C19 Eq. 17]
//   G1(v)    = A_P(v) / sum_i W_i int <v, m> D_i(m) dm = 1 / (1 + Lambda_P(v))  [C19 Eq. 11-15]
//   f_P(i,o) = F D_P(h) G1(i) G1(o) / (4 A_P(i) A_P(o))                 [C19 Eq. 7, 16]
// Each lobe's projected area int <v, m> D_i dm has a closed form: along v's azimuth the lobe's
// slopes s are N(mu, sigma^2), and with t = tan theta_v it is cos theta_v E[(1 - t s)_+] =
// cos theta_v ((1 - t mu) Phi(z) + t sigma phi(z)), z = (1 - t mu) / (t sigma).
// Slopes follow C19: m~ = (-m_x / m_z, -m_y / m_z), the height field's (p, q).
#include "gonio/material/fresnel_term.h"
#include "gonio/model/brdf_model.h"
#include "heightfield/heightfield.h"

#include <cstdint>
#include <vector>

namespace gonio {

// A non-centred anisotropic Beckmann lobe: a 2-D Gaussian of slopes [C19 Eq. 4].
struct SlopeLobe {
    double mx = 0, my = 0;            // mean slope
    double sxx = 0, syy = 0, sxy = 0; // covariance
};

// One lobe per sample of the surface's slope map (the forward differences p, q: the slopes of its
// triangles A, and of the normal map gonio writes), from the moments under a Gaussian weight k_i
// centred on the texel whose half maximum lies halfway to the next seed [C19 section 3.1, Eq. 5-6];
// the texels are constant, so the moments are exact sums over the 5 x 5 neighbourhood (weights from
// the normal CDF). Standard deviations below sigma_eps are raised to it [C19 section 3.2].
std::vector<SlopeLobe> fit_slope_lobes(const HeightField& surface, double sigma_eps = 0.01);

class PBrdfModel final : public BrdfModel {
  public:
    // The whole patch as footprint: W_i = 1 / a [C19 Eq. 9]. Tabulates the denominator of G1 over
    // the directions (theta_nodes x phi_nodes, bilinear); the exact sums stay available.
    PBrdfModel(std::vector<SlopeLobe> lobes, FresnelTerm fresnel, int theta_nodes = 181,
               int phi_nodes = 144);

    int channels() const override { return fresnel_.channels(); }
    void eval_cosine(const Vec3& i, const Vec3& o, double* out) const override;
    double narrowest_feature() const override { return narrow_; }
    double widest_feature() const override { return wide_; }

    double D(const Vec3& m) const;              // P-NDF [C19 Eq. 9]
    double projected_area(const Vec3& v) const; // A_P [C19 Eq. 17]
    double visible_area(const Vec3& v) const;   // sum_i W_i int <v, m> D_i dm, exact
    double lambda(const Vec3& v) const;         // Lambda_P [C19 Eq. 15], exact
    size_t lobe_count() const { return lobes_.size(); }

  private:
    double visible_area_table(const Vec3& v) const;
    void build_slope_grid();

    struct Lobe {
        SlopeLobe s;
        double ia, ib, ic, norm; // inverse covariance [[ia, ib], [ib, ic]], 1 / (2 pi sqrt(det))
    };
    std::vector<Lobe> lobes_;
    FresnelTerm fresnel_;
    double mean_x_ = 0, mean_y_ = 0; // sum W_i mu_i
    double narrow_ = 0, wide_ = 0;
    int theta_nodes_, phi_nodes_;
    std::vector<double> table_; // visible_area(v) / cos theta_v on the grid
    // The lobes that can reach each cell of a grid over slope space (D's culling, exact).
    double grid_x0_ = 0, grid_y0_ = 0, grid_x1_ = 0, grid_y1_ = 0, grid_sx_ = 1, grid_sy_ = 1;
    int grid_nx_ = 1, grid_ny_ = 1;
    bool grid_all_ = true;                  // no grid: D sums over every lobe
    std::vector<std::uint32_t> cell_start_; // cell c's lobes: cell_lobes_[start[c], start[c+1])
    std::vector<std::uint32_t> cell_lobes_;
};

} // namespace gonio
