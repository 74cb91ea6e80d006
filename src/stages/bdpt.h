// Stage `bdpt` (Part 7): bidirectional path tracing (Veach 1997, chapter 10;
// Lafortune and Willems 1993; pbrt-v3 section 16.3).
//
// The measurement of a pixel is an integral over paths x0 .. xk of every
// length (Veach's path integral, eq. 8.7):
//
//     I = sum_k  integral  Le(x0 -> x1) G(x0, x1) prod f(x(i-1) -> xi -> x(i+1)) G(xi, x(i+1))  W(x(k-1) -> xk)  dA(x0) .. dA(xk)
//     G(x, y) = V(x, y) |cos theta_x| |cos theta_y| / |x - y|^2.
//
// BDPT samples a light subpath y0 .. y(s-1) (random_walk from a light) and a
// camera subpath z0 .. z(t-1) (random_walk from the camera), and joins every
// prefix pair by one edge (connect): strategy (s, t) makes a path of
// s + t vertices, that is s + t - 2 bounces. Each (s, t) estimates the same
// paths with a different density p_(s,t); multiple importance sampling
// weighs them (mis_weight):
//
//     w_(s,t) = p_(s,t)^b / sum_i p_(i, s+t-i)^b,   b = 2 (power) or 1 (balance),
//
// computed without the p's themselves from the ratios of neighbouring
// strategies: p_(i+1) / p_i = pdf_fwd(x_i) / pdf_rev(x_i) (Veach eq. 10.9;
// pbrt-v3's MISWeight), vertex by vertex outwards from the connection.
//
// Special strategies: s = 0, the camera subpath hits a light on its own;
// t = 1, a light subpath vertex is joined to the lens (light tracing) and
// its contribution lands on whichever pixel sees it (a splat); s = 1, the
// light subpath's first vertex (its light point) is joined to a camera
// vertex (next-event estimation). Strategy (1, 1), a light seen directly by
// light tracing, is left out, as in pbrt: the path tracer does not draw
// point lights either, and MIS counts only the strategies evaluated.
//
// Depth (-m, -o): a path of s + t vertices has s + t - 2 bounces, counted as
// the path tracer counts them (stages/global.h): -m k keeps s + t - 2 <= k,
// -o 0 only s + t - 2 = k. Camera subpaths have up to k + 1 scattering
// vertices (the last only to find emission), light subpaths up to k.
//
// Tests: tests/bdpt/ (MIS weights summing to 1 against a brute-force
// evaluation; renders matching the path tracer and closed forms by z-test).
#pragma once

#include <optional>
#include <vector>

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "stages/bdpt_vertex.h"
#include "stages/settings.h"

namespace pt {

struct RenderContext;

/// One strategy's estimate, before its MIS weight.
struct Connection {
    Color L;  ///< the path's integrand over its density: radiance (t >= 2) or the value
              ///< of the splat (t = 1); black when the strategy cannot make a path
    std::optional<PathVertex> camera_vertex;  ///< t = 1: the lens point joined to
    Vec2 film;  ///< t = 1: where the camera sees the light vertex (generate_ray's coordinates)
};

/// Extends `path`, whose last vertex is the subpath's start (camera or
/// light vertex), by following `ray`: at every hit a surface vertex with
/// its beta and pdf_fwd (per unit area; per solid angle if the ray escapes
/// and `mode` is radiance with an environment light, which adds an escaped
/// vertex), then a BSDF sample continues the walk, setting the previous
/// vertex's pdf_rev. beta: the subpath's weight on `ray`; pdf_dir: the
/// solid-angle density of ray.d. Adds at most max_vertices vertices;
/// Russian roulette after context.settings.rr_depth of them. Returns how
/// many it added.
using RandomWalkFn = int (*)(const RenderContext& context, const Ray& ray, const Color& beta,
                             double pdf_dir, int max_vertices, Transport mode, Rng& rng,
                             std::vector<PathVertex>& path);
/// Strategy (s, t): joins light[s - 1] and camera[t - 1] (s, t as in the
/// file comment; s <= light.size(), 1 <= t <= camera.size()), with the
/// visibility test, and returns the contribution without its MIS weight.
using ConnectFn = Connection (*)(const RenderContext& context, const std::vector<PathVertex>& light,
                                 int s, const std::vector<PathVertex>& camera, int t, Rng& rng);
/// The MIS weight of strategy (s, t) for the path light[0..s) + camera[t..0]
/// whose densities are given (with the connection's pdf_rev already in
/// place); delta_light: light[0] is a point or directional light (no
/// camera subpath can hit it). Strategies with t = 0 and (1, 1) do not count.
using MisWeightFn = double (*)(const MisVertex* light, int s, const MisVertex* camera, int t,
                               bool delta_light, MisHeuristic heuristic);

struct BdptStage {
    RandomWalkFn random_walk;
    ConnectFn connect;
    MisWeightFn mis_weight;
};

namespace reference {
int random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path);
Connection connect(const RenderContext& context, const std::vector<PathVertex>& light, int s,
                   const std::vector<PathVertex>& camera, int t, Rng& rng);
double mis_weight(const MisVertex* light, int s, const MisVertex* camera, int t, bool delta_light,
                  MisHeuristic heuristic);
}  // namespace reference

namespace student {
int random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path);
Connection connect(const RenderContext& context, const std::vector<PathVertex>& light, int s,
                   const std::vector<PathVertex>& camera, int t, Rng& rng);
double mis_weight(const MisVertex* light, int s, const MisVertex* camera, int t, bool delta_light,
                  MisHeuristic heuristic);
}  // namespace student

// Framework helpers (reference only; students call them).

/// The camera subpath of camera ray `ray`: the camera vertex, then
/// stage.random_walk for up to max_depth + 1 vertices.
std::vector<PathVertex> camera_subpath(const RenderContext& context, const BdptStage& stage,
                                       const Ray& ray, Rng& rng);
/// The start of a light subpath: its light vertex y0 (a light picked by
/// power, a point and a direction from sample_Le) and what random_walk
/// continues with: the ray leaving y0, its weight beta = flux / pick and
/// the solid-angle density of its direction.
struct LightStart {
    PathVertex y0;
    Ray ray;
    Color beta;
    double pdf_dir = 0;
};
/// Nothing without lights or when sample_Le gives no light.
std::optional<LightStart> light_start(const RenderContext& context, Rng& rng);
/// A light subpath: light_start, then stage.random_walk for up to
/// max_depth vertices (empty without lights).
std::vector<PathVertex> light_subpath(const RenderContext& context, const BdptStage& stage, Rng& rng);

/// The MIS weight of the strategy (s, t) whose Connection is `c`: fills in
/// the densities that the connection changes (pdf_rev of the two joined
/// vertices and of their predecessors) and calls stage.mis_weight.
double strategy_weight(const RenderContext& context, const BdptStage& stage,
                       const std::vector<PathVertex>& light, int s,
                       const std::vector<PathVertex>& camera, int t, const Connection& c);

}  // namespace pt
