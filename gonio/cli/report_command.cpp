// `gonio report RESULT.h5 -o REPORT.html`: one self-contained interactive page per result file
// (gonio/report/report.h).
#include "core/output_files.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/report/report.h"

#include <chrono>
#include <cstdio>
#include <fstream>

namespace gonio {

namespace {
struct ReportArgs {
    ReportSource source;
    std::string output;
    bool overwrite = false, quiet = false;
};

int report(const ReportArgs& a) {
    const auto start = std::chrono::steady_clock::now();
    if (same_file(a.output, a.source.result))
        throw UsageError(a.output + ": the output is the input");
    refuse_existing(a.output, a.overwrite);
    const std::string plotly = read_plotly_js(); // before any work: a missing library fails now
    nlohmann::json data = file_format_of(a.source.result).rfind("gonio-masking", 0) == 0
                              ? masking_report_data(a.source.result)
                              : report_data(a.source);
    const std::string page = report_page(data, plotly);
    OutputSet files(a.overwrite);
    const std::string tmp = files.add(a.output);
    {
        std::ofstream out(tmp, std::ios::binary);
        out.write(page.data(), std::streamsize(page.size()));
        out.close();
        if (!out) throw std::runtime_error(a.output + ": cannot write the report");
    }
    files.commit();
    if (!a.quiet)
        std::printf(
            "wrote %s (%.1f MB, %.2f s; open it in a browser)\n", a.output.c_str(),
            page.size() / 1e6,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto a = std::make_shared<ReportArgs>();
    app.add_option("file", a->source.result, "HDF5 result file of gonio run or gonio model")
        ->required();
    app.add_option("-o,--output", a->output, "The HTML page")->required();
    app.add_option("--image", a->source.images,
                   "A PNG to show with it (gonio render's; repeatable)");
    app.add_option("--fit", a->source.fits,
                   "A fit of one of its cases to show with it (gonio fit -o FIT.json; "
                   "repeatable)");
    app.add_flag("--overwrite", a->overwrite, "Replace an existing output file");
    app.add_flag("-q,--quiet", a->quiet, "Print nothing on success");
    return [a] { return report(*a); };
}
} // namespace

const Command& report_command() {
    static const Command c{"report", "Write an interactive HTML page of a result file", setup};
    return c;
}

} // namespace gonio
