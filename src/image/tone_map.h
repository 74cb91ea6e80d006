// Tone mapping: what the PNG shows of the linear radiance the renderer
// computed (`--exposure EV`, `--tonemap clamp|reinhard|filmic|local`).
// The result is display-linear in [0, 1]; write_png then applies the sRGB
// transfer function (image/tonemap.h). PFM and EXR outputs are never tone
// mapped: they keep the radiance, which is what metrics compare.
//
// Every operator first scales the radiance by 2^EV (photographic exposure:
// +1 EV doubles the light). Then, with Y the luminance (Rec. 709 weights):
//
//   clamp     each channel clamped to [0, 1]: CS184's output, and the default
//             (with EV 0 the PNG is byte for byte what it was before this flag).
//   reinhard  c Y' / Y with Y' = Y / (1 + Y): the global operator of Reinhard,
//             Stark, Shirley and Ferwerda, "Photographic Tone Reproduction for
//             Digital Images" (SIGGRAPH 2002), eq. 3; hue is kept, highlights
//             approach white smoothly and never clip in luminance.
//   filmic    per channel x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),
//             Narkowicz's fit of the ACES reference rendering transform
//             ("ACES Filmic Tone Mapping Curve", 2016): a toe that deepens the
//             shadows and a shoulder that desaturates highlights, as film does.
//   local     Durand and Dorsey, "Fast Bilateral Filtering for the Display of
//             High-Dynamic-Range Images" (SIGGRAPH 2002): log10 Y is split by
//             an edge-preserving bilateral filter into a base layer (large-scale
//             variation) and a detail layer (log Y - base); only the base is
//             compressed, to a contrast of 100:1 with its brightest point at 1,
//             so local contrast (texture, edges) survives where a global
//             curve would flatten it. Spatial sigma 2% of the image's larger
//             side, range sigma 0.4 decades (the paper's values).
//
// Tests: tests/unit/test_tone_map.cpp (each curve's values, identity of
// clamp at 0 EV, exposure, the bilateral filter keeping an edge and the
// local operator's contrast), tests/cli/test_image_outputs.cpp (the flags).
#pragma once

#include <string>
#include <vector>

#include "image/image.h"

namespace pt {

enum class ToneMap { clamp, reinhard, filmic, local };

struct DisplaySettings {
    ToneMap tone_map = ToneMap::clamp;  ///< --tonemap
    double exposure = 0;                ///< --exposure, in stops (EV): radiance x 2^EV

    /// Whether the transform leaves every pixel as the renderer computed it.
    bool is_identity() const { return tone_map == ToneMap::clamp && exposure == 0; }
};

const char* to_string(ToneMap tone_map);

/// The display-linear image (every component in [0, 1]) of `radiance`.
Image tone_map(const Image& radiance, const DisplaySettings& settings);

/// The bilateral filter of a one-channel image (width x height, row-major):
/// each value replaced by the mean of its neighbours weighted by
/// exp(-d^2 / (2 sigma_s^2)) exp(-(v - v')^2 / (2 sigma_r^2)), d in pixels,
/// over a window of radius ceil(2 sigma_s). Tomasi and Manduchi 1998.
std::vector<float> bilateral_filter(const std::vector<float>& values, int width, int height, double sigma_spatial,
                                    double sigma_range);

}  // namespace pt
