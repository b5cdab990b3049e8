#pragma once
// The registry of models ([model] models): each kind declares its keys and reads its settings
// into a ModelChoice, which builds the model when the case runs. A model also says which facets
// it suits and which simulated quantity it is held against. Config loading, `gonio keys` and the
// configuration table (docs/configuration.md) come from this list.
#include "core/config_key.h"
#include "core/table_reader.h"
#include "gonio/material/material_kind.h"
#include "gonio/model/brdf_model.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/cell_model.h"
#include "gonio/trace/trace_backend.h"
#include "heightfield/heightfield.h"
#include "heightfield/ndf/ndf.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

// What every model of a case shares: the facets, the distribution, the masking term, the cell
// quadrature, and the trace's settings that Monte Carlo models follow.
struct ModelContext {
    const FacetSpec& facets;
    std::shared_ptr<const Ndf> ndf;
    MaskingForm masking;
    CellQuadrature quadrature;
    long long trace_rays;            // the case's rays per incidence (the V-cavity's default)
    int max_bounces;                 // the case's bounce cap
    const TraceBackendKind* backend; // the case's (models that trace the surface)
};

struct ModelChoice {
    std::string name;        // the kind's name
    std::string description; // with its settings, for the file
    ModelTarget compared_with = ModelTarget::l1;
    bool needs_surface = false; // fitted to the traced surface (the P-BRDF)
    bool monte_carlo = false;   // an estimate with batches (the V-cavity), not a quadrature
    // The model, ready to evaluate on the cells; `surface` is the case's first surface (null
    // unless needs_surface).
    std::function<std::unique_ptr<CellModel>(const HeightField* surface)> build;
};

// The builder of an analytic model: make(surface) integrated over the cells with the case's
// quadrature.
template <class Make>
std::function<std::unique_ptr<CellModel>(const HeightField*)> integrated(const ModelContext& c,
                                                                         Make make) {
    return [quadrature = c.quadrature, make](const HeightField* s) -> std::unique_ptr<CellModel> {
        return std::make_unique<IntegratedModel>(make(s), quadrature);
    };
}

struct ModelKind {
    std::string name;
    std::string summary;
    std::vector<Key> keys; // in [model]
    // Reads the kind's keys from [model]; refuses (r.fail on `models`) facets it does not suit.
    ModelChoice (*create)(TableReader& r, const ModelContext& context);
};

const std::vector<const ModelKind*>& model_kinds();
// [model]: the common keys, the models chosen and their settings.
struct ModelSettings {
    MaskingForm masking = MaskingForm::height_correlated;
    CellQuadrature quadrature;
    std::vector<ModelChoice> models; // empty with evaluate = false
};
ModelSettings read_models(TableReader r, const FacetSpec& facets, std::shared_ptr<const Ndf> ndf,
                          long long trace_rays, int max_bounces, const TraceBackendKind* backend);
std::vector<KeyGroup> model_key_groups();
std::vector<KeyGroup> ashikhmin_key_groups(); // the nested table model.ashikhmin

const ModelKind& l1_model_kind();
const ModelKind& il_model_kind();
const ModelKind& vcavity_model_kind();
const ModelKind& heitz16_model_kind();
const ModelKind& kulla_conty_model_kind();
const ModelKind& turquin_model_kind();
const ModelKind& ashikhmin_model_kind();
const ModelKind& pbrdf_model_kind();
// The decomposition of simulated L1 - Model L1 (gonio/masking/surface_point_model.cpp).
const ModelKind& smith_measured_ndf_model_kind();
const ModelKind& measured_g1_model_kind();
const ModelKind& measured_model_kind();

} // namespace gonio
