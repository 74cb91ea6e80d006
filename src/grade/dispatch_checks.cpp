// Part 3, one_bounce_radiance: that it picks the estimator the settings
// ask for (context.settings.direct: hemisphere, light, mis) and returns its
// estimate unchanged. At shading points of the graded scene, with the same
// random numbers (copies of one Rng), one_bounce_radiance must equal the
// chosen estimator's value: the student's own estimator (what their
// one_bounce calls) or the reference's (a table whose estimators are the
// reference's). Deterministic, and an estimator's bug is charged to that
// estimator's task alone, which an image of one_bounce_radiance could not
// do: the student's one_bounce calls the student's estimators directly.
#include <cmath>

#include "core/error.h"
#include "grade/bvh_inputs.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "render/integrators.h"
#include "stages/direct.h"
#include "stages/render_context.h"

namespace pt {
namespace {

bool same_value(const Color& a, const Color& b) {
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(a[c] - b[c]) <= 1e-12 * std::max(1.0, std::fabs(b[c])))) return false;
    return true;
}

std::string format_color(const Color& c) {
    return format_vec(Vec3(c.r, c.g, c.b));
}

/// The estimator `strategy` names in a direct stage.
DirectEstimateFn estimator(const DirectStage& stage, DirectStrategy strategy) {
    switch (strategy) {
        case DirectStrategy::hemisphere:
            return stage.estimate_direct_lighting_hemisphere;
        case DirectStrategy::light:
            return stage.estimate_direct_lighting_importance;
        case DirectStrategy::mis:
            return stage.estimate_direct_lighting_mis;
    }
    return nullptr;
}

const char* estimator_name(DirectStrategy strategy) {
    switch (strategy) {
        case DirectStrategy::hemisphere:
            return "estimate_direct_lighting_hemisphere";
        case DirectStrategy::light:
            return "estimate_direct_lighting_importance";
        case DirectStrategy::mis:
            return "estimate_direct_lighting_mis";
    }
    return "?";
}

/// The estimate of `fn` with a copy of `rng`; nothing when the student's
/// estimator is still a stub.
std::optional<Color> estimate(DirectEstimateFn fn, const RenderContext& context, const Ray& ray,
                              const SurfaceInteraction& isect, Rng rng) {
    try {
        return fn(context, ray, isect, rng);
    } catch (const NotImplemented&) {
        return std::nullopt;
    }
}

}  // namespace

TaskResult check_one_bounce_radiance(const TaskSpec& spec, const GradeEnvironment& env) {
    Scene scene = load_graded_scene(env, param(spec, "scene", std::string("scenes/cbox.json")));
    const int points = param(spec, "points", 200);
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, env.reference, AcceleratorSettings{});
    std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::direct);
    Rng rng = check_rng(env.seed, "one_bounce_radiance");
    const DirectStrategy strategies[] = {DirectStrategy::hemisphere, DirectStrategy::light,
                                         DirectStrategy::mis};
    CaseLog log;
    for (DirectStrategy strategy : strategies) {
        for (int light_samples : {1, 3}) {
            RenderSettings settings;
            settings.integrator = IntegratorKind::direct;
            settings.direct = strategy;
            settings.light_samples = light_samples;
            // The reference everywhere around the functions called, so that
            // both sides see the same BSDF and the same scene.
            RenderContext context{scene, *accelerator, env.reference, settings, *integrator};
            log.category(std::string("--direct ") + to_string(strategy));
            for (int i = 0; i < points; ++i) {
                Ray ray = env.reference.camera.generate_ray(scene.camera, rng.next_1d(),
                                                            rng.next_1d(), rng.next_2d());
                std::optional<SurfaceInteraction> isect = context.intersect(ray);
                if (!isect) continue;
                Rng stream(env.seed, uint64_t(i), uint64_t(light_samples));
                Rng copy = stream;
                std::optional<Color> own =
                    estimate(estimator(env.student.direct, strategy), context, ray, *isect, stream);
                // A student estimator still a stub (task 3.8 before 3.6 is done) is
                // graded by its own task: its strategy cannot be checked here.
                if (!own && strategy == DirectStrategy::mis) break;
                Color got = env.student.direct.one_bounce_radiance(context, ray, *isect, copy);
                std::optional<Color> ref = estimate(estimator(env.reference.direct, strategy),
                                                    context, ray, *isect, stream);
                if ((own && same_value(got, *own)) || (ref && same_value(got, *ref))) {
                    log.agreed();
                    continue;
                }
                std::string instead;  // what it equals, if another estimator
                for (DirectStrategy other : strategies) {
                    if (other == strategy) continue;
                    std::optional<Color> o = estimate(estimator(env.student.direct, other), context,
                                                      ray, *isect, stream);
                    if (o && same_value(got, *o))
                        instead = "; it equals " + std::string(estimator_name(other)) +
                                  "'s: does it dispatch on context.settings.direct?";
                }
                log.mismatch("-l " + std::to_string(light_samples) + ", the camera ray through " +
                             format_vec(isect->p) + ": one_bounce_radiance returns " +
                             format_color(got) + ", but " + estimator_name(strategy) + " returns " +
                             format_color(own ? *own : *ref) + " with the same random numbers" +
                             instead);
            }
        }
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "the estimator the settings choose");
}

}  // namespace pt
