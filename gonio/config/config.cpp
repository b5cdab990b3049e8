#include "gonio/config/config.h"

#include "gonio/config/config_error.h"
#include "gonio/config/overrides.h"
#include "gonio/config/table_reader.h"
#include "gonio/material/ior_table.h"
#include "heightfield/exr_io.h"
#include "heightfield/ndf/gaussian_angles.h"
#include "heightfield/ndf/generalized_normal.h"
#include "heightfield/ndf/generalized_t.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/piecewise_linear.h"
#include "heightfield/ndf/student_t.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

namespace gonio {

namespace {

// Every key a section may hold; anything else is reported as unknown.
const std::map<std::string, std::vector<std::string>>& schema() {
    static const std::map<std::string, std::vector<std::string>> s = {
        {"",
         {"seed", "name", "ndf", "material", "spectrum", "beam", "sensor", "model", "surface",
          "trace", "case"}},
        {"case",
         {"name", "ndf", "material", "spectrum", "beam", "sensor", "model", "surface", "trace"}},
        {"ndf", {"type",  "alpha",           "alpha_x",   "alpha_y",  "gamma",      "p",
                 "q",     "sigma",           "k",         "floor",    "points",     "theta",
                 "value", "source",          "x",         "y",        "components", "weights",
                 "file",  "theta_intervals", "phi_count", "theta_max"}},
        {"material", {"type", "eta", "ior", "n", "k", "f0", "albedo"}},
        {"spectrum", {"wavelengths"}},
        {"beam", {"theta_i", "phi_i"}},
        {"sensor", {"cells"}},
        {"model",
         {"masking", "quadrature", "tolerance", "evaluate", "models", "body_points", "vcavity_rays",
          "ashikhmin", "pbrdf_sigma_eps"}},
        {"trace",
         {"rays", "orders", "max_bounces", "batches", "target_error", "target",
          "target_cell_fraction", "max_rays", "max_seconds"}},
        {"surface",
         {"generator", "constraint", "size", "spacing", "iterations", "threshold",
          "stop_when_converged", "lattice", "relief", "correlation_length", "input", "edges",
          "seed"}},
    };
    return s;
}
const std::vector<std::string> kSections = {"ndf",    "material", "spectrum", "beam",
                                            "sensor", "model",    "surface",  "trace"};

const Range kAlpha{1e-6, 100};
const Range kThetaI{0, 90, false, true};
const Range kPhiI{0, 360};
const Range kCells{1, 1e7};
const Range kWavelength{200, 20000};
const Range kEta{1e-3, 100};
const Range kK{0, 100};
const Range kF0{0, 1};

class Loader {
  public:
    Loader(const toml::table& root, std::string file) : root_(root), file_(std::move(file)) {}

    Config load() {
        Config cfg;
        check_sections(root_, "", "");
        TableReader top(&root_, "", nullptr, "", file_, usage_);
        cfg.seed = static_cast<std::uint64_t>(top.integer("seed", {0, 9.2e18}, 1));
        seed_ = cfg.seed;
        const toml::node* cases = root_.get("case");
        if (cases) {
            usage_.mark(cases);
            const toml::array* arr = cases->as_array();
            if (!arr || !arr->is_array_of_tables() || arr->empty())
                throw ConfigError(file_, line(cases), "case",
                                  "must be an array of tables: [[case]] sections");
            for (size_t k = 0; k < arr->size(); ++k) {
                const toml::table& t = *(*arr)[k].as_table();
                const std::string path = "case[" + std::to_string(k) + "]";
                check_sections(t, "case", path);
                cfg.cases.push_back(load_case(&t, path));
            }
        } else {
            cfg.cases.push_back(load_case(nullptr, ""));
        }
        check_names(cfg);
        report_unused(root_, "");
        return cfg;
    }

  private:
    static int line(const toml::node* n) {
        return n ? static_cast<int>(n->source().begin.line) : 0;
    }

    std::string join(const std::string& a, const std::string& b) const {
        return a.empty() ? b : a + "." + b;
    }

