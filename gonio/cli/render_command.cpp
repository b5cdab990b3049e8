#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/render/colour_difference.h"
#include "gonio/render/renderer.h"
#include "gonio/table/result_case.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace gonio {

namespace {
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
        throw RenderArgumentError(c.file + ": the " + what + " table of case " + c.name +
                                  " cannot be rendered: " + e.what());
    }
}
} // namespace

int run_render_command(const RenderOptions& o) {
    const std::string ext = ".png";
    if (o.output.size() <= ext.size() || o.output.compare(o.output.size() - 4, 4, ext) != 0)
        throw RenderArgumentError("-o " + o.output + ": the output must be a .png file");
    const std::string stem = o.output.substr(0, o.output.size() - 4);
    std::vector<std::string> outputs{o.output, stem + ".exr"};
    if (!o.compare.empty())
        for (const char* suffix : {"_l1.png", "_l1.exr", "_de00.png"})
            outputs.push_back(stem + suffix);
    if (o.compare == "model")
        for (const char* suffix : {"_model.png", "_model.exr"}) outputs.push_back(stem + suffix);
    for (const std::string& p : outputs)
        if (!o.overwrite && std::filesystem::exists(p))
            throw RenderArgumentError(p + ": exists; pass --overwrite to replace it");
    const auto limit = limit_threads(o.threads);
    const ResultCase c = read_result_case(o.input, o.case_name);
    if (!c.simulated)
        throw RenderArgumentError(o.input + ": case " + c.name +
                                  " holds models only (gonio model): nothing simulated to render");
    if (o.compare == "model" && !c.has("model_l1"))
        throw RenderArgumentError(o.input + ": case " + c.name +
                                  " has no Model L1 (model.models) to compare with");
    const Environment env = o.env == "uniform" ? Environment::uniform(1.0)
                            : o.env == "sky"   ? Environment::overcast_sky()
                                               : Environment::from_exr(o.env);
    const RenderScene scene(o.object);
    const LambertianBsdf floor({0.5, 0.5, 0.5});
    RenderSettings s = o.settings;
    s.quiet = o.quiet;
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
        write_png(r.result.image, stem + suffix + ".png");
        write_exr(r.result.image, stem + suffix + ".exr");
    };
    if (c.transmits && !o.quiet)
        std::printf("note: case %s transmits; the render shows its reflection only\n",
                    c.name.c_str());
    const Rendered main = draw(rgb_table(c, table_data(c, TableOrder::linf), "L-infinity"),
                               "L-infinity (every order)");
    save(main, "");
    if (o.compare.empty()) return 0;
    const Rendered l1 =
        draw(rgb_table(c, table_data(c, TableOrder::l1), "L1"), "L1 (single scattering)");
    save(l1, "_l1");
    const Rendered* a = &main;
    const Rendered* b = &l1;
    Rendered model;
    if (o.compare == "model") {
        model = draw(rgb_table(c, model_table_data(c, "l1"), "Model L1"), "Model L1 (Smith)");
        save(model, "_model");
        a = &l1;
        b = &model;
    }
    const std::vector<double> de = delta_e00(a->result.image, b->result.image);
    write_png(false_colour(de, s.width, s.height), stem + "_de00.png");
    const DifferenceStats st = difference_stats(de, main.result.object);
    std::printf("Delta E00 (%s against %s) over %lld object pixels: mean %.2f, 95th percentile "
                "%.2f, max %.2f\n",
                a->label.c_str(), b->label.c_str(), st.pixels, st.mean, st.p95, st.max);
    return 0;
}

} // namespace gonio
