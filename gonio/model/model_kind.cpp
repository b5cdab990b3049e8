#include "gonio/model/model_kind.h"

#include "core/registry.h"

namespace gonio {

namespace {
const Key kMasking =
    Key::string("masking", enum_names<MaskingForm>(),
                "G2 of Model L1 and of the IL model: Smith [R19 Eq. 9, 3], Smith "
                "height-direction-correlated [Heitz 2014 Eq. 101] or Torrance-Sparrow [M18 Eq. 15]")
        .fallback(name_of(MaskingForm::height_correlated));
const Key kQuadrature =
    Key::integer("quadrature", {1, 64}, "Gauss-Legendre points per axis inside each cell")
        .fallback(4.0);
const Key kTolerance =
    Key::number("tolerance", {1e-12, 0.1}, "relative tolerance of each cell's integral")
        .fallback(1e-6);
const Key kEvaluate =
    Key::boolean("evaluate", "`false`: no model at all (`gonio run` traces only)").fallback(true);

const Key& models_key() {
    static const Key key = [] {
        std::vector<std::string> names;
        for (const ModelKind* k : model_kinds()) names.push_back(k->name);
        return Key::strings("models", names,
                            "the models evaluated on the cells (each suits some facets: below)")
            .note_default("`\"l1\"` (specular facets), `\"il\"` (diffuse)");
    }();
    return key;
}
} // namespace

const std::vector<const ModelKind*>& model_kinds() {
    static const std::vector<const ModelKind*> kinds = {
        &l1_model_kind(),          &il_model_kind(),          &vcavity_model_kind(),
        &heitz16_model_kind(),     &kulla_conty_model_kind(), &turquin_model_kind(),
        &ashikhmin_model_kind(),   &pbrdf_model_kind(),       &smith_measured_ndf_model_kind(),
        &measured_g1_model_kind(), &measured_model_kind()};
    return kinds;
}

ModelSettings read_models(TableReader r, const FacetSpec& facets, std::shared_ptr<const Ndf> ndf,
                          long long trace_rays, int max_bounces, const TraceBackendKind* backend) {
    ModelSettings s;
    s.masking = enum_named<MaskingForm>(r.string(kMasking));
    s.quadrature.points = static_cast<int>(r.integer(kQuadrature));
    s.quadrature.rel_tol = r.number(kTolerance);
    const bool evaluate = r.boolean(kEvaluate);
    const std::vector<std::string> names =
        r.string_list(models_key().name, models_key().choices,
                      std::vector<std::string>{facets.diffuse ? "il" : "l1"});
    const ModelContext context{facets,     std::move(ndf), s.masking, s.quadrature,
                               trace_rays, max_bounces,    backend};
    // Every chosen kind reads its keys even with evaluate = false, so that they count as used.
    for (const std::string& name : names)
        s.models.push_back(find_named(model_kinds(), name, "model").create(r, context));
    if (!evaluate) s.models.clear();
    return s;
}

std::vector<KeyGroup> model_key_groups() {
    std::vector<KeyGroup> groups{
        {"model", "", "", {models_key(), kMasking, kQuadrature, kTolerance, kEvaluate}}};
    for (const ModelKind* k : model_kinds())
        if (!k->keys.empty()) groups.push_back({"model", k->name, k->summary, k->keys});
    for (const KeyGroup& g : ashikhmin_key_groups()) groups.push_back(g);
    return groups;
}

} // namespace gonio
