#pragma once
// Builds a distribution from its validated description (the config's [ndf] table).
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <string>

namespace gonio {

struct NdfSpec {
    // "beckmann" | "ggx" | "student_t" | "generalized_normal" | "generalized_t"
    std::string type = "beckmann";
    double alpha_x = 0.5;
    double alpha_y = 0.5;
    double gamma = 2; // student_t
    double p = 2;     // generalized_normal, generalized_t
    double q = 1;     // generalized_t
};

std::unique_ptr<Ndf> make_ndf(const NdfSpec& spec);

} // namespace gonio
