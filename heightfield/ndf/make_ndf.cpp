#include "heightfield/ndf/make_ndf.h"

#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/generalized_normal.h"
#include "heightfield/ndf/generalized_t.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/student_t.h"

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
    throw std::invalid_argument("unknown NDF type '" + spec.type + "'");
}

} // namespace gonio
