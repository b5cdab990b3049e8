#include "gonio/material/facet_materials.h"

#include "gonio/material/interfaced_lambertian.h"

namespace gonio {

std::vector<std::unique_ptr<Material>> facet_materials(const CaseConfig& c) {
    std::vector<std::unique_ptr<Material>> parts;
    if (c.material_type == "lambertian")
        parts.push_back(std::make_unique<LambertianFacet>(c.albedo));
    else if (c.material_type == "interfaced_lambertian")
        parts.push_back(std::make_unique<InterfacedLambertianFacet>(c.interface_eta, c.albedo));
    else if (c.material_type == "dielectric")
        for (int k = 0; k < c.fresnel.channels(); ++k)
            parts.push_back(std::make_unique<DielectricFacet>(c.fresnel.dielectric_eta(k)));
    else
        parts.push_back(std::make_unique<SpecularReflector>(c.fresnel));
    return parts;
}

} // namespace gonio