    // Unknown keys are reported at once, with a suggestion.
    void check_sections(const toml::table& t, const std::string& kind, const std::string& path) {
        const auto& allowed = schema().at(kind);
        for (const auto& [k, v] : t) {
            const std::string key(k.str());
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                unknown(key, v, allowed, path);
            if (std::find(kSections.begin(), kSections.end(), key) != kSections.end()) {
                const toml::table* sec = v.as_table();
                if (!sec) throw ConfigError(file_, line(&v), join(path, key), "must be a table");
                usage_.mark(&v);
                const auto& sec_allowed = schema().at(key);
                for (const auto& [sk, sv] : *sec) {
                    const std::string skey(sk.str());
                    if (std::find(sec_allowed.begin(), sec_allowed.end(), skey) ==
                        sec_allowed.end())
                        unknown(skey, sv, sec_allowed, join(path, key));
                }
            }
        }
    }

    [[noreturn]] void unknown(const std::string& key, const toml::node& v,
                              const std::vector<std::string>& allowed, const std::string& path) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        const std::string guess = closest_name(key, allowed.data(), allowed.size());
        throw ConfigError(file_, line(&v), join(path, key),
                          "unknown key" +
                              (guess.empty() ? "" : " (did you mean '" + guess + "'?)") +
                              "; allowed here: " + list);
    }

    // Keys that are known but that no case used (e.g. `ior` for a mirror) are errors too.
    void report_unused(const toml::table& t, const std::string& path) {
        for (const auto& [k, v] : t) {
            const std::string key = join(path, std::string(k.str()));
            if (const toml::table* sub = v.as_table(); sub && usage_.used(&v)) {
                report_unused(*sub, key);
                continue;
            }
            if (const toml::array* arr = v.as_array(); arr && arr->is_array_of_tables()) {
                for (size_t i = 0; i < arr->size(); ++i)
                    report_unused(*(*arr)[i].as_table(), key + "[" + std::to_string(i) + "]");
                continue;
            }
            if (!usage_.used(&v))
                throw ConfigError(file_, line(&v), key,
                                  "is not used by any case (it does not apply to the settings "
                                  "around it, e.g. a material key the material type ignores)");
        }
    }

    const toml::table* section(const toml::table* t, const std::string& name) const {
        if (!t) return nullptr;
        const toml::node* n = t->get(name);
        return n ? n->as_table() : nullptr;
    }

    TableReader reader(const toml::table* case_table, const std::string& case_path,
                       const std::string& name) {
        return TableReader(section(case_table, name), join(case_path, name), section(&root_, name),
                           name, file_, usage_);
    }

    CaseConfig load_case(const toml::table* t, const std::string& path) {
        CaseConfig c;
        if (t) {
            TableReader named(t, path, nullptr, "", file_, usage_);
            c.name = named.any_string("name");
        } else {
            TableReader top(&root_, "", nullptr, "", file_, usage_);
            std::string stem = file_.substr(file_.find_last_of('/') + 1);
            stem = stem.substr(0, stem.find('.'));
            c.name = top.has("name") ? top.any_string("name") : stem;
        }
        load_ndf(c, reader(t, path, "ndf"));
        load_material(c, reader(t, path, "material"), reader(t, path, "spectrum"));
        TableReader beam = reader(t, path, "beam");
        c.theta_i_deg = beam.number_list("theta_i", kThetaI);
        c.phi_i_deg = beam.number_list("phi_i", kPhiI, std::vector<double>{0.0});
        TableReader sensor = reader(t, path, "sensor");
        c.sensor_cells = static_cast<int>(sensor.integer("cells", kCells, 3240));
        TableReader model = reader(t, path, "model");
        const std::string masking = model.string(
            "masking", {"height-correlated", "uncorrelated", "v-cavity"}, "height-correlated");
        c.masking = masking == "uncorrelated" ? MaskingForm::uncorrelated
                    : masking == "v-cavity"   ? MaskingForm::v_cavity
                                              : MaskingForm::height_correlated;
        c.quadrature.points = static_cast<int>(model.integer("quadrature", {1, 64}, 4));
        c.quadrature.rel_tol = model.number("tolerance", {1e-12, 0.1}, 1e-6);
        load_models(c, model);
        TableReader trace = reader(t, path, "trace");
        c.rays = trace.integer("rays", {1, 1e12}, 1 << 20);
        if (c.vcavity_rays == 0) c.vcavity_rays = c.rays;
        c.orders = static_cast<int>(trace.integer("orders", {1, 1000}, 10));
        c.max_bounces = static_cast<int>(trace.integer("max_bounces", {1, 1000000}, 1000));
        c.batches = static_cast<int>(trace.integer("batches", {2, 1024}, 32));
        load_target(c, trace);
        load_surface(c, reader(t, path, "surface"));
        return c;
    }

