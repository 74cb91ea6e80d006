// BDPT's strategy images (--bdpt-strategies DIR), as in Veach's thesis,
// figure 10.3: for every path length up to a depth, one image per strategy
// (s, t), weighted by its MIS weight and unweighted. The weighted images
// of one length sum to BDPT's image of that many bounces; each unweighted
// one is a complete (noisier) estimate of it on its own.
//
// Layers of the integrator's SplatFilm (render/splat_film.h): layer 0 is
// the image's light tracing; then, for depth d = 0 .. D and s = 0 .. d + 1
// (t = d + 2 - s >= 1), two layers: weighted, unweighted.
#pragma once

#include <string>
#include <vector>

#include "image/image.h"

namespace pt {

/// The first of the two layers of strategy (s, t) (s + t >= 2, t >= 1).
int strategy_layer(int s, int t);
/// Layers after layer 0 for strategy images up to `depth` bounces (0 for depth < 0).
int strategy_layer_count(int depth);
/// Writes the strategy images of RenderResult::layers into `dir`
/// (s<S>_t<T>_weighted.pfm and .png, the same _unweighted, and a grid
/// strategies.png of the weighted ones, a row per depth). Throws on a write failure.
void write_strategy_images(const std::vector<Image>& layers, int depth, const std::string& dir);

}  // namespace pt
