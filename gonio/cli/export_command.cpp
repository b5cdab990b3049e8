// `gonio export FILE --format F -o OUT`: a simulated case in a format other tools read
// (gonio/export/export.h); exit 3 when the format cannot hold the case.
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/export/export.h"

#include <cstdio>

namespace gonio {

namespace {
struct ExportArgs {
    ExportOptions options;
    std::string format, orders = "linf";
};

int export_case(ExportArgs& a) {
    ExportOptions& o = a.options;
    o.format = &export_format_named(a.format); // CLI11 checked the names
    o.orders = enum_named<TableOrder>(a.orders);
    try {
        check_export_options(o);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    refuse_existing(o.output, o.overwrite);
    try {
        const ExportReport r = export_result(o);
        if (!o.quiet) {
            std::printf("%s: %s, %.1f MB in %.2f s\n", r.output.c_str(), o.format->name,
                        r.bytes / 1e6, r.seconds);
            for (const std::string& note : r.notes) std::printf("  %s\n", note.c_str());
        }
        return 0;
    } catch (const ExportRefused& e) {
        std::fprintf(stderr, "gonio export: refused: %s\n", e.what());
        return 3;
    }
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto a = std::make_shared<ExportArgs>();
    std::vector<std::string> names;
    std::string help;
    for (const ExportFormat* f : export_formats()) {
        names.push_back(f->name);
        help += (help.empty() ? "" : "; ") + std::string(f->name) + ": " + f->summary;
    }
    ExportOptions& o = a->options;
    app.add_option("file", o.input, "HDF5 result file of gonio run")->required();
    app.add_option("--format", a->format, help)->required()->check(CLI::IsMember(names));
    app.add_option("-o,--output", o.output, "Output file")->required();
    app.add_option("--case", o.case_name, "The case to export (default: the only one)");
    app.add_option("--orders", a->orders, "l1, l2plus, linf (default) or t (astm)")
        ->check(CLI::IsMember(enum_names<TableOrder>()));
    app.add_flag("--rgb", o.rgb, "rgl: an rgb field (Mitsuba's RGB variants)");
    app.add_option("--sweep", o.sweep,
                   "albedo: every case, with this config key (e.g. ndf.alpha) as a column");
    app.add_flag("--overwrite", o.overwrite, "Replace an existing output file");
    app.add_flag("-q,--quiet", o.quiet, "Print nothing on success");
    return [a] { return export_case(*a); };
}
} // namespace

const Command& export_command() {
    static const Command c{
        "export", "Write a simulated case in a format renderers and BRDF tools read", setup};
    return c;
}

} // namespace gonio
