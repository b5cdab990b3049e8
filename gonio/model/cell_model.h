#pragma once
// A model as gonio holds it against the simulation: evaluated on the sensor's cells at one
// incidence. Analytic models (a BrdfModel integrated over each cell: IntegratedModel) and Monte
// Carlo estimators (the V-cavity) share this interface and give the same record, so the
// comparison, the work units and the result file need to know nothing else about a model.
#include "core/enum_names.h"
#include "core/math.h"
#include "gonio/model/brdf_model.h"
#include "gonio/model/cell_integrator.h"
#include "heightfield/heightfield.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace gonio {

// The simulated quantity a model is held against: single scattering, every order, or (for the
// part of a multiple-scattering model beyond its single scattering) orders 2 and up.
enum class ModelTarget { l1, linf, l2plus };
template <>
struct EnumNames<ModelTarget> {
    static constexpr const char* what = "simulated quantity";
    static constexpr const char* names[] = {"l1", "linf", "l2plus"};
};

// One model at one incidence. Arrays are [cell][channel] (energies, fractions of the incident
// power) or [channel] (albedos).
struct ModelIncidence {
    std::vector<double> energy;
    double seconds = 0;            // wall time of the evaluation (provenance, not data)
    double relative_tolerance = 0; // analytic models: the quadrature's, taken as an error bound
    // Monte Carlo models: the batches whose mean `energy` is ([batch][cell][channel]), the
    // albedo's standard error, the single-scattering part and the albedos of order 1, 2, 2 and up.
    int batches = 0;
    std::vector<double> energy_batches;
    std::vector<double> albedo_stderr;
    std::vector<double> l1_energy;
    std::vector<double> l1_albedo, l2_albedo, l2plus_albedo;
    // Models of every order that know their single scattering (the Monte Carlo ones, the
    // compensated analytic ones): l1_energy above ([cell][channel]) and, when Monte Carlo, its
    // batches, so that their orders 2 and up are held against simulated L2+ too.
    std::vector<double> l1_energy_batches;
    // Monte Carlo models of every order: the albedo of orders 1, 2 and 3 and up
    // ([order][channel], kOrderBins orders) with standard errors, reflected and (for transmissive
    // facets) transmitted.
    static constexpr int kOrderBins = 3;
    std::vector<double> order_albedo, order_albedo_stderr;
    std::vector<double> order_transmittance, order_transmittance_stderr;
    bool monte_carlo() const { return batches > 0; }
    bool has_orders() const { return !l1_energy.empty(); }
};

struct TraceResult;
// A Monte Carlo model's record from its estimate, binned in orders 1, 2 and 3 and up
// (TraceSettings::orders = 2): every order, order 1 and the albedos of each.
ModelIncidence monte_carlo_incidence(const TraceResult& estimate);

class CellModel {
  public:
    virtual ~CellModel() = default;
    // The model at incidence wi (unit, wi.z > 0) on every cell of `sensor`. Monte Carlo models
    // draw from the random streams of (seed, stream), so the result is a function of them.
    virtual ModelIncidence evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t seed,
                                    std::uint64_t stream) const = 0;
    // Models of the surface itself (gonio/masking/surface_point_model.cpp) take every surface of
    // an ensemble: surface r (r = 1, 2, ... in order; the first came with the model) ...
    virtual void add_surface(const HeightField&) {}
    // ... and evaluate an incidence on the first `surfaces` of them (the incidence's own, so that
    // a unit's result does not depend on which units a process traced before it).
    virtual ModelIncidence evaluate_on(const Vec3& wi, const BeckersSensor& sensor,
                                       std::uint64_t seed, std::uint64_t stream,
                                       int surfaces) const {
        (void)surfaces;
        return evaluate(wi, sensor, seed, stream);
    }
};

// An analytic BRDF, its f cos(theta_o) integrated over each cell (cell_integrator.h).
class IntegratedModel final : public CellModel {
  public:
    IntegratedModel(std::unique_ptr<BrdfModel> model, const CellQuadrature& quadrature)
        : model_(std::move(model)), quadrature_(quadrature) {}
    ModelIncidence evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t seed,
                            std::uint64_t stream) const override;

  private:
    std::unique_ptr<BrdfModel> model_;
    CellQuadrature quadrature_;
};

} // namespace gonio