    // An accuracy target instead of a ray count (trace.rays is then one round).
    void load_target(CaseConfig& c, TableReader& r) {
        AccuracyTarget& t = c.target;
        t.quantity = r.string("target", accuracy_target_quantities(), "l1_albedo");
        t.cell_fraction = r.number("target_cell_fraction", {0, 1, true, false}, 0.1);
        t.max_rays = r.integer("max_rays", {1, 1e13}, 10'000'000'000LL);
        t.max_seconds = r.number("max_seconds", {0, 1e7, true, false}, 3600);
        if (!r.has("target_error")) {
            for (const char* k : {"target", "target_cell_fraction", "max_rays", "max_seconds"})
                if (r.has(k)) r.fail(k, "applies only with trace.target_error");
            return;
        }
        t.relative_error = r.number("target_error", {0, 1, true, false});
        if (t.max_rays < c.rays)
            r.fail("max_rays", "must be at least trace.rays (" + std::to_string(c.rays) +
                                   "), the rays of one round");
    }

    // Which models the case evaluates, and their settings; each must suit the material.
    void load_models(CaseConfig& c, TableReader& r) {
        const bool evaluate = r.boolean("evaluate", true);
        const std::vector<std::string> fallback{c.diffuse() ? "il" : "l1"};
        c.models = r.string_list("models", {"l1", "il", "vcavity", "ashikhmin", "pbrdf"}, fallback);
        if (!evaluate) c.models.clear();
        for (const std::string& m : c.models) {
            const bool needs_specular = m == "l1" || m == "ashikhmin" || m == "pbrdf";
            if (needs_specular && c.diffuse())
                r.fail("models", "\"" + m + "\" is a specular model; for " + c.material_type +
                                     " facets use \"il\" (and \"vcavity\")");
            if (m == "il" && !c.diffuse())
                r.fail("models", "\"il\" needs lambertian or interfaced_lambertian facets, not " +
                                     c.material_type);
            if (m == "vcavity" && c.material_type == "dielectric")
                r.fail("models", "\"vcavity\" follows paths inside opaque V-grooves; dielectric "
                                 "facets transmit");
        }
        c.body_points = static_cast<int>(r.integer("body_points", {4, 256}, 32));
        c.vcavity_rays = r.integer("vcavity_rays", {1, 1e12}, 0);
        c.pbrdf_sigma_eps = r.number("pbrdf_sigma_eps", {1e-4, 1}, 0.01);
        if (r.has("ashikhmin")) {
            TableReader a = r.table("ashikhmin");
            a.allow_only({"distribution", "sigma", "correlation_width", "diffuse", "rho_d",
                          "theta_nodes", "phi_nodes"});
            c.ashikhmin_distribution = a.string("distribution", {"ndf", "satin", "velvet"}, "ndf");
            c.ashikhmin_sigma = a.number("sigma", {0.01, 10}, 0.5);
            c.ashikhmin.correlation_width = radians(a.number("correlation_width", {0, 90}, 0.0));
            c.ashikhmin.diffuse = a.string("diffuse", {"none", "dielectric", "metal"}, "none");
            c.ashikhmin.rho_d = a.number_list("rho_d", {0, 1}, std::vector<double>{1.0});
            if (c.ashikhmin.rho_d.size() != 1 && int(c.ashikhmin.rho_d.size()) != c.channels())
                a.fail("rho_d", "has " + std::to_string(c.ashikhmin.rho_d.size()) +
                                    " values; give one, or one per channel (" +
                                    std::to_string(c.channels()) + ")");
            c.ashikhmin.theta_nodes = static_cast<int>(a.integer("theta_nodes", {3, 1000}, 61));
            c.ashikhmin.phi_nodes = static_cast<int>(a.integer("phi_nodes", {4, 1000}, 32));
        }
    }

    void load_surface(CaseConfig& c, TableReader r) {
        SurfaceSpec& s = c.surface;
        // Its own seed keeps one surface while the rays' seed varies (their spread is then the
        // Monte Carlo error alone).
        s.seed = static_cast<std::uint64_t>(
            r.integer("seed", {0, 9.2e18}, static_cast<long long>(seed_)));
        if (r.has("input")) {
            // A measured height map replaces generation: generation keys would be unused.
            s.input = r.any_string("input");
            const std::string resolved = resolve(s.input);
            if (!std::ifstream(resolved)) r.fail("input", "cannot open height map " + resolved);
            s.input = resolved;
            s.edges = r.string("edges", {"periodic", "mirror"}, "periodic");
            s.generator = "input";
            return;
        }
        s.generator =
            r.string("generator", {"sliced-matching", "algorithm1", "heitz"}, "sliced-matching");
        s.size = static_cast<int>(r.integer("size", {8, 16384}, 256));
        s.spacing = r.number("spacing", {1e-9, 1e9, true, false}, 1.0);
        if (s.generator == "heitz") {
            if (c.ndf.type != "beckmann")
                r.fail("generator",
                       "\"heitz\" makes Beckmann surfaces only; this case's ndf.type is \"" +
                           c.ndf.type + "\"");
            s.correlation_length = r.number("correlation_length", {0.5, 1e6}, 8.0);
            return;
        }
        s.iterations = static_cast<int>(r.integer("iterations", {0, 1000000}, 500));
        s.threshold = r.number("threshold", {0, 1, true, false}, 0.02);
        s.stop_when_converged = r.boolean("stop_when_converged", false);
        s.constraint = r.string("constraint", {"none", "domes", "holes"}, "none");
        if (s.constraint != "none") {
            s.lattice = static_cast<int>(r.integer("lattice", {1, double(s.size / 2)}, 8));
            s.relief = r.number("relief", {1e-6, 100}, 0.5);
        }
    }

    void load_ndf(CaseConfig& c, TableReader all) { c.ndf = load_ndf_spec(all, 0); }

    // One distribution; blends, mixtures and sampled curves hold others as nested tables.
    NdfSpec load_ndf_spec(TableReader all, int depth) {
        if (depth > 0) all.allow_only(schema().at("ndf"));
        if (depth > 4) all.fail("type", "distributions nest at most 4 deep");
        NdfSpec s;
        s.type = all.string("type", {"beckmann", "ggx", "student_t", "generalized_normal",
                                     "generalized_t", "gaussian", "piecewise_linear", "sinc",
                                     "blend", "mixture", "tabulated", "height_map"});
        // Shape parameters of the generalised family [R19 section 2.1], in the ranges where D is
        // bounded and Smith's Lambda finite (see heightfield/ndf/).
        if (s.type == "student_t") {
            s.gamma = all.number("gamma", {1, StudentT::kGammaMax, true, false});
            char value[32];
            std::snprintf(value, sizeof value, "%g", s.gamma);
            if (s.gamma < StudentT::kGammaMin) // a valid distribution, but not a surface's
                all.fail("gamma", "value " + std::string(value) +
                                      " is outside gonio's domain [2, 1e6]: below 2 the slopes' "
                                      "variance is infinite (no height field follows them) and "
                                      "D diverges at the horizon; at 3/2 or below Smith's Lambda "
                                      "is infinite");
        }
        if (s.type == "generalized_normal")
            s.p = all.number("p", {GeneralizedNormal::kPMin, GeneralizedNormal::kPMax});
        if (s.type == "generalized_t") {
            s.p = all.number("p", {GeneralizedT::kPMin, GeneralizedT::kPMax});
            s.q = all.number("q", {0, GeneralizedT::kQMax, true, false});
            if (!(s.p * s.q >= 2))
                all.fail("q", "p q must be >= 2 (below 2, D diverges at the horizon)");
        }
        if (s.type == "beckmann" || s.type == "ggx" || s.type == "student_t" ||
            s.type == "generalized_normal" || s.type == "generalized_t")
            load_alpha(s, all);
        if (s.type == "gaussian") // M18 Eq. 14; sigma in degrees like every angle of a config
            s.sigma = radians(all.number(
                "sigma", {degrees(GaussianAngles::kSigmaMin), degrees(GaussianAngles::kSigmaMax)}));
        if (s.type == "gaussian") // the cut that keeps Smith's Lambda finite (gaussian_angles.h)
            s.theta_max = radians(all.number(
                "theta_max",
                {degrees(GaussianAngles::kThetaMaxMin), degrees(GaussianAngles::kThetaMaxMax)},
                degrees(GaussianAngles::kThetaMaxDefault)));
        if (s.type == "sinc") {
            s.k = all.number("k", {0, 200, true, false});
            s.floor = all.number("floor", {0, 1}, 0.0);
            s.intervals = static_cast<int>(all.integer("points", {9, 4097}, 129)) - 1;
        }
        if (s.type == "piecewise_linear") load_piecewise_linear(s, all, depth);
        if (s.type == "blend") {
            for (const char* axis : {"x", "y"}) {
                s.parts.push_back(load_ndf_spec(all.table(axis), depth + 1));
                const NdfSpec& part = s.parts.back();
                const bool isotropic = part.alpha_x == part.alpha_y && part.type != "blend" &&
                                       part.type != "mixture" && part.type != "tabulated" &&
                                       part.type != "height_map";
                if (!isotropic)
                    all.fail(axis, "must be an isotropic curve (one alpha; not a blend, mixture "
                                   "or table) [R19 Eq. 10]");
            }
        }
        if (s.type == "mixture") {
            for (TableReader& part : all.table_list("components"))
                s.parts.push_back(load_ndf_spec(part, depth + 1));
            s.weights = all.number_list("weights", {0, 1e300, true, false},
                                        std::vector<double>(s.parts.size(), 1.0));
            if (s.weights.size() != s.parts.size())
                all.fail("weights", "has " + std::to_string(s.weights.size()) +
                                        " values; give one per component (" +
                                        std::to_string(s.parts.size()) + ")");
        }
        if (s.type == "tabulated" || s.type == "height_map") {
            s.file = resolve(all.any_string("file"));
            if (!std::ifstream(s.file)) all.fail("file", "cannot open " + s.file);
            try { // a bad table or height map is reported now, not after other cases ran
                if (s.type == "tabulated")
                    read_ndf_table(s.file);
                else
                    read_height_exr(s.file);
            } catch (const std::exception& e) {
                all.fail("file", e.what());
            }
        }
        if (s.type == "height_map") { // the facet table's grid
            s.theta_intervals = static_cast<int>(all.integer("theta_intervals", {2, 900}, 45));
            s.phi_count = static_cast<int>(all.integer("phi_count", {1, 3600}, 36));
        }
        return s;
    }

    // Roughness keys go together: a case that gives any of them replaces the defaults' ones.
    void load_alpha(NdfSpec& s, TableReader& all) {
        const bool own = all.has_own("alpha") || all.has_own("alpha_x") || all.has_own("alpha_y");
        TableReader r = own ? all.own() : all;
        const bool iso = r.has("alpha");
        const bool aniso = r.has("alpha_x") || r.has("alpha_y");
        if (iso && aniso)
            r.fail("alpha", "give either alpha or both alpha_x and alpha_y, not both");
        if (iso) {
            s.alpha_x = s.alpha_y = r.number("alpha", kAlpha);
        } else if (aniso) {
            s.alpha_x = r.number("alpha_x", kAlpha);
            s.alpha_y = r.number("alpha_y", kAlpha);
        } else {
            r.fail("alpha", "missing: give alpha (isotropic) or alpha_x and alpha_y; allowed " +
                                kAlpha.describe());
        }
    }

    // R19 Eq. 11: control points given (theta in degrees, from 0 to 90, and values), or sampled
    // from another distribution at `points` angles.
    void load_piecewise_linear(NdfSpec& s, TableReader& all, int depth) {
        if (all.has("source")) {
            s.parts.push_back(load_ndf_spec(all.table("source"), depth + 1));
            s.intervals = static_cast<int>(all.integer("points", {3, 4097}, 65)) - 1;
            return;
        }
        if (!all.has("theta"))
            all.fail("theta", "missing: give theta (degrees, 0 to 90) and value, or a source "
                              "distribution to sample");
        for (double t : all.number_list("theta", {0, 90})) s.theta.push_back(radians(t));
        s.value = all.number_list("value", {0, 1e300});
        try {
            PiecewiseLinearNdf check(ControlPoints{s.theta, s.value});
        } catch (const std::invalid_argument& e) {
            all.fail("theta", e.what());
        }
    }

    // A path relative to the config file's directory.
    std::string resolve(const std::string& path) const {
        if (path.empty() || path[0] == '/') return path;
        const size_t slash = file_.find_last_of('/');
        return slash == std::string::npos ? path : file_.substr(0, slash + 1) + path;
    }

    // A per-channel list: a single value (achromatic) or one value per wavelength.
    std::vector<double> per_channel(TableReader& r, const std::string& key, const Range& range,
                                    const std::vector<double>& wavelengths) {
        std::vector<double> v = r.number_list(key, range);
        if (v.size() != 1 && v.size() != wavelengths.size())
            r.fail(key, "has " + std::to_string(v.size()) +
                            " values; give one (achromatic) or one per wavelength (" +
                            std::to_string(wavelengths.size()) + ")");
        return v;
    }

    void load_material(CaseConfig& c, TableReader r, TableReader spectrum) {
        c.material_type = r.string(
            "type",
            {"mirror", "dielectric", "conductor", "schlick", "lambertian", "interfaced_lambertian"},
            "mirror");
        // Wavelengths matter only to a spectral material; read them lazily so that an unused
        // [spectrum] is reported.
        auto wavelengths = [&]() {
            return spectrum.number_list("wavelengths", kWavelength,
                                        std::vector<double>{650.0, 550.0, 450.0});
        };
        if (c.material_type == "mirror") {
            c.fresnel = FresnelTerm::mirror();
        } else if (c.material_type == "lambertian") {
            c.albedo = r.number_list("albedo", {0, 1});
            if (c.albedo.size() > 1) { // spectral: one value per wavelength
                c.wavelengths_nm = wavelengths();
                if (c.albedo.size() != c.wavelengths_nm.size())
                    r.fail("albedo", "has " + std::to_string(c.albedo.size()) +
                                         " values; give one (achromatic) or one per wavelength (" +
                                         std::to_string(c.wavelengths_nm.size()) + ")");
            }
        } else if (c.material_type == "interfaced_lambertian") { // M18 section 3.1
            c.albedo = r.number_list("albedo", {0, 1});
            c.interface_eta = r.number_list("eta", {1, 100});
            if (c.albedo.size() > 1 || c.interface_eta.size() > 1) { // spectral
                c.wavelengths_nm = wavelengths();
                for (const auto& [key, v] :
                     {std::pair{"albedo", &c.albedo}, std::pair{"eta", &c.interface_eta}})
                    if (v->size() != 1 && v->size() != c.wavelengths_nm.size())
                        r.fail(key, "has " + std::to_string(v->size()) +
                                        " values; give one (achromatic) or one per wavelength (" +
                                        std::to_string(c.wavelengths_nm.size()) + ")");
            }
        } else if (c.material_type == "dielectric" || c.material_type == "schlick") {
            const bool dielectric = c.material_type == "dielectric";
            const std::string key = dielectric ? "eta" : "f0";
            std::vector<double> v = r.number_list(key, dielectric ? kEta : kF0);
            if (v.size() > 1) { // spectral: one value per wavelength
                c.wavelengths_nm = wavelengths();
                if (v.size() != c.wavelengths_nm.size())
                    r.fail(key, "has " + std::to_string(v.size()) +
                                    " values; give one (achromatic) or one per wavelength (" +
                                    std::to_string(c.wavelengths_nm.size()) + ")");
            }
            c.fresnel = dielectric ? FresnelTerm::dielectric(v) : FresnelTerm::schlick(v);
        } else { // conductor
            c.wavelengths_nm = wavelengths();
            std::vector<std::complex<double>> eta;
            if (r.has("ior")) {
                if (r.has("n") || r.has("k"))
                    r.fail("ior", "give either ior (a table) or n and k, not both");
                const std::string name = r.any_string("ior");
                const std::string file = resolve_ior_path(name);
                IorTable table = [&]() {
                    try {
                        return IorTable::load(file);
                    } catch (const std::exception& e) {
                        r.fail("ior", std::string(e.what()) +
                                          " (a name such as \"Au\", \"Ag\", \"Cu\", \"Al\" or a "
                                          "path to a CSV)");
                    }
                }();
                for (double w : c.wavelengths_nm) {
                    if (w < table.min_wavelength() || w > table.max_wavelength())
                        spectrum.fail("wavelengths",
                                      "wavelength " + std::to_string(w) + " nm is outside table " +
                                          file + "; allowed [" +
                                          std::to_string(table.min_wavelength()) + ", " +
                                          std::to_string(table.max_wavelength()) + "] nm");
                    eta.push_back(table.at(w));
                }
                c.material_source = file;
            } else {
                const std::vector<double> n = per_channel(r, "n", kEta, c.wavelengths_nm);
                const std::vector<double> k = per_channel(r, "k", kK, c.wavelengths_nm);
                for (size_t i = 0; i < c.wavelengths_nm.size(); ++i)
                    eta.emplace_back(n[n.size() == 1 ? 0 : i], k[k.size() == 1 ? 0 : i]);
            }
            c.fresnel = FresnelTerm::conductor(eta);
        }
    }

    void check_names(const Config& cfg) {
        std::set<std::string> seen;
        for (size_t k = 0; k < cfg.cases.size(); ++k) {
            const std::string& n = cfg.cases[k].name;
            const std::string key = cfg.cases.size() > 1 || root_.get("case")
                                        ? "case[" + std::to_string(k) + "].name"
                                        : "name";
            const toml::node* node = nullptr;
            if (const toml::array* arr = root_["case"].as_array())
                node = (*arr)[k].as_table()->get("name");
            if (n.empty() ||
                n.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                    "0123456789_.-+") != std::string::npos)
                throw ConfigError(file_, line(node), key,
                                  "\"" + n + "\" is not allowed; use letters, digits and _ . - +");
            if (!seen.insert(n).second)
                throw ConfigError(file_, line(node), key, "\"" + n + "\" names two cases");
        }
    }

