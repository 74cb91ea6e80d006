// Part 7, tasks 1 to 3: bidirectional path tracing.
// Read assignments/part7/README.md first; the contract of each function is
// in src/stages/bdpt.h, the vertices and their densities in
// src/stages/bdpt_vertex.h (convert_density, vertex_f, vertex_pdf,
// pdf_light, vertex_Le, make_surface_vertex are yours to call).
#include "core/error.h"
#include "stages/bdpt.h"
#include "stages/render_context.h"

namespace pt::student {

int random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path) {
    // TODO(part7.1): random_walk, as src/stages/bdpt.h states its contract.
    // [guided]
    // Follow `ray`; at each hit push make_surface_vertex(context, hit, beta)
    // with pdf_fwd = convert_density(pdf_dir, previous vertex, new vertex). Stop after
    // max_vertices vertices. Otherwise sample the BSDF (v.bsdf->sample_f with rng.next_2d()),
    // multiply beta by f |cos| / pdf (in importance mode also by eta^2 and the
    // shading-normal factor of README eq. 5), set the previous vertex's pdf_rev from
    // bsdf.pdf(wi, wo) converted to area there, mark delta samples (pdfs 0), apply Russian
    // roulette after context.settings.rr_depth vertices, and continue. A camera ray
    // (mode radiance) that escapes adds an `escaped` vertex when the scene has an
    // environment. Return the number of vertices added.
    // [/guided]
    (void)context, (void)ray, (void)beta, (void)pdf_dir, (void)max_vertices, (void)mode, (void)rng, (void)path;
    throw NotImplemented(7, "1", "random_walk");
}

Connection connect(const RenderContext& context, const std::vector<PathVertex>& light, int s,
                   const std::vector<PathVertex>& camera, int t, Rng& rng) {
    // TODO(part7.2): connect, as src/stages/bdpt.h states its contract.
    // [guided]
    // Strategy (s, t), README "Connecting". s = 0: camera[t-1]'s own
    // emission (vertex_Le) times its beta. t = 1: camera_sample_Wi towards light[s-1],
    // We / pdf times f |cos| times beta, a visibility test, and camera_vertex / film set.
    // s = 1: the light vertex light[0] (area, point, directional or environment) seen
    // from camera[t-1]. Otherwise beta_y f_y G f_z beta_z with a visibility test.
    // Black whenever a vertex cannot be connected (PathVertex::connectible).
    // [/guided]
    (void)context, (void)light, (void)s, (void)camera, (void)t, (void)rng;
    throw NotImplemented(7, "2", "connect");
}

double mis_weight(const MisVertex* light, int s, const MisVertex* camera, int t, bool delta_light,
                  MisHeuristic heuristic) {
    // TODO(part7.3): mis_weight, as src/stages/bdpt.h states its contract.
    // [guided]
    // The ratio recursion, README eq. 8: walk from the connection
    // towards the camera (camera[t-1] .. camera[1]) and towards the light
    // (light[s-1] .. light[0]) multiplying r by pdf_rev / pdf_fwd (0 counts as 1),
    // adding r (balance) or r^2 (power) for every strategy that can make the path
    // (no edge at a delta vertex; not s = 0 onto a delta light; never t = 0 or (1, 1)).
    // Return 1 / (1 + sum).
    // [/guided]
    (void)light, (void)s, (void)camera, (void)t, (void)delta_light, (void)heuristic;
    throw NotImplemented(7, "3", "mis_weight");
}

}  // namespace pt::student
