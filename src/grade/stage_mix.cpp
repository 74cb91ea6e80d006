#include "grade/stage_mix.h"

#include "core/error.h"
#include "stages/render_context.h"

namespace pt {
namespace {

// One entry per slot: which stage it belongs to and how to copy it. When a
// part lands with new stages or functions, add their slots here.
struct Slot {
    const char* name;
    Stage stage;
    void (*copy)(Stages& to, const Stages& from);
};

#define PT_FUNCTION_SLOT(stage_name, member)                                                       \
    {                                                                                              \
#stage_name "." #member, Stage::stage_name,                                                \
            [](Stages & to, const Stages& from) { to.stage_name.member = from.stage_name.member; } \
    }

const Slot kSlots[] = {
    {"camera", Stage::camera, [](Stages& to, const Stages& from) { to.camera = from.camera; }},
    PT_FUNCTION_SLOT(camera, generate_ray),
    PT_FUNCTION_SLOT(camera, raytrace_pixel),
    {"intersect", Stage::intersect,
     [](Stages& to, const Stages& from) { to.intersect = from.intersect; }},
    PT_FUNCTION_SLOT(intersect, intersect_triangle),
    PT_FUNCTION_SLOT(intersect, intersect_sphere),
    {"bvh", Stage::bvh, [](Stages& to, const Stages& from) { to.bvh = from.bvh; }},
    {"direct", Stage::direct, [](Stages& to, const Stages& from) { to.direct = from.direct; }},
    PT_FUNCTION_SLOT(direct, diffuse_f),
    PT_FUNCTION_SLOT(direct, diffuse_sample_f),
    PT_FUNCTION_SLOT(direct, zero_bounce_radiance),
    PT_FUNCTION_SLOT(direct, estimate_direct_lighting_hemisphere),
    PT_FUNCTION_SLOT(direct, estimate_direct_lighting_importance),
    PT_FUNCTION_SLOT(direct, one_bounce_radiance),
    PT_FUNCTION_SLOT(direct, power_heuristic),
    PT_FUNCTION_SLOT(direct, balance_heuristic),
    PT_FUNCTION_SLOT(direct, estimate_direct_lighting_mis),
    {"adaptive", Stage::adaptive,
     [](Stages& to, const Stages& from) { to.adaptive = from.adaptive; }},
    PT_FUNCTION_SLOT(adaptive, has_converged),
    {"global", Stage::global, [](Stages& to, const Stages& from) { to.global = from.global; }},
    PT_FUNCTION_SLOT(global, at_least_one_bounce_radiance),
    PT_FUNCTION_SLOT(global, est_radiance_global_illumination),
    {"sampler", Stage::sampler, [](Stages& to, const Stages& from) { to.sampler = from.sampler; }},
    PT_FUNCTION_SLOT(sampler, stratified_sample_2d),
    PT_FUNCTION_SLOT(sampler, scrambled_radical_inverse),
    {"photon", Stage::photon, [](Stages& to, const Stages& from) { to.photon = from.photon; }},
    PT_FUNCTION_SLOT(photon, emit_photon),
    PT_FUNCTION_SLOT(photon, build_kdtree),
    PT_FUNCTION_SLOT(photon, k_nearest),
    PT_FUNCTION_SLOT(photon, density_estimate),
    {"media", Stage::media, [](Stages& to, const Stages& from) { to.media = from.media; }},
    PT_FUNCTION_SLOT(media, homogeneous_transmittance),
    PT_FUNCTION_SLOT(media, sample_distance),
    PT_FUNCTION_SLOT(media, hg_phase),
    PT_FUNCTION_SLOT(media, sample_hg),
    PT_FUNCTION_SLOT(media, in_scattered_radiance),
    {"bdpt", Stage::bdpt, [](Stages& to, const Stages& from) { to.bdpt = from.bdpt; }},
    PT_FUNCTION_SLOT(bdpt, random_walk),
    PT_FUNCTION_SLOT(bdpt, connect),
    PT_FUNCTION_SLOT(bdpt, mis_weight),
};

#undef PT_FUNCTION_SLOT

}  // namespace

/// The reference's one_bounce_radiance, but calling the estimators of the
/// context's stage table: the reference's own calls its estimators
/// directly, so a student estimator switched into the table alone would
/// never run.
Color one_bounce_through_table(const RenderContext& context, const Ray& ray,
                               const SurfaceInteraction& isect, Rng& rng) {
    const DirectStage& stage = context.stages.direct;
    switch (context.settings.direct) {
        case DirectStrategy::hemisphere:
            return stage.estimate_direct_lighting_hemisphere(context, ray, isect, rng);
        case DirectStrategy::light:
            return stage.estimate_direct_lighting_importance(context, ray, isect, rng);
        case DirectStrategy::mis:
            return stage.estimate_direct_lighting_mis(context, ray, isect, rng);
    }
    return Color(0);
}

std::vector<std::string> known_slots() {
    std::vector<std::string> names;
    for (const Slot& s : kSlots)
        names.push_back(s.name);
    return names;
}

Stages mix_stages(const Stages& reference, const Stages& student,
                  const std::vector<std::string>& slots, const std::string& where) {
    Stages mixed = reference;
    StageSet set = StageSet::none();
    bool estimator = false, one_bounce = false;
    for (const std::string& name : slots) {
        const Slot* found = nullptr;
        for (const Slot& s : kSlots)
            if (name == s.name) found = &s;
        if (!found) {
            std::string list;
            for (const std::string& n : known_slots())
                list += (list.empty() ? "" : ", ") + n;
            throw InputError(where + ": unknown student function \"" + name + "\" (known: " + list +
                             ")");
        }
        found->copy(mixed, student);
        set = set.with(found->stage);
        estimator = estimator || name.rfind("direct.estimate_", 0) == 0;
        one_bounce = one_bounce || name == "direct" || name == "direct.one_bounce_radiance";
    }
    if (estimator && !one_bounce) mixed.direct.one_bounce_radiance = one_bounce_through_table;
    mixed.student = set;
    return mixed;
}

}  // namespace pt
