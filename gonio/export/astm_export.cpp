// ASTM E1392 text as BRDF tools read it (libbsdf's AstmReader, ALTA's data_astm): header lines
// "KEYWORD value" ending with NUM_POINTS and VARS, then one comma-separated row per sample with
// theta_i, phi_i, theta_s, phi_s in radians and one column per channel (`<lambda>nm` for spectral
// channels). gonio writes one row per swept incidence and sensor cell centre, the cell averages
// as stored (no interpolation); transmission (--orders t) as MEAS_NAME BTDF, theta_s measured from
// the lower pole (cell k of the lower sensor mirrors upper cell k).
#include "core/number_text.h"
#include "gonio/export/export_formats.h"
#include "gonio_version.h"

#include <cmath>

namespace gonio {

static void write_astm(const ResultCase& c, const ExportOptions& o, std::ostream& out,
                       ExportReport& report) {
    const TableOrder order = requested_order(o, true);
    if (!c.simulated)
        throw ExportRefused(c.file + ": case " + c.name +
                            " holds models only (gonio model): no simulated orders to export");
    if (order == TableOrder::transmission && !c.transmits)
        throw ExportRefused("case " + c.name + " (" + c.material +
                            ") transmits nothing: it has no BTDF to export");
    const TableData d = table_data(c, order);
    const BeckersSensor sensor(d.cells);
    const size_t nt = d.theta_i_deg.size(), np = d.phi_i_deg.size(), C = size_t(d.channels);
    const bool btdf = order == TableOrder::transmission;
    out << "SOURCE gonio " << kVersion << " (git " << kGitHash << "), virtual gonioreflectometer\n"
        << "SAMPLE_NAME \"" << c.name << "\"\n"
        << "FILE_NAME \"" << c.file << "\"\n"
        << "MEAS_NAME " << (btdf ? "BTDF" : "BRDF") << "\n"
        << "ORDERS " << name_of(order) << "\n"
        << "SENSOR_CELLS " << d.cells << " (Beckers equal-area; theta_s, phi_s at cell centres"
        << (btdf ? ", theta_s from the lower pole" : "") << ")\n"
        << "NUM_POINTS " << nt * np * size_t(d.cells) << "\n"
        << "VARS theta_i,phi_i,theta_s,phi_s";
    if (C == 1 && c.wavelength_nm.empty())
        out << (btdf ? ",BTDF" : ",BRDF");
    else
        for (size_t ch = 0; ch < C; ++ch) out << "," << shortest(c.wavelength_nm[ch]) << "nm";
    out << "\n";
    for (size_t ti = 0; ti < nt; ++ti)
        for (size_t pj = 0; pj < np; ++pj) {
            const std::string incidence = shortest(radians(d.theta_i_deg[ti])) + "," +
                                          shortest(radians(d.phi_i_deg[pj])) + ",";
            for (int cell = 0; cell < d.cells; ++cell) {
                const SensorCell& s = sensor.cell(cell);
                out << incidence << shortest(s.theta_center) << "," << shortest(s.phi_center);
                const double* v = d.f.data() + ((ti * np + pj) * size_t(d.cells) + cell) * C;
                for (size_t ch = 0; ch < C; ++ch) out << "," << shortest(v[ch]);
                out << "\n";
            }
        }
    report.notes.push_back(std::to_string(nt * np * size_t(d.cells)) + " rows (" +
                           std::to_string(nt * np) + " incidences x " + std::to_string(d.cells) +
                           " cells)");
}

const ExportFormat& astm_format() {
    static const ExportFormat f{"astm", "ASTM E1392 text, one row per incidence and cell centre",
                                false,  false,
                                false,  write_astm};
    return f;
}

} // namespace gonio