    const toml::table& root_;
    std::string file_;
    UsageTracker usage_;
    std::uint64_t seed_ = 1;
};

} // namespace

std::string CaseConfig::material_description() const {
    if (!diffuse()) return fresnel.describe();
    std::string s = material_type + "(";
    if (material_type == "interfaced_lambertian") {
        s += "eta=";
        for (size_t k = 0; k < interface_eta.size(); ++k)
            s += (k ? ", " : "") + std::to_string(interface_eta[k]);
        s += "; ";
    }
    s += "albedo=";
    for (size_t k = 0; k < albedo.size(); ++k) s += (k ? ", " : "") + std::to_string(albedo[k]);
    return s + ")";
}

const char* masking_name(MaskingForm form) {
    return form == MaskingForm::uncorrelated ? "uncorrelated"
           : form == MaskingForm::v_cavity   ? "v-cavity"
                                             : "height-correlated";
}

Config parse_config(const std::string& text, const std::string& path,
                    const std::vector<std::string>& overrides) {
    toml::table root;
    try {
        root = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw ConfigError(path, static_cast<int>(e.source().begin.line), "",
                          "TOML syntax error: " + std::string(e.description()));
    }
    for (const auto& o : overrides) apply_override(root, o, path);
    Config cfg = Loader(root, path).load();
    cfg.path = path;
    cfg.text = text;
    cfg.overrides = overrides;
    std::ostringstream s;
    s << root;
    cfg.effective_toml = s.str();
    return cfg;
}

Config load_config(const std::string& path, const std::vector<std::string>& overrides) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ConfigError(path, -1, "", "cannot open the config file (missing or unreadable)");
    std::stringstream buffer;
    buffer << in.rdbuf();
    return parse_config(buffer.str(), path, overrides);
}

} // namespace gonio
