#include "heightfield/surface_spec.h"

#include "heightfield/measured/map_preparation.h"
#include "heightfield/ndf/ndf.h"
#include "heightfield/surface_generator.h"

#include <stdexcept>

namespace gonio {

namespace {
const Key& generator_key() {
    static const Key key = [] {
        std::vector<std::string> names;
        for (const SurfaceGenerator* g : surface_generators()) names.push_back(g->name);
        return Key::string("generator", names,
                           "how the microsurface is made (docs/microsurfaces.md)")
            .fallback(default_generator()->name);
    }();
    return key;
}
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
              "a measured height map instead of generation (X3P, SDF, GSF, a plain matrix or "
              "OpenEXR: docs/measured-surfaces.md), or an OpenEXR normal map (R, G, B = the unit "
              "normal) integrated by Frankot-Chellappa")
        .note_default("—");
// A measured map's preparation (heightfield/measured/map_preparation.h, docs/measured-surfaces.md).
std::vector<std::string> level_choices() {
    std::vector<std::string> names = enum_names<Levelling>();
    names.insert(names.begin(), "auto");
    return names;
}
const Key kLevel = Key::string("level", level_choices(),
                               "input maps: least-squares form removed (auto: a plane for "
                               "third-party formats, none for OpenEXR maps)")
                       .fallback("auto");
const Key kSpikes = Key::number("spikes", {0, 1e6},
                                "input maps: points farther than this many robust sigmas from "
                                "their 3x3 median are spikes, removed and filled (0: none)")
                        .note_default("20 (0 for OpenEXR maps)");
const Key kMaxMissing = Key::number("max_missing", {0, 0.9},
                                    "input maps: the largest share of missing points (spikes "
                                    "included) filled by interpolation; more is refused")
                            .fallback(0.05);
const Key kHighPass = Key::number("high_pass", {0, 1e12},
                                  "input maps: the cut-off wavelength of a Gaussian high-pass "
                                  "(ISO 16610-61) removing the form and waviness longer than it, "
                                  "in micrometres (whatever surface.input_unit; an OpenEXR "
                                  "map's own unit) (0: none)")
                          .fallback(0.0);
const Key kInputSpacing = Key::number("input_spacing", {1e-9, 1e9, true, false},
                                      "input maps: the spacing of a plain matrix of heights, in "
                                      "surface.input_unit (other formats carry their own)")
                              .note_default("—");
const Key kInputUnit = Key::string("input_unit", {"m", "mm", "um", "µm", "nm"},
                                   "input maps: the length unit of a plain matrix's heights and "
                                   "of surface.input_spacing (other formats carry their own)")
                           .fallback("um");
const Key kInputChecksums =
    Key::boolean("input_checksums", "input maps: refuse a file whose checksums (X3P's MD5) "
                                    "do not match; false reads it anyway")
        .fallback(true);
const Key kEdges = Key::string("edges", enum_names<Edges>(),
                               "input maps: keep as is, or tile with mirror images into a periodic "
                               "2n² map")
                       .fallback("periodic");
// Every generator: the ensemble.
const Key kRealisations =
    Key::integer("realisations", {1, 4096},
                 "independent surfaces per case, the rays of every incidence spread over them: "
                 "every error then includes the surfaces' spread (docs/ensembles.md)")
        .fallback(1.0);
const Key kMaxRealisations =
    Key::integer("max_realisations", {2, 4096},
                 "with `trace.target_error` and an ensemble: the most surfaces the target may add")
        .fallback(64.0);
} // namespace

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
        s.edges = enum_named<Edges>(r.string(kEdges));
        s.prepare_asked = r.has(kLevel.name) || r.has(kSpikes.name) || r.has(kMaxMissing.name) ||
                          r.has(kHighPass.name);
        s.level = r.string(kLevel);
        s.spikes = r.has(kSpikes.name) ? r.number(kSpikes) : -1;
        s.max_missing = r.number(kMaxMissing);
        s.high_pass = r.number(kHighPass);
        if (r.has(kInputSpacing.name)) s.input_spacing = r.number(kInputSpacing);
        s.input_unit = r.string(kInputUnit);
        s.input_checksums = r.boolean(kInputChecksums);
        s.generator = nullptr;
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
    s.generator = &generator_named(r.string(generator_key()));
    s.size = static_cast<int>(r.integer(kSize));
    s.spacing = r.number(kSpacing);
    s.generator->read(r, ndf, s);
    return s;
}

std::vector<KeyGroup> surface_key_groups() {
    std::vector<KeyGroup> groups{
        {"surface",
         "",
         "",
         {generator_key(), kSeed, kSize, kSpacing, kInput, kEdges, kLevel, kSpikes, kMaxMissing,
          kHighPass, kInputSpacing, kInputUnit, kInputChecksums, kRealisations, kMaxRealisations}}};
    // One group per list of keys; generators sharing a list share its group.
    for (const SurfaceGenerator* g : surface_generators()) {
        KeyGroup* shared = nullptr;
        for (size_t k = 1; k < groups.size(); ++k)
            if (groups[k].keys.size() == g->keys->size() &&
                groups[k].keys[0].name == g->keys->at(0).name)
                shared = &groups[k];
        if (shared) {
            shared->owner += std::string(", ") + g->name;
            continue;
        }
        groups.push_back({"surface", g->name, g->summary, *g->keys});
    }
    return groups;
}

} // namespace gonio
