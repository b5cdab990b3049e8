#pragma once
// Light from every direction: a latitude-longitude radiance map (z up; column u = phi / 2 pi from
// +x counter-clockwise, row v = theta / pi from +z), looked up per texel and importance-sampled
// texel by texel in proportion to luminance x sin theta (the map's own pdf, exact for what eval
// returns). The uniform environment and the analytic sky are made as such maps, so every light
// source is sampled the same way.
#include "core/math.h"
#include "gonio/render/image.h"

#include <array>
#include <string>
#include <vector>

namespace gonio {

using Rgb = std::array<double, 3>;

class Environment {
  public:
    explicit Environment(Image map); // linear radiance; throws on an empty map
    static Environment uniform(double radiance);
    // The CIE standard overcast sky, L(theta) = L_z (1 + 2 cos theta) / 3 above the horizon
    // [Moon & Spencer 1942, CIE S 011/E:2003 type 1], L_z = 1, and a dark grey ground below.
    static Environment overcast_sky();
    static Environment from_exr(const std::string& path);
    // "uniform" (radiance 1), "sky" (overcast_sky), or else a lat-long EXR map's path.
    static Environment named(const std::string& name_or_path);

    Rgb radiance(const Vec3& d) const;
    // A direction with its solid-angle pdf, from two uniforms.
    Vec3 sample(double u1, double u2, double& pdf) const;
    double pdf(const Vec3& d) const;

  private:
    void texel(const Vec3& d, int& x, int& y) const;
    Image map_;
    std::vector<double> row_cdf_;    // [height + 1]
    std::vector<double> column_cdf_; // [height][width + 1]
    std::vector<double> texel_p_;    // [height][width]: probability of the texel
};

} // namespace gonio
