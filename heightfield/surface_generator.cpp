#include "heightfield/surface_generator.h"

#include "core/check.h"
#include "core/registry.h"

#include <chrono>
#include <stdexcept>

namespace gonio {

const std::vector<const SurfaceGenerator*>& surface_generators() {
    static const std::vector<const SurfaceGenerator*> all = {
        &sliced_matching_generator(), &algorithm1_generator(), &heitz_generator()};
    return all;
}

const SurfaceGenerator* default_generator() {
    return &sliced_matching_generator();
}

const SurfaceGenerator& generator_named(const std::string& name) {
    return find_named(surface_generators(), name, "generator");
}

const char* generator_name(const SurfaceSpec& spec) {
    return spec.generator ? spec.generator->name : "input";
}

HeightField generate_surface(const Ndf& ndf, const SurfaceSpec& spec, int threads,
                             GenerationLog* log, const ProgressFn& progress) {
    const auto start = std::chrono::steady_clock::now();
    GONIO_CHECK_MSG(spec.generator, "a measured map is loaded, not generated");
    GenerationLog local;
    GenerationLog* lg = log ? log : &local;
    *lg = GenerationLog{};
    HeightField s = spec.generator->generate(ndf, spec, threads, lg, progress);
    // The generators work in grid units (slopes per sample step); heights scale with the spacing.
    for (float& v : s.h) v = float(v * spec.spacing);
    s.spacing = spec.spacing;
    lg->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return s;
}

} // namespace gonio
