#include "heightfield/ndf/make_ndf.h"

#include "heightfield/exr_io.h"
#include "heightfield/ndf/anisotropic_blend.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/gaussian_angles.h"
#include "heightfield/ndf/generalized_normal.h"
#include "heightfield/ndf/generalized_t.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/mixture_ndf.h"
#include "heightfield/ndf/piecewise_linear.h"
#include "heightfield/ndf/sinc_ndf.h"
#include "heightfield/ndf/student_t.h"
#include "heightfield/ndf/tabulated_ndf.h"

#include <stdexcept>

namespace gonio {

std::unique_ptr<Ndf> make_ndf(const NdfSpec& spec) {
    if (spec.type == "beckmann") return std::make_unique<Beckmann>(spec.alpha_x, spec.alpha_y);
    if (spec.type == "ggx") return std::make_unique<Ggx>(spec.alpha_x, spec.alpha_y);
    if (spec.type == "student_t")
        return std::make_unique<StudentT>(spec.alpha_x, spec.alpha_y, spec.gamma);
    if (spec.type == "generalized_normal")
        return std::make_unique<GeneralizedNormal>(spec.alpha_x, spec.alpha_y, spec.p);
    if (spec.type == "generalized_t")
        return std::make_unique<GeneralizedT>(spec.alpha_x, spec.alpha_y, spec.p, spec.q);
    if (spec.type == "gaussian")
        return std::make_unique<GaussianAngles>(spec.sigma, spec.theta_max);
    if (spec.type == "sinc") return std::make_unique<SincNdf>(spec.k, spec.floor, spec.intervals);
    if (spec.type == "piecewise_linear") {
        if (spec.parts.empty())
            return std::make_unique<PiecewiseLinearNdf>(ControlPoints{spec.theta, spec.value});
        const auto source = make_ndf(spec.parts.at(0));
        return std::make_unique<PiecewiseLinearNdf>(
            PiecewiseLinearNdf::sampled_from(*source, spec.intervals), "piecewise_linear",
            "points=" + std::to_string(spec.intervals + 1) + " from " + source->describe());
    }
    if (spec.type == "blend") {
        if (spec.parts.size() != 2) throw std::invalid_argument("blend: needs the x and y curves");
        return std::make_unique<AnisotropicBlend>(make_ndf(spec.parts[0]), make_ndf(spec.parts[1]));
    }
    if (spec.type == "mixture") {
        std::vector<std::unique_ptr<Ndf>> parts;
        for (const NdfSpec& p : spec.parts) parts.push_back(make_ndf(p));
        return std::make_unique<MixtureNdf>(std::move(parts), spec.weights);
    }
    if (spec.type == "tabulated")
        return std::make_unique<TabulatedNdf>(read_ndf_table(spec.file), spec.file);
    if (spec.type == "height_map")
        return std::make_unique<TabulatedNdf>(
            facet_ndf_table(read_height_exr(spec.file), spec.theta_intervals, spec.phi_count),
            spec.file, "height_map");
    throw std::invalid_argument("unknown NDF type '" + spec.type + "'");
}

} // namespace gonio
