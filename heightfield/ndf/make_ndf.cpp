#include "heightfield/ndf/make_ndf.h"

#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <stdexcept>

namespace gonio {

std::unique_ptr<Ndf> make_ndf(const NdfSpec& spec) {
    if (spec.type == "beckmann") return std::make_unique<Beckmann>(spec.alpha_x, spec.alpha_y);
    if (spec.type == "ggx") return std::make_unique<Ggx>(spec.alpha_x, spec.alpha_y);
    throw std::invalid_argument("unknown NDF type '" + spec.type + "'");
}

} // namespace gonio
