#pragma once
// Builds a distribution from its validated description (the config's [ndf] table).
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <string>

namespace gonio {

struct NdfSpec {
    std::string type = "beckmann"; // "beckmann" | "ggx"
    double alpha_x = 0.5;
    double alpha_y = 0.5;
};

std::unique_ptr<Ndf> make_ndf(const NdfSpec& spec);

} // namespace gonio
