// gonio: a virtual gonioreflectometer for explicit microfacet surfaces. See README.md.
#include "core/config_error.h"
#include "gonio/cli/commands.h"
#include "gonio/distributed/mpi_job.h"
#include "gonio/export/export.h"
#include "gonio_version.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

int gonio_main(int argc, char** argv, const gonio::MpiJob& job);

int main(int argc, char** argv) {
    // Under mpirun: MPI starts here, and every rank but 0 keeps quiet.
    const gonio::MpiJob job = gonio::mpi_start(&argc, &argv);
    const int code = gonio_main(argc, argv, job);
    gonio::mpi_finish();
    return code;
}

int gonio_main(int argc, char** argv, const gonio::MpiJob& job) {
    CLI::App app{"gonio: a virtual gonioreflectometer for microfacet surfaces"};
    app.set_version_flag("--version",
                         std::string(gonio::kVersion) + " (git " + gonio::kGitHash + ")");
    app.require_subcommand(1);

    std::string command_line;
    for (int k = 0; k < argc; ++k) command_line += (k ? " " : "") + std::string(argv[k]);

    gonio::ModelOptions model;
    model.command_line = command_line;
    CLI::App* model_cmd = app.add_subcommand(
        "model", "Evaluate the analytic Model L1 on the sensor cells for every case and incidence");
    model_cmd->add_option("config", model.config, "TOML config file")->required();
    model_cmd->add_option("-o,--output", model.output, "HDF5 result file (default: <config>.h5)");
    model_cmd->add_option("--set", model.overrides,
                          "Override a config key, e.g. --set ndf.alpha=0.3 or "
                          "--set case.1.beam.theta_i=[0,60] (repeatable)");
    model_cmd->add_flag("--overwrite", model.overwrite, "Replace an existing output file");
    model_cmd->add_flag("-q,--quiet", model.quiet, "No progress and no table");
    model_cmd->add_option("--threads", model.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));

    gonio::SurfaceOptions surface;
    CLI::App* surface_cmd = app.add_subcommand(
        "surface", "Generate (or reuse from the cache) the microsurface of every case; write EXR");
    surface_cmd->add_option("config", surface.config, "TOML config file")->required();
    surface_cmd->add_option("-o,--output", surface.output,
                            "EXR height map (default: <config>_<case>.exr; with several cases the "
                            "case name is appended)");
    surface_cmd->add_option("--set", surface.overrides, "Override a config key (repeatable)");
    surface_cmd->add_flag("--overwrite", surface.overwrite, "Replace existing output files");
    surface_cmd->add_flag("-q,--quiet", surface.quiet, "No progress and no report");
    surface_cmd->add_flag("--no-cache", surface.no_cache,
                          "Neither read nor write the surface cache");
    surface_cmd->add_option("--cache-dir", surface.cache_dir,
                            "Surface cache directory (default: $GONIO_CACHE_DIR, else "
                            "~/.cache/gonio/surfaces)");
    surface_cmd->add_option("--threads", surface.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));

    gonio::RunOptions run;
    run.command_line = command_line;
    CLI::App* run_cmd = app.add_subcommand(
        "run",
        "Trace every case and incidence on the explicit microsurface; compare with Model L1");
    run_cmd->add_option("config", run.config, "TOML config file")->required();
    run_cmd->add_option("-o,--output", run.output, "HDF5 result file (default: <config>.h5)");
    run_cmd->add_option("--set", run.overrides, "Override a config key (repeatable)");
    run_cmd->add_flag("--overwrite", run.overwrite, "Replace an existing output file");
    run_cmd->add_flag("-q,--quiet", run.quiet, "No progress and no table");
    run_cmd->add_flag("--no-cache", run.no_cache, "Neither read nor write the surface cache");
    run_cmd->add_option("--cache-dir", run.cache_dir, "Surface cache directory");
    run_cmd->add_option("--threads", run.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));
    run_cmd->add_option("--shard", run.shard,
                        "i/N: trace only shard i of N into a part file for gonio merge; 'slurm': "
                        "i and N from SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT");
    run_cmd->add_flag("--resume", run.resume, "Continue an interrupted run from OUT.checkpoint");

    std::vector<std::string> merge_parts;
    std::string merge_output;
    bool merge_overwrite = false, merge_quiet = false;
    int merge_threads = 0;
    CLI::App* merge_cmd =
        app.add_subcommand("merge", "Put the parts of a sharded gonio run together");
    merge_cmd->add_option("parts", merge_parts, "Part files of gonio run --shard")->required();
    merge_cmd->add_option("-o,--output", merge_output, "HDF5 result file")->required();
    merge_cmd->add_flag("--overwrite", merge_overwrite, "Replace an existing output file");
    merge_cmd->add_flag("-q,--quiet", merge_quiet, "No table");
    merge_cmd->add_option("--threads", merge_threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));

    gonio::NdfOptions ndf;
    CLI::App* ndf_cmd = app.add_subcommand(
        "ndf", "Print each case's D and Lambda along phi = 0 and 90 deg and its Model L1 albedo");
    ndf_cmd->add_option("config", ndf.config, "TOML config file")->required();
    ndf_cmd->add_option("--csv", ndf.csv, "Write the curves (0.5 deg steps) to this CSV file");
    ndf_cmd->add_option("--set", ndf.overrides, "Override a config key: key.path=value");
    ndf_cmd->add_option("--threads", ndf.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));

    std::string compare_path;
    CLI::App* compare_cmd =
        app.add_subcommand("compare", "Print the Model-vs-simulated table of a result file");
    compare_cmd->add_option("file", compare_path, "HDF5 result file")->required();

    std::string info_path;
    bool info_json = false;
    CLI::App* info_cmd = app.add_subcommand("info", "Summarise a result file");
    info_cmd->add_option("file", info_path, "HDF5 result file")->required();
    info_cmd->add_flag("--json", info_json, "Print a JSON object instead of text");

    bool keys_markdown = false;
    CLI::App* keys_cmd = app.add_subcommand(
        "keys", "List every config key: its section, range, default and meaning");
    keys_cmd->add_flag("--markdown", keys_markdown,
                       "Print the README's configuration table (Markdown)");

    gonio::ExportOptions exp;
    CLI::App* export_cmd = app.add_subcommand(
        "export", "Write a simulated case in a format renderers and BRDF tools read");
    export_cmd->add_option("file", exp.input, "HDF5 result file of gonio run")->required();
    export_cmd
        ->add_option("--format", exp.format,
                     "rgl (Mitsuba 3 / pbrt-v4 measured), merl, astm, albedo (CSV)")
        ->required()
        ->check(CLI::IsMember({"rgl", "merl", "astm", "albedo"}));
    export_cmd->add_option("-o,--output", exp.output, "Output file")->required();
    export_cmd->add_option("--case", exp.case_name, "The case to export (default: the only one)");
    export_cmd->add_option("--orders", exp.orders, "l1, l2plus, linf (default) or t (astm)")
        ->check(CLI::IsMember({"l1", "l2plus", "linf", "t"}));
    export_cmd->add_flag("--rgb", exp.rgb, "rgl: an rgb field (Mitsuba's RGB variants)");
    export_cmd->add_option("--sweep", exp.sweep,
                           "albedo: every case, with this config key (e.g. ndf.alpha) as a column");
    export_cmd->add_flag("--overwrite", exp.overwrite, "Replace an existing output file");
    export_cmd->add_flag("-q,--quiet", exp.quiet, "Print nothing on success");

    std::string cache_action, cache_dir;
    CLI::App* cache_cmd = app.add_subcommand(
        "cache", "List or clear the surface cache ($GONIO_CACHE_DIR; $GONIO_CACHE_MAX caps it)");
    cache_cmd->add_option("action", cache_action, "list or clear")
        ->required()
        ->check(CLI::IsMember({"list", "clear"}));
    cache_cmd->add_option("--cache-dir", cache_dir, "Surface cache directory");

    gonio::RenderOptions rnd;
    std::string render_size = "400x300", render_light;
    CLI::App* render_cmd = app.add_subcommand(
        "render", "Render a simulated case's tabulated BSDF on an object (PNG and EXR)");
    render_cmd->add_option("file", rnd.input, "HDF5 result file of gonio run")->required();
    render_cmd->add_option("-o,--output", rnd.output, "Output .png (an .exr beside it)")
        ->required();
    render_cmd->add_option("--case", rnd.case_name, "The case (default: the only one)");
    render_cmd
        ->add_option("--compare", rnd.compare,
                     "l1: also without multiple scattering; model: simulated L1 against "
                     "Model L1; both write the Delta E00 image")
        ->check(CLI::IsMember({"l1", "model"}));
    render_cmd->add_option("--spp", rnd.settings.spp, "Samples per pixel (default 64)")
        ->check(CLI::Range(1, 1 << 20));
    render_cmd->add_option("--size", render_size, "WxH (default 400x300)");
    render_cmd->add_option("--object", rnd.object, "sphere (default) or torus")
        ->check(CLI::IsMember({"sphere", "torus"}));
    render_cmd->add_option("--env", rnd.env, "uniform, sky (default) or a lat-long FILE.exr");
    render_cmd->add_option("--light", render_light,
                           "theta,phi in degrees: a directional light from there");
    render_cmd->add_option("--depth", rnd.settings.max_depth, "Path vertices (default 5)")
        ->check(CLI::Range(1, 64));
    render_cmd->add_option("--seed", rnd.settings.seed, "Random seed (default 1)");
    render_cmd->add_flag("--overwrite", rnd.overwrite, "Replace existing images");
    render_cmd->add_flag("-q,--quiet", rnd.quiet, "No progress");
    render_cmd->add_option("--threads", rnd.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 1024));

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : 2;
    }
    try {
        if (*model_cmd) return gonio::run_model_command(model);
        if (*surface_cmd) return gonio::run_surface_command(surface);
        if (*run_cmd) {
            run.quiet = run.quiet || job.rank != 0;
            return gonio::run_run_command(run);
        }
        if (*ndf_cmd) return gonio::run_ndf_command(ndf);
        if (*compare_cmd) return gonio::run_compare_command(compare_path);
        if (*info_cmd) return gonio::run_info_command(info_path, info_json);
        if (*keys_cmd) return gonio::run_keys_command(keys_markdown);
        if (*export_cmd) return gonio::run_export_command(exp);
        if (*merge_cmd)
            return gonio::run_merge_command(merge_parts, merge_output, merge_overwrite, merge_quiet,
                                            merge_threads);
        if (*cache_cmd) return gonio::run_cache_command(cache_action, cache_dir);
        if (*render_cmd) {
            int w = 0, h = 0;
            char x = 0, rest = 0;
            if (std::sscanf(render_size.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || x != 'x' ||
                w < 8 || h < 8 || w > 8192 || h > 8192)
                throw gonio::RenderArgumentError("--size " + render_size +
                                                 ": expected WxH, each in [8, 8192]");
            rnd.settings.width = w;
            rnd.settings.height = h;
            if (!render_light.empty()) {
                double theta = 0, phi = 0;
                if (std::sscanf(render_light.c_str(), "%lf,%lf%c", &theta, &phi, &rest) != 2 ||
                    theta < 0 || theta >= 90)
                    throw gonio::RenderArgumentError(
                        "--light " + render_light +
                        ": expected theta,phi in degrees, theta in [0, 90)");
                rnd.settings.light = true;
                rnd.settings.light_direction =
                    gonio::spherical_direction(gonio::radians(theta), gonio::radians(phi));
            }
            return gonio::run_render_command(rnd);
        }
    } catch (const gonio::RenderArgumentError& e) {
        std::fprintf(stderr, "gonio render: error: %s\n", e.what());
        return 2;
    } catch (const gonio::ConfigError& e) {
        std::fprintf(stderr, "gonio: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gonio: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
