#pragma once
// The tabulated BSDF of a simulated case (R19 section 4, step 4 of Figure 4): a continuous
// f(wi, wo) from the per-incidence sensor histograms of one order (L1, L2+, L-infinity, or the
// transmitted lobe), with eval, importance sampling and its exact pdf.
//
// Across the sensor, each incidence's lobe is interpolated between neighbouring cell centres
// (sensor_lobe.h) and rescaled so that its integral is the table's own albedo, sum f_c Omega_perp_c
// (interpolation keeps energy). Across incidences it is linear in theta_i (clamped at the ends of
// the sweep) and, for anisotropic cases, linear in phi_i with wrapping over the full turn. An
// isotropic case is rotated instead: the lobe swept at phi_i is turned to the query's azimuth
// (R19 sweeps isotropic cases at phi_i = 0 only); several swept azimuths are averaged, and a
// lobe swept at phi_i = 0 or 180 degrees is averaged with its mirror image in the plane of
// incidence (an isotropic BSDF's symmetry).
//
// f is a mixture of node lobes with non-negative weights, so sampling picks a node in proportion
// to weight times node integral and then samples that node's lobe exactly: the pdf returned is
// the mixture's, exactly proportional to the sampling scalar (the mean over channels) times cos.
#include "core/enum_names.h"
#include "core/math.h"
#include "gonio/table/sensor_lobe.h"
#include "sensor/beckers_sensor.h"

#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct ResultCase;

// The orders a table is built from: single scattering, multiple, every order, transmission.
enum class TableOrder { l1, l2plus, linf, transmission };
template <>
struct EnumNames<TableOrder> {
    static constexpr const char* what = "order";
    static constexpr const char* names[] = {"l1", "l2plus", "linf", "t"};
};

// What a table is built from: one order of one case's sweep.
struct TableData {
    std::vector<double> theta_i_deg, phi_i_deg; // the sweep, in any order
    int cells = 0, channels = 1;
    std::vector<double> f;             // [theta_i][phi_i][cell][channel], 1/sr: cell averages
    std::vector<double> f_stderr;      // the same layout (empty when unknown)
    std::vector<double> albedo_stderr; // [theta_i][phi_i][channel] (empty when unknown)
    bool isotropic = true;
    bool transmission = false; // the lobes lie on the lower sensor (cell k mirrors upper cell k)
};

// The order's data of a simulated case; throws std::runtime_error with the reason (a model-only
// file, transmission of a material that does not transmit).
TableData table_data(const ResultCase& c, TableOrder order);
// A model's cell averages (`model_<name>`, e.g. Model L1) as a table on the same sweep.
TableData model_table_data(const ResultCase& c, const std::string& model);

class BsdfTable {
  public:
    // Throws std::invalid_argument naming what is wrong (sizes, an anisotropic case not swept
    // around the full turn of phi_i).
    explicit BsdfTable(TableData data);

    int channels() const { return data_.channels; }
    bool isotropic() const { return data_.isotropic; }
    bool transmission() const { return data_.transmission; }
    const TableData& data() const { return data_; }
    const BeckersSensor& sensor() const { return *sensor_; }
    // The sorted, distinct swept angles (degrees; phi_i in [0, 360)).
    const std::vector<double>& theta_nodes() const { return theta_; }
    const std::vector<double>& phi_nodes() const { return phi_; }
    // Whether wi's polar angle lies within the swept range (outside it the nearest is used).
    bool covers(const Vec3& wi, double tolerance_deg = 1e-6) const;

    // f(wi, wo) per channel in 1/sr, without the cosine; wi.z > 0. 0 where wo lies on the other
    // side (below the surface for reflection, above it for transmission).
    void eval(const Vec3& wi, const Vec3& wo, double* f) const;
    // The sampling scalar: the mean of f over channels.
    double eval_mean(const Vec3& wi, const Vec3& wo) const;
    struct Sample {
        Vec3 wo;
        double pdf = 0; // solid angle
    };
    // wo with pdf proportional to eval_mean(wi, wo) |cos theta_o|, from three uniforms in [0, 1).
    // False when the lobe at wi is empty.
    bool sample(const Vec3& wi, double u0, double u1, double u2, Sample& s) const;
    double pdf(const Vec3& wi, const Vec3& wo) const;
    // Integral of f |cos theta_o| over the outgoing hemisphere, per channel (exact).
    void albedo(const Vec3& wi, double* a) const;
    // The table's own albedo at a node, sum_c f_c Omega_perp_c, and its standard error
    // (0 when unknown); indices into theta_nodes() / phi_nodes().
    double node_albedo(int theta_index, int phi_index, int channel) const;
    double node_albedo_stderr(int theta_index, int phi_index, int channel) const;

  private:
    struct Node {
        std::vector<double> f; // [cell][channel], rescaled to keep the node's albedo
        std::vector<double> albedo, albedo_stderr; // per channel
        SensorLobeSampler sampler;                 // on the channel mean
    };
    struct Blend {
        int node = 0;
        double weight = 0;
        double rotation = 0; // radians: the node lobe is evaluated at R_z(rotation) wo
    };
    int blend(const Vec3& wi, Blend* out) const;
    Vec3 to_node(const Vec3& wo, double rotation) const;
    const Node& node(int ti, int pj) const { return nodes_[size_t(ti) * phi_.size() + pj]; }

    TableData data_;
    std::unique_ptr<BeckersSensor> sensor_;
    std::unique_ptr<SensorLobeGrid> grid_;
    std::vector<double> theta_, phi_; // degrees
    std::vector<Node> nodes_;         // [theta][phi]
    int max_blend_ = 4;
};

} // namespace gonio
