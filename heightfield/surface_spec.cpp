#include "heightfield/surface_spec.h"

#include "heightfield/ndf/ndf.h"

#include <stdexcept>

namespace gonio {

namespace {
const char* const kGeneratorNames[] = {"sliced-matching", "algorithm1", "heitz", "input"};
const char* const kConstraintNames[] = {"none", "domes", "holes"};
const char* const kEdgeNames[] = {"periodic", "mirror"};

const Key kGenerator = Key::string("generator", {"sliced-matching", "algorithm1", "heitz"},
                                   "how the microsurface is made (below)")
                           .fallback("sliced-matching");
const Key kSeed = Key::integer("seed", {0, 9.2e18},
                               "the surface's own seed: vary `seed` with this fixed and only the "
                               "rays change")
                      .note_default("`seed`");
const Key kSize = Key::integer("size", {8, 16384}, "samples per side of the periodic height field")
                      .fallback(256.0);
const Key kSpacing = Key::number("spacing", {1e-9, 1e9, true, false},
                                 "distance between samples (heights scale with it; slopes do not)")
                         .fallback(1.0);
const Key kInput =
    Key::path("input",
              "a measured height map instead of generation (square, one channel Y/Z/H/R), "
              "or a normal map (R, G, B = the unit normal) integrated by Frankot-Chellappa")
        .note_default("—");
const Key kEdges = Key::string("edges", {"periodic", "mirror"},
                               "input maps: keep as is, or tile with mirror images into a periodic "
                               "2n² map")
                       .fallback("periodic");
// The matching generators (sliced-matching, algorithm1).
const Key kIterations =
    Key::integer("iterations", {0, 1e6}, "iterations of the generator (R19: 500)").fallback(500.0);
const Key kThreshold =
    Key::number("threshold", {0, 1, true, false}, "Schwarz threshold of Algorithm 1 (R19: 0.02)")
        .fallback(0.02)
        .cited("R19 Eq. 19");
const Key kStop = Key::boolean("stop_when_converged",
                               "stop when the NDF distance (checked every 10 iterations) stops "
                               "improving")
                      .fallback(false);
const Key kConstraint = Key::string("constraint", {"none", "domes", "holes"},
                                    "constrained generation: start from a lattice")
                            .fallback("none")
                            .cited("R19 section 5.3.2");
const Key kLattice = Key::integer("lattice", {1, 8192}, "domes/holes: features per side")
                         .fallback(8.0)
                         .noting("at most size/2");
const Key kRelief =
    Key::number("relief", {1e-6, 100}, "domes/holes: height over radius").fallback(0.5);
// Every generator: the ensemble.
const Key kRealisations =
    Key::integer("realisations", {1, 4096},
                 "independent surfaces per case, the rays of every incidence spread over them: "
                 "every error then includes the surfaces' spread (README, \"Surface ensembles\")")
        .fallback(1.0);
const Key kMaxRealisations =
    Key::integer("max_realisations", {2, 4096},
                 "with `trace.target_error` and an ensemble: the most surfaces the target may add")
        .fallback(64.0);
// heitz
const Key kCorrelation =
    Key::number("correlation_length", {0.5, 1e6}, "heitz: Gaussian correlation length, in samples")
        .fallback(8.0);

template <class E, size_t N>
E by_name(const char* const (&names)[N], const std::string& s) {
    for (size_t k = 0; k < N; ++k)
        if (s == names[k]) return E(k);
    throw std::invalid_argument("unknown name '" + s + "'");
}
} // namespace

const char* name_of(Generator g) {
    return kGeneratorNames[int(g)];
}
const char* name_of(Constraint c) {
    return kConstraintNames[int(c)];
}
const char* name_of(Edges e) {
    return kEdgeNames[int(e)];
}
Generator generator_named(const std::string& name) {
    return by_name<Generator>(kGeneratorNames, name);
}

std::uint64_t realisation_seed(std::uint64_t seed, int r) {
    if (r == 0) return seed;
    // SplitMix64 of (seed, r): distinct realisations of distinct seeds collide with probability
    // ~2^-64.
    std::uint64_t z = seed ^ (0x9e3779b97f4a7c15ull * std::uint64_t(r));
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

SurfaceSpec realisation(const SurfaceSpec& spec, int r) {
    SurfaceSpec s = spec;
    s.seed = realisation_seed(spec.seed, r);
    return s;
}

SurfaceSpec read_surface(TableReader& r, std::uint64_t seed, const Ndf& ndf, bool target) {
    SurfaceSpec s;
    // Its own seed keeps one surface while the rays' seed varies (their spread is then the
    // Monte Carlo error alone).
    s.seed = static_cast<std::uint64_t>(r.integer(kSeed.name, kSeed.range, (long long)seed));
    if (r.has(kInput.name)) {
        // A measured map replaces generation: generation keys would be unused.
        s.input = r.path(kInput);
        s.edges = by_name<Edges>(kEdgeNames, r.string(kEdges));
        s.generator = Generator::input;
        if (r.has(kRealisations.name) && r.integer(kRealisations) > 1)
            r.fail(kRealisations.name, "a measured map is one surface: an ensemble needs a "
                                       "generator");
        return s;
    }
    s.realisations = static_cast<int>(r.integer(kRealisations));
    if (r.has(kMaxRealisations.name)) {
        if (!target || s.realisations < 2)
            r.fail(kMaxRealisations.name, "applies only with trace.target_error and "
                                          "surface.realisations >= 2");
        s.max_realisations = static_cast<int>(r.integer(kMaxRealisations));
        if (s.max_realisations < s.realisations)
            r.fail(kMaxRealisations.name, "must be at least surface.realisations (" +
                                              std::to_string(s.realisations) + ")");
    }
    s.generator = by_name<Generator>(kGeneratorNames, r.string(kGenerator));
    s.size = static_cast<int>(r.integer(kSize));
    s.spacing = r.number(kSpacing);
    if (s.generator == Generator::heitz) {
        double ax, ay;
        if (!ndf.gaussian_slopes(ax, ay))
            r.fail("generator",
                   "\"heitz\" makes Beckmann surfaces only; this case's ndf.type is \"" +
                       ndf.name() + "\"");
        s.correlation_length = r.number(kCorrelation);
        return s;
    }
    s.iterations = static_cast<int>(r.integer(kIterations));
    s.threshold = r.number(kThreshold);
    s.stop_when_converged = r.boolean(kStop);
    s.constraint = by_name<Constraint>(kConstraintNames, r.string(kConstraint));
    if (s.constraint != Constraint::none) {
        s.lattice = static_cast<int>(
            r.integer(kLattice.name, {1, double(s.size / 2)}, (long long)*kLattice.number_default));
        s.relief = r.number(kRelief);
    }
    return s;
}

std::vector<KeyGroup> surface_key_groups() {
    return {{"surface",
             "",
             "",
             {kGenerator, kSeed, kSize, kSpacing, kInput, kEdges, kRealisations, kMaxRealisations}},
            {"surface",
             "sliced-matching, algorithm1",
             "iterative Frankot-Chellappa with matching [R19 Algorithm 1]",
             {kIterations, kThreshold, kStop, kConstraint, kLattice, kRelief}},
            {"surface", "heitz", "random-phase Gaussian surface (Heitz 2015)", {kCorrelation}}};
}

} // namespace gonio
