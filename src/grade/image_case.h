// An image case: one scene rendered with given settings for an image
// check, as a manifest describes it:
//
//   {"label": "jittered samples", "scene": "scenes/cbox_spheres.json",
//    "integrator": "normals", "width": 64, "height": 64, "spp": 8,
//    "converged_spp": 1024}
//
// Optional keys: "bias_spp" (samples per pixel of the student's render for
// the bias test of noise_rule.h; default 16 x spp, at most converged_spp, or
// spp itself when spp = converged_spp, i.e. when there is no noise),
// "light_samples", "max_depth" (0: emission only), "accumulate_bounces",
// "direct" (light | hemisphere | mis), "russian_roulette" (true; false is
// --rr-depth off), "rr_depth" (3: bounces before roulette), "max_mean_spp" (turns adaptive
// sampling on with `spp` as the maximum; the mean number of samples per
// pixel may not exceed it: adaptive sampling must stop), with
// "samples_per_batch" (32) and "max_tolerance" (0.05) as -a N TOL.
// Without adaptive sampling every pixel must report exactly `spp` samples.
// With it, the converged reference is rendered without it (unbiased, every
// pixel at converged_spp), the reference runs at `spp` with it (the noise
// to expect), and the bias test weighs each pixel by the samples it took.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "render/renderer.h"
#include "stages/settings.h"
#include "scene/scene.h"
#include "stages/stages.h"

namespace pt {

struct ImageCase {
    std::string label;            ///< shown in the report
    std::string scene;            ///< path relative to the assets folder
    int width = 64, height = 64;  ///< film size, pixels
    RenderSettings settings;      ///< spp is the student's sample count
    int converged_spp = 1024;     ///< samples per pixel of the converged reference
    int bias_spp = 16;            ///< samples per pixel of the student's render for the bias test
    std::optional<double> max_mean_spp;  ///< adaptive sampling: limit on the mean samples per pixel
};

/// Parses one entry of an image task's "cases"; throws InputError naming
/// `where` for unknown keys or bad values.
ImageCase parse_image_case(const nlohmann::json& j, const std::string& where);

/// The case's scene from `assets_dir`, at the case's film size.
Scene load_case_scene(const ImageCase& c, const std::string& assets_dir);

/// A fingerprint of the case's inputs: the scene file, the meshes and
/// material files it names, and the render settings (not spp or seed).
/// Reference renders are cached under it.
std::string case_fingerprint(const ImageCase& c, const std::string& assets_dir);

/// Renders the case with `stages` at `spp` samples per pixel and `seed`.
RenderResult render_case(const Scene& scene, const ImageCase& c, const Stages& stages, int spp,
                         uint64_t seed, int threads);

}  // namespace pt
