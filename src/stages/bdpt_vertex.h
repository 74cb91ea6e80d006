// Path vertices of bidirectional path tracing (stage `bdpt`, Part 7) and
// the densities that connect them.
//
// A light path x0 x1 ... xk (x0 on a light, xk on the camera) is built from
// a light subpath y0 .. y(s-1) and a camera subpath z0 .. z(t-1), joined by
// one edge (strategy (s, t), s + t = k + 1 vertices, k - 1 bounces). Its
// contribution is the path integrand divided by the density of the path
// measured per unit area at every vertex (Veach 1997 section 8.2, the
// area-product measure). So each vertex keeps
//
//   pdf_fwd   the density, per unit area at this vertex, with which the
//             subpath that made it sampled it from the vertex before;
//   pdf_rev   the density with which the *other* subpath would have sampled
//             it, coming from the vertex after (filled in as the walk goes
//             and, for the vertices next to the connection, by connect).
//
// A density per solid angle at x becomes one per unit area at y by
//     p_A(y) = p_omega * |cos theta_y| / |x - y|^2          (Veach eq. 8.10)
// (convert_density). Vertices at infinity (a camera ray that escaped to
// the environment, a light subpath that starts at a directional or
// environment light) keep densities per unit solid angle, and the vertex
// after a light at infinity gets the density of the disk the light's rays
// start from, p_disk |cos theta| (pbrt-v3 section 16.3.3 does the same).
//
// Transport mode: a light subpath carries importance, so at a refraction
// its BSDF lacks the (n_o / n_i)^2 that radiance gains (Veach 1997 section
// 5.2), and shading normals need Veach's correction (section 5.3,
// |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|)); vertex_f applies both.
//
// Tests: tests/bdpt (densities against the subpath's own sampling; MIS
// weights summing to 1; renders against the path tracer and closed forms).
#pragma once

#include <optional>
#include <vector>

#include "core/color.h"
#include "core/vec3.h"
#include "scene/bsdf.h"
#include "scene/interaction.h"
#include "scene/light_set.h"

namespace pt {

struct RenderContext;

/// Which quantity a subpath carries: radiance (camera subpaths) or
/// importance (light subpaths).
enum class Transport { radiance, importance };

/// What a vertex is.
enum class VertexKind {
    camera,   ///< z0: the lens point (the centre of projection of a pinhole)
    light,    ///< y0: a point on a light, a point light, or (at infinity) a ray from a far light
    surface,  ///< a scattering point found by a ray
    escaped,  ///< a camera ray that left the scene: the environment, at infinity
};

/// One vertex of a subpath.
struct PathVertex {
    VertexKind kind = VertexKind::surface;
    Vec3 p;        ///< position, world space (escaped: unused)
    Vec3 ng;       ///< unit geometric normal as stored (area light: its emitting side); 0 if none
    Vec3 ns;       ///< unit shading normal (surfaces), else ng
    Vec3 w;        ///< escaped: unit direction the camera ray left in; light at infinity:
                   ///< the unit direction its light travels in
    Color beta;    ///< the subpath's weight from its start to here (integrand / density so far)
    double pdf_fwd = 0;  ///< density of this vertex from the one before (see the file comment)
    double pdf_rev = 0;  ///< density of this vertex from the one after, in the other direction
    bool delta = false;  ///< the direction leaving this vertex was drawn from a Dirac delta lobe
    std::optional<SurfaceInteraction> isect;  ///< surfaces: the hit
    std::optional<BSDF> bsdf;                 ///< surfaces: the BSDF at the hit
    const Light* light = nullptr;  ///< light vertices, and surfaces on an area light
    Color Le;             ///< light vertices: radiance (area, environment), intensity W/sr
                          ///< (point) or irradiance (directional) of the emitted ray
    Vec3 p_error;         ///< light vertices: rounding bound of p (area lights)
    double pdf_pos = 0;   ///< light vertices: sample_Le's density of p (1 for a point light)
    double pdf_dir = 0;   ///< light vertices: sample_Le's density of w
    double pick = 0;      ///< light vertices: the probability of choosing this light

    bool on_surface() const { return kind == VertexKind::surface || (kind == VertexKind::light && ng.norm2() > 0 && !at_infinity()); }
    /// Escaped camera rays and light vertices of directional and environment lights.
    bool at_infinity() const {
        return kind == VertexKind::escaped || (kind == VertexKind::light && light && light->at_infinity());
    }
    /// Whether another vertex can be joined to this one by an edge: not at
    /// infinity, not a delta BSDF (a delta light is connectible).
    bool connectible() const;
};

/// What MIS needs of a vertex (stages/bdpt.h, mis_weight).
struct MisVertex {
    double pdf_fwd = 0;  ///< PathVertex::pdf_fwd (0 after a delta bounce)
    double pdf_rev = 0;  ///< PathVertex::pdf_rev, with the connection's densities
    bool delta = false;  ///< PathVertex::delta
};

/// The unit direction from `from` towards `to`, also when either is at
/// infinity (an escaped vertex lies along its w, a far light against its w).
Vec3 direction_to(const PathVertex& from, const PathVertex& to);

/// p_omega, a density per unit solid angle at `from`, as a density per
/// unit area at `to` (Veach eq. 8.10); unchanged when `to` is at infinity.
double convert_density(double pdf_omega, const PathVertex& from, const PathVertex& to);

/// The BSDF of surface vertex v for light arriving from direction `wi`
/// and leaving towards its previous vertex (v.isect->wo), world-space unit
/// direction; in importance mode the adjoint (see the file comment).
Color vertex_f(const PathVertex& v, const Vec3& wi, Transport mode);

/// The density per unit area (solid angle, if `next` is at infinity) with
/// which vertex v, reached from `prev` (null for an endpoint), samples
/// `next`: its BSDF for surfaces, the camera's ray density, or the light's.
double vertex_pdf(const RenderContext& context, const PathVertex& v, const PathVertex* prev,
                  const PathVertex& next);

/// The density with which the light under v (a light vertex, an emitting
/// surface, or an escaped ray's environment) emits a ray that reaches `next`.
double pdf_light(const RenderContext& context, const PathVertex& v, const PathVertex& next);

/// The density with which a light subpath would start at v: the chance of
/// its light times sample_Le's density of the point (or, at infinity, the direction).
double pdf_light_origin(const RenderContext& context, const PathVertex& v);

/// Emitted radiance of an escaped vertex or an emitting surface vertex
/// towards `towards` (the vertex before it; one-sided area lights).
Color vertex_Le(const RenderContext& context, const PathVertex& v, const PathVertex& towards);

/// A surface vertex for `isect` with weight beta (its BSDF built by the context).
PathVertex make_surface_vertex(const RenderContext& context, const SurfaceInteraction& isect,
                               const Color& beta);

}  // namespace pt
