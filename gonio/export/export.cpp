#include "gonio/export/export.h"

#include "core/output_files.h"
#include "core/registry.h"
#include "gonio/export/atomic_output.h"
#include "gonio/export/export_formats.h"

#include <chrono>
#include <cmath>

namespace gonio {

const std::vector<const ExportFormat*>& export_formats() {
    static const std::vector<const ExportFormat*> formats{&rgl_format(), &merl_format(),
                                                          &astm_format(), &albedo_format()};
    return formats;
}

void check_export_options(const ExportOptions& o) {
    if (!o.format) throw std::invalid_argument("no format (--format)");
    if (o.output.empty()) throw std::invalid_argument("no output file (-o)");
    if (same_file(o.output, o.input))
        throw std::invalid_argument(o.output + ": the output is the input");
    if (o.rgb && !o.format->rgb_option)
        throw std::invalid_argument("--rgb does not apply to the " + std::string(o.format->name) +
                                    " format");
    if (!o.sweep.empty() && !o.format->sweep_option)
        throw std::invalid_argument("--sweep does not apply to the " + std::string(o.format->name) +
                                    " format");
}

const ExportFormat& export_format_named(const std::string& name) {
    return find_named(export_formats(), name, "format");
}

TableOrder requested_order(const ExportOptions& o, bool transmission_allowed) {
    if (o.orders == TableOrder::transmission && !transmission_allowed)
        throw ExportRefused(std::string(o.format->name) +
                            " holds reflection only: --orders t (transmission) cannot be "
                            "written to it");
    return o.orders;
}

void require_hemisphere_sweep(const BsdfTable& t, const std::string& format) {
    const auto& theta = t.theta_nodes();
    double widest = 0;
    for (size_t k = 1; k < theta.size(); ++k) widest = std::max(widest, theta[k] - theta[k - 1]);
    std::string why;
    if (theta.front() > 1)
        why = "it starts at theta_i = " + std::to_string(theta.front());
    else if (theta.back() < 80)
        why = "it ends at theta_i = " + std::to_string(theta.back());
    else if (widest > 10)
        why = "it has a gap of " + std::to_string(widest) + " degrees";
    if (!why.empty())
        throw ExportRefused("the sweep is too sparse for " + format + " (" + why +
                            "): it needs theta_i from 0 to at least 80 degrees in steps of at "
                            "most 10");
}

BsdfTable load_table(const ResultCase& c, TableOrder order, const std::string& format) {
    if (!c.simulated)
        throw ExportRefused(c.file + ": case " + c.name +
                            " holds models only (gonio model): no simulated orders to export to " +
                            format);
    if (order == TableOrder::transmission && !c.transmits)
        throw ExportRefused(c.file + ": case " + c.name + " (" + c.material +
                            ") transmits nothing: it has no lower sensor");
    TableData d = table_data(c, order); // an unreadable file is an error, not a refusal
    try {
        return BsdfTable(std::move(d));
    } catch (const std::invalid_argument& e) {
        throw ExportRefused(std::string(e.what()));
    }
}

ExportReport export_result(const ExportOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    check_export_options(o); // (the command line checks them first, as usage errors)
    const ExportFormat& format = *o.format;
    // With --sweep the albedo table reads every case; the first one stands for the file here.
    const ResultCase c = read_result_case(
        o.input, o.sweep.empty() ? o.case_name : [&] {
            return o.case_name.empty() ? read_result_case_names(o.input).front() : o.case_name;
        }());
    ExportReport report;
    report.output = o.output;
    AtomicOutput out(o.output, o.overwrite, format.binary);
    format.write(c, o, out.stream(), report);
    report.bytes = out.commit();
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

} // namespace gonio
