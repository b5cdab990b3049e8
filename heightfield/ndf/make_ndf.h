#pragma once
// Builds a distribution from its validated description (the config's [ndf] table).
#include <memory>
#include <string>

#include "heightfield/ndf/ndf.h"

namespace gonio {

struct NdfSpec {
    std::string type = "beckmann"; // "beckmann" | "ggx"
    double alpha_x = 0.5;
    double alpha_y = 0.5;
};

std::unique_ptr<Ndf> make_ndf(const NdfSpec& spec);

} // namespace gonio
