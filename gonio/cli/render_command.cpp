// `gonio render FILE -o OUT.png`: the case's tabulated BSDF on an object (gonio/render), PNG and
// EXR, and with --compare the images without multiple scattering or of Model L1, and their
// Delta E00.
#include "core/output_files.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/progress.h"
#include "gonio/render/colour_difference.h"
#include "gonio/render/renderer.h"
#include "gonio/table/result_case.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <vector>

namespace gonio {

// What --compare renders beside the simulated BSDF.
enum class RenderComparison { none, l1, model };
template <>
struct EnumNames<RenderComparison> {
    static constexpr const char* what = "comparison";
    static constexpr const char* names[] = {"none", "l1", "model"};
};

namespace {
struct RenderOptions {
    std::string input, output, case_name;
    RenderComparison compare = RenderComparison::none;
    RenderObject object = RenderObject::sphere;
    std::string env = "sky"; // uniform, sky or an EXR path
    RenderSettings settings;
    bool overwrite = false, quiet = false;
    int threads = 0;
};

struct Rendered {
    std::string label;
    RenderResult result;
};

std::shared_ptr<const BsdfTable> rgb_table(const ResultCase& c, TableData d, const char* what) {
    long clipped = 0;
    TableData rgb = to_linear_srgb(std::move(d), c.wavelength_nm, &clipped);
    try {
        return std::make_shared<const BsdfTable>(std::move(rgb));
    } catch (const std::invalid_argument& e) {
        throw UsageError(c.file + ": the " + what + " table of case " + c.name +
                         " cannot be rendered: " + e.what());
    }
}

int render_case(const RenderOptions& o) {
    const std::string ext = ".png";
    if (o.output.size() <= ext.size() || o.output.compare(o.output.size() - 4, 4, ext) != 0)
        throw UsageError("-o " + o.output + ": the output must be a .png file");
    const std::string stem = o.output.substr(0, o.output.size() - 4);
    std::vector<std::string> outputs{o.output, stem + ".exr"};
    if (o.compare != RenderComparison::none)
        for (const char* suffix : {"_l1.png", "_l1.exr", "_de00.png"})
            outputs.push_back(stem + suffix);
    if (o.compare == RenderComparison::model)
        for (const char* suffix : {"_model.png", "_model.exr"}) outputs.push_back(stem + suffix);
    for (const std::string& p : outputs) {
        refuse_existing(p, o.overwrite);
        if (same_file(p, o.input)) throw UsageError(p + ": the output is the input");
    }
    // Every image appears, or none: each is written under its temporary name, all renamed last.
    OutputSet files(o.overwrite);
    std::map<std::string, std::string> temporary;
    for (const std::string& p : outputs) temporary[p] = files.add(p);
    const auto limit = limit_threads(o.threads);
    const ResultCase c = read_result_case(o.input, o.case_name);
    if (!c.simulated)
        throw UsageError(o.input + ": case " + c.name +
                         " holds models only (gonio model): nothing simulated to render");
    if (o.compare == RenderComparison::model && !c.has("model_l1"))
        throw UsageError(o.input + ": case " + c.name +
                         " has no Model L1 (model.models) to compare with");
    const Environment env = Environment::named(o.env);
    const RenderScene scene(o.object);
    const LambertianBsdf floor({0.5, 0.5, 0.5});
    RenderSettings s = o.settings;
    Progress progress(s.height, o.quiet);
    s.progress = [&](int rows, int) {
        progress.update(rows, "rows");
        if (rows == s.height) progress.finish();
    };
    auto draw = [&](std::shared_ptr<const BsdfTable> table, const std::string& label) {
        const TableBsdf bsdf(std::move(table));
        Rendered r{label, render(scene, env, bsdf, floor, s)};
        if (!o.quiet)
            std::printf("%s: %dx%d, %d spp, %.1f s, noise %.1f %% per pixel (rms over the "
                        "object)\n",
                        label.c_str(), s.width, s.height, s.spp, r.result.seconds,
                        100 * r.result.relative_noise);
        return r;
    };
    auto save = [&](const Rendered& r, const std::string& suffix) {
        write_png(r.result.image, temporary.at(stem + suffix + ".png"));
        write_exr(r.result.image, temporary.at(stem + suffix + ".exr"));
    };
    if (c.transmits && !o.quiet)
        std::printf("note: case %s transmits; the render shows its reflection only\n",
                    c.name.c_str());
    const Rendered main = draw(rgb_table(c, table_data(c, TableOrder::linf), "L-infinity"),
                               "L-infinity (every order)");
    save(main, "");
    if (o.compare == RenderComparison::none) {
        files.commit();
        return 0;
    }
    const Rendered l1 =
        draw(rgb_table(c, table_data(c, TableOrder::l1), "L1"), "L1 (single scattering)");
    save(l1, "_l1");
    const Rendered* a = &main;
    const Rendered* b = &l1;
    Rendered model;
    if (o.compare == RenderComparison::model) {
        model = draw(rgb_table(c, model_table_data(c, "l1"), "Model L1"), "Model L1 (Smith)");
        save(model, "_model");
        a = &l1;
        b = &model;
    }
    const std::vector<double> de = delta_e00(a->result.image, b->result.image);
    write_png(false_colour(de, s.width, s.height), temporary.at(stem + "_de00.png"));
    files.commit();
    const DifferenceStats st = difference_stats(de, main.result.object);
    std::printf("Delta E00 (%s against %s) over %lld object pixels: mean %.2f, 95th percentile "
                "%.2f, max %.2f\n",
                a->label.c_str(), b->label.c_str(), st.pixels, st.mean, st.p95, st.max);
    return 0;
}

// --size WxH and --light theta,phi (degrees), checked at the edge: finite, in range.
void parse_geometry(RenderOptions& o, const std::string& size, const std::string& light) {
    int w = 0, h = 0;
    char x = 0, rest = 0;
    if (std::sscanf(size.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || x != 'x' || w < 8 ||
        h < 8 || w > 8192 || h > 8192)
        throw UsageError("--size " + size + ": expected WxH, each in [8, 8192]");
    o.settings.width = w, o.settings.height = h;
    if (light.empty()) return;
    double theta = 0, phi = 0;
    if (std::sscanf(light.c_str(), "%lf,%lf%c", &theta, &phi, &rest) != 2 ||
        !std::isfinite(theta) || !std::isfinite(phi) || theta < 0 || theta >= 90)
        throw UsageError("--light " + light +
                         ": expected theta,phi in degrees, finite, theta in [0, 90)");
    o.settings.light = true;
    o.settings.light_direction = spherical_direction(radians(theta), radians(phi));
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    struct Args {
        RenderOptions o;
        std::string size = "400x300", light, compare = "none", object = "sphere";
    };
    auto a = std::make_shared<Args>();
    RenderOptions& o = a->o;
    app.add_option("file", o.input, "HDF5 result file of gonio run")->required();
    app.add_option("-o,--output", o.output, "Output .png (an .exr beside it)")->required();
    app.add_option("--case", o.case_name, "The case (default: the only one)");
    app.add_option("--compare", a->compare,
                   "l1: also without multiple scattering; model: simulated L1 against Model L1; "
                   "both write the Delta E00 image")
        ->check(CLI::IsMember(enum_names<RenderComparison>()));
    app.add_option("--spp", o.settings.spp, "Samples per pixel (default 64)")
        ->check(CLI::Range(1, 1 << 20));
    app.add_option("--size", a->size, "WxH (default 400x300)");
    app.add_option("--object", a->object, "sphere (default) or torus")
        ->check(CLI::IsMember(enum_names<RenderObject>()));
    app.add_option("--env", o.env, "uniform, sky (default) or a lat-long FILE.exr");
    app.add_option("--light", a->light, "theta,phi in degrees: a directional light from there");
    app.add_option("--depth", o.settings.max_depth, "Path vertices (default 5)")
        ->check(CLI::Range(1, 64));
    app.add_option("--seed", o.settings.seed, "Random seed (default 1)");
    app.add_flag("--overwrite", o.overwrite, "Replace existing images");
    app.add_flag("-q,--quiet", o.quiet, "No progress");
    app.add_option("--threads", o.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));
    return [a] {
        a->o.compare = enum_named<RenderComparison>(a->compare);
        a->o.object = enum_named<RenderObject>(a->object);
        parse_geometry(a->o, a->size, a->light);
        return render_case(a->o);
    };
}
} // namespace

const Command& render_command() {
    static const Command c{
        "render", "Render a simulated case's tabulated BSDF on an object (PNG and EXR)", setup};
    return c;
}

} // namespace gonio
