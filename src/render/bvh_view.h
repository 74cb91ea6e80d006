// The BVH visualisation of Part 2, as renders:
//
//  - `--bvh-view PATH`: the scene in grey under a headlight, the primitives
//    below the BVH node at PATH (L/R steps from the root: "", "L", "RR"...)
//    tinted, and that node's box drawn as a wireframe, as CS184's BVH viewer
//    shows the root, root-right, root-right-right... of the cow. Edges
//    hidden behind a surface are drawn dimmer.
//  - `--bvh-depth-image FILE.png`: a heat map of the BVH nodes visited by
//    the camera ray of each pixel (black: none; white: the most), where the
//    BVH does its work.
//
// Both are integrators, so the usual renderer (tiles, threads, -s, -r, -p)
// makes them; the app writes them with -f and --bvh-depth-image.
#pragma once

#include <memory>
#include <string>

#include "image/image.h"
#include "render/integrators.h"
#include "stages/bvh.h"

namespace pt {

struct Scene;
class Accelerator;

/// The node at `path` of the accelerator's BVH. Throws InputError (naming
/// --bvh-view) when the accelerator is not a BVH or the path goes below a leaf.
BvhNodeView select_bvh_node(const Accelerator& accel, const std::string& path);

/// The --bvh-view integrator for `node` of a BVH over `scene`, for a film
/// `film_height` pixels high (the wireframe is about 1.5 pixels wide).
std::unique_ptr<Integrator> make_bvh_view_integrator(const Scene& scene, const BvhNodeView& node,
                                                     int film_height);

/// An integrator whose "radiance" is the number of BVH nodes the camera ray
/// visits (grey level = count): the raw data of the depth image.
std::unique_ptr<Integrator> make_bvh_cost_integrator();

/// The heat map of a cost image: 0 black, `max_count` and above white,
/// through purple, red and yellow (a sequential map after matplotlib's
/// "inferno", monotone in lightness so that more work always looks brighter).
Image bvh_cost_heat_map(const Image& counts, double max_count);

}  // namespace pt
