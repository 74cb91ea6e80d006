// Part 7, bidirectional path tracing's three student functions (issue 18).
// Every expected value is computed here, by trusted code, from the scene
// and the vertices' positions; nothing calls the reference's random_walk,
// connect or mis_weight (the runners hold no reference of what they grade).
//
//   random_walk  camera and light subpaths (roulette off) on the graded
//                scenes. Each new vertex must be where the ray from the
//                vertex before first hits the scene; its pdf_fwd, the
//                previous vertex's pdf_rev (both per unit area, Veach eq.
//                8.10: p_omega |cos theta| / d^2, no cosine at a point
//                light or the camera), its beta (beta_prev f |cos| / p_omega,
//                the adjoint BSDF in importance mode) and its delta flag are
//                recomputed from the BSDFs the grader builds at the trusted
//                hits, within rel_tol. Distribution: from the centre of the
//                cube's floor (scenes/grading_bdpt_cube.json), the next
//                vertex over the five other faces (4 x 4 cells each) against
//                the area density cos cos / (pi d^2) integrated over each
//                cell (midpoint rule, 16 x 16 points: the densities are
//                smooth there); chi-square at the manifest's significance.
//                And max_vertices 0 (the light subpath of -m 0) adds nothing.
//                In a scene with an environment a camera walk may end with
//                an escaped vertex (w: the unit direction of a ray from the
//                vertex before that hits nothing; pdf_fwd per solid angle),
//                and densities towards a light at infinity stay per solid
//                angle.
//   connect      every strategy (s, t) of reference subpaths (the Cornell
//                box with its blocks, and the light bulb: a point light in
//                a glass sphere, so delta vertices and blocked connections)
//                against the closed forms of stages/bdpt.h: s = 0 the
//                emission, t = 1 We / pdf with the lens sample of the same
//                random numbers, s = 1 the light's Le cos / (d^2 pick pdf_pos)
//                (Le / (d^2 pick) for a point light), otherwise beta f G f
//                beta with G = |cos| |cos| / d^2; 0 where a vertex cannot be
//                joined (delta BSDF, the back of a one-sided light, the
//                lens out of view) or the edge is blocked. Visibility is
//                the grader's own closest-hit ray from one end towards the
//                other; within 10^-3 of the edge's length of an end, a hit is
//                ambiguous and either answer is allowed.
//   mis_weight   random paths of 2 to 8 vertices with random densities in
//                both directions and delta vertices (the light a delta
//                light, too): each strategy's weight against the brute-force
//                p_s^b / sum_i p_i^b over the strategies that can make the
//                path (rel_tol), and the weights of one path summing to 1;
//                the power and the balance heuristic.
#include <algorithm>
#include <cmath>
#include <memory>

#include "core/math.h"
#include "grade/bvh_inputs.h"
#include "grade/case_log.h"
#include "grade/chi_square.h"
#include "grade/function_checks.h"
#include "grade/mis_oracle.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "render/integrators.h"
#include "scene/camera_importance.h"
#include "scene/material.h"
#include "stages/bdpt.h"
#include "stages/render_context.h"

namespace pt {
namespace {

std::string format_color(const Color& c) { return format_vec(Vec3(c.r, c.g, c.b)); }

bool close(double got, double want, double rel_tol) {
    return std::fabs(got - want) <= rel_tol * std::fabs(want) + 1e-300;
}
/// Componentwise, relative to the largest component (a colour's small
/// channel may be rounding noise of its large one).
bool close(const Color& got, const Color& want, double rel_tol) {
    const double scale = std::max({std::fabs(want.r), std::fabs(want.g), std::fabs(want.b)});
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(got[c] - want[c]) <= rel_tol * scale + 1e-300)) return false;
    return true;
}

/// A scene with its accelerator and a BDPT context on the reference stages.
struct GradedScene {
    Scene scene;
    std::unique_ptr<Accelerator> accelerator;
    std::unique_ptr<Integrator> integrator;
    RenderSettings settings;
    std::unique_ptr<RenderContext> context;

    GradedScene(const GradeEnvironment& env, const std::string& path, int max_depth)
        : scene(load_graded_scene(env, path)) {
        accelerator = build_accelerator(scene, env.reference, AcceleratorSettings{});
        integrator = make_integrator(IntegratorKind::bdpt);
        settings.integrator = IntegratorKind::bdpt;
        settings.max_depth = max_depth;
        settings.russian_roulette = false;  // deterministic betas: no 1 / q
        context = std::make_unique<RenderContext>(scene, *accelerator, env.reference, settings, *integrator);
    }
};

/// The solid-angle density with which surface vertex v, reached from
/// `prev`, samples the direction towards `next` (its BSDF's pdf).
double bsdf_pdf_omega(const PathVertex& v, const PathVertex& prev, const PathVertex& next) {
    const Vec3 wp = direction_to(v, prev), wn = direction_to(v, next);
    return v.bsdf->pdf(v.bsdf->to_local(wp), v.bsdf->to_local(wn));
}

/// p_omega at `from` as a density per unit area at `to`: p |cos theta_to| / d^2,
/// without the cosine where `to` is a point (a point light, the camera).
double area_density(double pdf_omega, const PathVertex& from, const PathVertex& to) {
    // At infinity (an escaped camera ray, a directional light or the sky) a
    // density stays per unit solid angle (stages/bdpt_vertex.h).
    if (to.kind == VertexKind::escaped || (to.kind == VertexKind::light && to.light && to.light->at_infinity()))
        return pdf_omega;
    const Vec3 d = to.p - from.p;
    const double d2 = d.norm2();
    if (!(d2 > 0)) return 0;
    const bool surface = to.kind == VertexKind::surface || (to.kind == VertexKind::light && to.ng.norm2() > 0);
    return pdf_omega * (surface ? std::fabs(dot(to.ng, d)) / std::sqrt(d2) : 1.0) / d2;
}

const char* mode_name(Transport mode) { return mode == Transport::radiance ? "camera" : "light"; }

/// Checks one walk of the student's random_walk: `path` as it returned it,
/// path[0] the trusted start. Returns the trusted vertices (hits and BSDFs).
void check_walk(const RenderContext& context, Transport mode, const Color& beta, double pdf_dir,
                int max_vertices, int added, const std::vector<PathVertex>& path, const PathVertex& start,
                const Ray& first_ray, double rel_tol, CaseLog& log, const std::string& where) {
    const size_t n = path.size();
    if (n == 0 || added < 0 || added > max_vertices || n != size_t(added) + 1) {
        log.mismatch(where + ": random_walk returned " + std::to_string(added) + " with max_vertices " +
                     std::to_string(max_vertices) + " and made the path " + std::to_string(n) +
                     " vertices long (from 1)");
        return;
    }
    log.agreed();
    std::vector<PathVertex> tv(n);
    tv[0] = start;
    for (size_t i = 1; i < n; ++i) {
        const std::string at = where + ", vertex " + std::to_string(i);
        const PathVertex& v = path[i];
        if (v.kind == VertexKind::escaped) {
            // A camera ray that leaves a scene with an environment: the last
            // vertex, its w the unit direction of a ray from the vertex
            // before that hits nothing.
            const bool allowed = i + 1 == n && mode == Transport::radiance && context.lights.environment();
            Ray ray = first_ray;
            if (i > 1) ray = tv[i - 1].isect->spawn_ray(v.w);
            const bool along = i > 1 || (v.w - normalize(first_ray.d)).norm() <= 1e-9;
            if (!allowed || !along || !(std::fabs(v.w.norm() - 1) <= 1e-9) || context.intersect(ray)) {
                log.mismatch(at + ": an escaped vertex (w " + format_vec(v.w) + "), but " +
                             (!allowed ? std::string("only a camera walk in a scene with an environment ends so")
                                       : std::string("its w is not the unit direction of a ray that leaves the scene")));
                return;
            }
            tv[i] = v;
            log.agreed();
            continue;
        }
        if (v.kind != VertexKind::surface) {
            log.mismatch(at + ": neither a surface vertex nor an escaped one");
            return;
        }
        // The vertex must be the first hit of the ray from the one before.
        Ray ray = first_ray;
        if (i > 1) {
            const Vec3 d = v.p - tv[i - 1].p;
            if (!(d.norm2() > 0) || !d.is_finite()) {
                log.mismatch(at + ": at the position of the vertex before, " + format_vec(v.p));
                return;
            }
            ray = tv[i - 1].isect->spawn_ray(normalize(d));
        }
        const std::optional<SurfaceInteraction> hit = context.intersect(ray);
        const double dist = (v.p - ray.o).norm();
        if (!hit || !((hit->p - v.p).norm() <= 1e-6 * std::max(dist, 1e-3))) {
            log.mismatch(at + ": at " + format_vec(v.p) + ", but the ray from the vertex before towards it first hits " +
                         (hit ? format_vec(hit->p) : std::string("nothing")));
            return;
        }
        tv[i] = make_surface_vertex(context, *hit, v.beta);
        log.agreed();
    }
    // pdf_fwd: the density of vertex i from vertex i - 1 (0 after a delta bounce).
    for (size_t i = 1; i < n; ++i) {
        double omega = pdf_dir;
        if (i > 1) omega = tv[i - 1].bsdf->is_delta() ? 0.0 : bsdf_pdf_omega(tv[i - 1], tv[i - 2], tv[i]);
        const double want = area_density(omega, tv[i - 1], tv[i]);
        if (close(path[i].pdf_fwd, want, rel_tol))
            log.agreed();
        else
            log.mismatch(where + ", vertex " + std::to_string(i) + ": pdf_fwd " + format_num(path[i].pdf_fwd) +
                         ", but the density per unit area of reaching it from vertex " + std::to_string(i - 1) +
                         " is " + format_num(want) + " (p_omega " + format_num(omega) + " x |cos| / d^2)");
    }
    // pdf_rev of vertex j: the density with which vertex j + 1, reached from
    // j + 2, samples j. Set for every j whose j + 2 exists; the vertex before
    // the last may or may not have it (a walk that escapes sets it).
    for (size_t j = 0; j + 2 < n; ++j) {
        const PathVertex& via = tv[j + 1];
        const double omega = via.bsdf->is_delta() ? 0.0 : bsdf_pdf_omega(via, tv[j + 2], tv[j]);
        const double want = area_density(omega, via, tv[j]);
        if (close(path[j].pdf_rev, want, rel_tol))
            log.agreed();
        else
            log.mismatch(where + ", vertex " + std::to_string(j) + ": pdf_rev " + format_num(path[j].pdf_rev) +
                         ", but the density per unit area of sampling it back from vertex " +
                         std::to_string(j + 1) + " is " + format_num(want) + " (p_omega " + format_num(omega) +
                         " x |cos| / d^2)");
    }
    // Delta flags of the vertices the walk scattered at.
    for (size_t i = 1; i + 1 < n; ++i) {
        if (path[i].delta == tv[i].bsdf->is_delta())
            log.agreed();
        else
            log.mismatch(where + ", vertex " + std::to_string(i) + ": delta " + (path[i].delta ? "true" : "false") +
                         " on a " + (tv[i].bsdf->is_delta() ? "delta" : "non-delta") + " BSDF");
    }
    // beta: the start's weight on vertex 1, then beta_prev f |cos| / p_omega.
    if (close(path.size() > 1 ? path[1].beta : beta, beta, rel_tol))
        log.agreed();
    else
        log.mismatch(where + ": vertex 1 has beta " + format_color(path[1].beta) + ", not the walk's beta " +
                     format_color(beta));
    for (size_t i = 2; i < n; ++i) {
        const PathVertex& v = tv[i - 1];
        const std::string at = where + ", vertex " + std::to_string(i);
        const Color& got = path[i].beta;
        if (v.bsdf->is_delta()) {
            // A delta lobe's weight (reflectance over the lobe's chance): finite, not negative.
            bool ok = true;
            for (int c = 0; c < 3; ++c)
                ok = ok && std::isfinite(got[c]) && got[c] >= 0;
            if (ok)
                log.agreed();
            else
                log.mismatch(at + ": beta " + format_color(got) + " after a delta bounce");
            continue;
        }
        const Vec3 wi = direction_to(v, tv[i]);
        const double omega = bsdf_pdf_omega(v, tv[i - 2], tv[i]);
        const Color want = omega > 0 ? path[i - 1].beta * vertex_f(v, wi, mode) * (std::fabs(dot(wi, v.ns)) / omega)
                                     : Color(0);
        if (close(got, want, rel_tol))
            log.agreed();
        else
            log.mismatch(at + ": beta " + format_color(got) + ", but beta_prev f |cos| / p_omega = " +
                         format_color(want) + (mode == Transport::importance ? " (the adjoint BSDF)" : ""));
    }
}

/// The start of a camera subpath: the lens vertex and a camera ray.
PathVertex camera_start(const GradeEnvironment& env, const Scene& scene, Rng& rng, Ray* ray, double* pdf_dir) {
    *ray = env.reference.camera.generate_ray(scene.camera, rng.next_1d(), rng.next_1d(), rng.next_2d());
    PathVertex z0;
    z0.kind = VertexKind::camera;
    z0.p = ray->o;
    z0.beta = Color(1.0);
    *pdf_dir = camera_pdf_We(scene.camera, ray->o, ray->d).dir;
    return z0;
}

/// The cube's faces for the chi-square test: face f (0 floor .. 5) as a
/// point of [-1, 1]^3 from two coordinates in [0, 1], with its inward normal.
struct CubeFace {
    Vec3 origin, e1, e2, n;
};
const CubeFace kFaces[6] = {
    {Vec3(-1, -1, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), Vec3(0, 1, 0)},   // floor, y = -1
    {Vec3(-1, 1, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), Vec3(0, -1, 0)},   // ceiling, y = 1
    {Vec3(-1, -1, -1), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 1)},   // back, z = -1
    {Vec3(-1, -1, 1), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, -1)},   // front, z = 1
    {Vec3(-1, -1, -1), Vec3(0, 2, 0), Vec3(0, 0, 2), Vec3(1, 0, 0)},   // left, x = -1
    {Vec3(1, -1, -1), Vec3(0, 2, 0), Vec3(0, 0, 2), Vec3(-1, 0, 0)},   // right, x = 1
};

/// Which cell (face * g * g + row * g + column) of the cube holds p, or -1.
int cube_cell(const Vec3& p, int g) {
    for (int f = 0; f < 6; ++f) {
        const CubeFace& face = kFaces[f];
        if (std::fabs(dot(p - face.origin, face.n)) > 1e-6) continue;
        const double a = dot(p - face.origin, face.e1) / face.e1.norm2();
        const double b = dot(p - face.origin, face.e2) / face.e2.norm2();
        if (a < -1e-9 || a > 1 + 1e-9 || b < -1e-9 || b > 1 + 1e-9) continue;
        return (f * g + std::clamp(int(a * g), 0, g - 1)) * g + std::clamp(int(b * g), 0, g - 1);
    }
    return -1;
}

/// The chance that a cosine-distributed direction from x (normal nx) first
/// hits cell (row, column) of face f: the area density cos cos / (pi d^2)
/// integrated by the midpoint rule on m x m points.
double cell_probability(const Vec3& x, const Vec3& nx, int f, int row, int col, int g, int m) {
    const CubeFace& face = kFaces[f];
    double sum = 0;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            const Vec3 y = face.origin + face.e1 * ((row + (i + 0.5) / m) / g) + face.e2 * ((col + (j + 0.5) / m) / g);
            const Vec3 d = y - x;
            const double d2 = d.norm2();
            const double cx = dot(nx, d), cy = -dot(face.n, d);
            if (cx > 0 && cy > 0) sum += cx * cy / (kPi * d2 * d2);
        }
    return sum * std::sqrt(face.e1.norm2() * face.e2.norm2()) / (double(g) * g * m * m);
}

}  // namespace

TaskResult check_random_walk(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-6);
    const int walks = param(spec, "walks", 100);
    const int max_vertices = param(spec, "max_vertices", 5);
    const int samples = param(spec, "samples", 10000);
    const double significance = param(spec, "significance", 1e-5);
    const std::vector<std::string> scenes = param(
        spec, "scenes",
        std::vector<std::string>{"scenes/grading_bdpt_cube.json", "scenes/cbox.json", "scenes/light_bulb.json"});
    Rng rng = check_rng(env.seed, "random_walk");
    CaseLog log;
    for (const std::string& name : scenes) {
        GradedScene g(env, name, max_vertices);
        for (Transport mode : {Transport::radiance, Transport::importance}) {
            log.category(std::string(mode_name(mode)) + " subpaths: vertices, area densities both ways, beta");
            for (int w = 0; w < walks; ++w) {
                Ray ray;
                double pdf_dir = 0;
                Color beta(1.0);
                PathVertex start;
                if (mode == Transport::radiance) {
                    start = camera_start(env, g.scene, rng, &ray, &pdf_dir);
                } else {
                    const std::optional<LightStart> s = light_start(*g.context, rng);
                    if (!s) continue;
                    start = s->y0, ray = s->ray, beta = s->beta, pdf_dir = s->pdf_dir;
                }
                std::vector<PathVertex> path{start};
                Rng walk_rng(env.seed, uint64_t(w), uint64_t(mode == Transport::radiance ? 1 : 2));
                const int added = env.student.bdpt.random_walk(*g.context, ray, beta, pdf_dir, max_vertices, mode,
                                                               walk_rng, path);
                check_walk(*g.context, mode, beta, pdf_dir, max_vertices, added, path, start, ray, rel_tol, log,
                           name + ", " + mode_name(mode) + " walk " + std::to_string(w));
            }
        }
    }

    // max_vertices 0: the light subpath of -m 0 (light_subpath passes
    // max_depth) must stay its light vertex alone; a walk that tests its
    // limit only after a push adds one.
    log.category("max_vertices 0 (the light subpath of -m 0): nothing added");
    {
        GradedScene g(env, scenes.empty() ? std::string("scenes/cbox.json") : scenes.front(), 0);
        for (Transport mode : {Transport::radiance, Transport::importance}) {
            Ray ray;
            double pdf_dir = 0;
            Color beta(1.0);
            PathVertex start;
            if (mode == Transport::radiance) {
                start = camera_start(env, g.scene, rng, &ray, &pdf_dir);
            } else {
                const std::optional<LightStart> s = light_start(*g.context, rng);
                if (!s) continue;
                start = s->y0, ray = s->ray, beta = s->beta, pdf_dir = s->pdf_dir;
            }
            std::vector<PathVertex> path{start};
            Rng walk_rng(env.seed, uint64_t(0), uint64_t(mode == Transport::radiance ? 4 : 5));
            const int added = env.student.bdpt.random_walk(*g.context, ray, beta, pdf_dir, 0, mode, walk_rng, path);
            if (added == 0 && path.size() == 1)
                log.agreed();
            else
                log.mismatch(std::string(mode_name(mode)) + " walk with max_vertices 0: returned " +
                             std::to_string(added) + " and made the path " + std::to_string(path.size()) +
                             " vertices long (from 1); it must add none");
        }
    }

    // The distribution of the next vertex from the centre of the cube's floor.
    log.category("the next vertex from the cube's floor: chi-square against the integrated area density");
    GradedScene cube(env, "scenes/grading_bdpt_cube.json", 2);
    const int grid = 4, cells = 6 * grid * grid;
    const Vec3 x(0, -1, 0), nx(0, 1, 0);
    std::vector<double> observed(size_t(cells) + 1, 0), expected(size_t(cells) + 1, 0);
    double total = 0;
    for (int f = 1; f < 6; ++f)
        for (int r = 0; r < grid; ++r)
            for (int c = 0; c < grid; ++c) {
                const double p = cell_probability(x, nx, f, r, c, grid, 16);
                expected[size_t((f * grid + r) * grid + c)] = samples * p;
                total += p;
            }
    PathVertex above;
    above.kind = VertexKind::camera;
    above.p = Vec3(0, 0.5, 0);
    above.beta = Color(1.0);
    const Ray down(above.p, Vec3(0, -1, 0));
    int valid = 0;
    for (int i = 0; i < samples; ++i) {
        std::vector<PathVertex> path{above};
        Rng walk_rng(env.seed, uint64_t(i), 3);
        const int added =
            env.student.bdpt.random_walk(*cube.context, down, Color(1.0), 1.0, 2, Transport::radiance, walk_rng, path);
        if (added != 2 || path.size() != 3) {
            observed[size_t(cells)] += 1;  // no second vertex: expected never, in a closed cube
            continue;
        }
        const int cell = cube_cell(path[2].p, grid);
        observed[size_t(cell < 0 ? cells : cell)] += 1;
        valid += cell >= 0;
    }
    const ChiSquareResult chi = chi_square_test(observed, expected, significance);
    const std::string chi_message = std::to_string(samples) + " walks, " + std::to_string(valid) +
                                    " second vertices on the faces (integrated density " + format_num(total) +
                                    "): " + chi.message;
    if (chi.passed)
        log.agreed();
    else
        log.mismatch("from the centre of the floor: " + chi_message);
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the densities the grader computes");
    r.details.insert(r.details.begin(), "chi-square of the next vertex: " + chi_message);
    return r;
}

namespace {

/// The closed form of strategy (s, t) (stages/bdpt.h, connect), computed
/// from the vertices, and whether the grader's visibility ray was
/// ambiguous. `u` is the lens sample the connection draws first (t = 1).
struct Expected {
    Color L;
    bool ambiguous = false;  ///< visibility within the end band: L or 0 allowed
    bool blocked = false;    ///< nonzero but for the blocked edge
    std::optional<Vec2> film;
    std::optional<Vec3> lens;
};

/// Whether the segment from surface vertex `from` to point `to` is free:
/// the first hit along it lies at the end (within 10^-3 of its length:
/// ambiguous) or beyond.
void visibility(const RenderContext& context, const SurfaceInteraction& from, const Vec3& to, Expected& e) {
    const Vec3 d = to - from.p;
    const double len = d.norm();
    const std::optional<SurfaceInteraction> hit = context.intersect(from.spawn_ray(d / len));
    const double at = hit ? (hit->p - from.p).norm() : INFINITY;
    if (at >= len * (1 - 1e-9)) return;
    if (at >= len * (1 - 1e-3) || at <= len * 1e-3) {
        e.ambiguous = true;
        return;
    }
    e.blocked = !e.L.is_black();
    e.L = Color(0);
}

Expected expected_connection(const RenderContext& context, const std::vector<PathVertex>& light, int s,
                             const std::vector<PathVertex>& camera, int t, Vec2 u) {
    Expected e;
    if (s == 0) {
        if (t < 2) return e;
        const PathVertex& z = camera[size_t(t) - 1];
        if (z.kind != VertexKind::surface || !z.isect->material) return e;
        const Vec3 w = normalize(camera[size_t(t) - 2].p - z.p);
        if (dot(z.isect->ng, w) > 0) e.L = z.beta * z.isect->material->emission;  // one-sided emitters
        return e;
    }
    const PathVertex& y = light[size_t(s) - 1];
    if (t == 1) {
        if (y.kind != VertexKind::surface || y.bsdf->is_delta()) return e;
        const CameraImportanceSample cs = camera_sample_Wi(context.scene.camera, y.p, u);
        if (!cs.valid()) return e;
        e.L = y.beta * vertex_f(y, cs.wi, Transport::importance) * (cs.We / cs.pdf) * std::fabs(dot(cs.wi, y.ns));
        e.film = cs.film;
        e.lens = cs.p_lens;
        if (!e.L.is_black()) visibility(context, *y.isect, cs.p_lens, e);
        return e;
    }
    const PathVertex& z = camera[size_t(t) - 1];
    if (z.kind != VertexKind::surface || z.bsdf->is_delta()) return e;
    const Vec3 d = y.p - z.p;
    const double d2 = d.norm2();
    if (!(d2 > 0)) return e;
    const Vec3 wi = d / std::sqrt(d2);
    const double cos_z = std::fabs(dot(wi, z.ns));
    if (s == 1) {
        // The light's own point: emission per unit area over the density of the point.
        const Light& l = *y.light;
        Color E;
        if (l.kind() == LightKind::point) {
            E = y.Le / (d2 * y.pick);
        } else {
            const double cos_light = -dot(y.ng, wi);
            if (!(cos_light > 0)) return e;  // the back of a one-sided light
            E = y.Le * (cos_light / (d2 * y.pick * y.pdf_pos));
        }
        e.L = z.beta * vertex_f(z, wi, Transport::radiance) * cos_z * E;
    } else {
        if (y.kind != VertexKind::surface || y.bsdf->is_delta()) return e;
        const double G = cos_z * std::fabs(dot(wi, y.ns)) / d2;
        e.L = z.beta * vertex_f(z, wi, Transport::radiance) * G * vertex_f(y, -wi, Transport::importance) * y.beta;
    }
    if (!e.L.is_black()) visibility(context, *z.isect, y.p, e);
    return e;
}

}  // namespace

TaskResult check_bdpt_connect(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-6);
    const int paths = param(spec, "paths", 40);
    const std::vector<std::string> scenes =
        param(spec, "scenes", std::vector<std::string>{"scenes/cbox.json", "scenes/light_bulb.json"});
    Rng rng = check_rng(env.seed, "connect");
    CaseLog log;
    int blocked = 0, ambiguous = 0;
    for (const std::string& name : scenes) {
        GradedScene g(env, name, 4);
        for (int i = 0; i < paths; ++i) {
            Ray ray;
            double pdf_dir = 0;
            camera_start(env, g.scene, rng, &ray, &pdf_dir);
            // Reference subpaths (this task grades connect alone).
            const std::vector<PathVertex> camera = camera_subpath(*g.context, env.reference.bdpt, ray, rng);
            const std::vector<PathVertex> light = light_subpath(*g.context, env.reference.bdpt, rng);
            for (int s = 0; s <= int(light.size()); ++s)
                for (int t = 1; t <= int(camera.size()); ++t) {
                    if (s + t < 2) continue;
                    Rng r(env.seed, uint64_t(i), uint64_t(100 * s + t));
                    Rng copy = r;
                    const Connection c = env.student.bdpt.connect(*g.context, light, s, camera, t, r);
                    const Expected e = expected_connection(*g.context, light, s, camera, t, copy.next_2d());
                    const std::string where = name + ", path " + std::to_string(i) + ", strategy (" +
                                              std::to_string(s) + ", " + std::to_string(t) + ")";
                    if (e.blocked) ++blocked;
                    if (e.ambiguous) ++ambiguous;
                    log.category(e.blocked          ? "blocked edges: 0"
                                 : e.L.is_black()   ? "nothing to join (delta BSDF, back of a light, lens out of view): 0"
                                 : s == 0           ? "s = 0: the camera subpath's own emission"
                                 : t == 1           ? "t = 1: light tracing, We / pdf, the film position"
                                 : s == 1           ? "s = 1: the light's point (area and point lights)"
                                                    : "beta f G f beta with G = |cos| |cos| / d^2");
                    bool ok = close(c.L, e.L, rel_tol) || (e.ambiguous && c.L.is_black());
                    std::string also;
                    if (ok && t == 1 && !c.L.is_black()) {
                        ok = c.camera_vertex.has_value() && e.film && std::fabs(c.film.x - e.film->x) <= 1e-6 &&
                             std::fabs(c.film.y - e.film->y) <= 1e-6 &&
                             (c.camera_vertex->p - *e.lens).norm() <= 1e-6 * (1 + e.lens->norm());
                        if (!ok)
                            also = c.camera_vertex ? "; film (" + format_num(c.film.x) + ", " + format_num(c.film.y) +
                                                         ") instead of (" + format_num(e.film ? e.film->x : 0) + ", " +
                                                         format_num(e.film ? e.film->y : 0) + ")"
                                                   : "; no camera_vertex for a splat";
                    }
                    if (ok && e.ambiguous)
                        log.allowed();
                    else if (ok)
                        log.agreed();
                    else
                        log.mismatch(where + ": L = " + format_color(c.L) + ", but the closed form gives " +
                                     format_color(e.L) + (e.blocked ? " (the edge is blocked)" : "") + also);
                }
        }
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the closed forms");
    r.details.insert(r.details.begin(), std::to_string(blocked) + " strategies blocked by the scene, " +
                                            std::to_string(ambiguous) + " within the visibility band");
    return r;
}

TaskResult check_bdpt_mis_weight(const TaskSpec& spec, const GradeEnvironment& env) {
    using namespace mis_oracle;
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int cases = param(spec, "cases", 1000);
    Rng rng = check_rng(env.seed, "mis_weight");
    CaseLog log;
    struct Family {
        const char* name;
        double decades, delta_chance;
        bool delta_light;
    };
    const Family families[] = {
        {"random paths, densities over 3 decades, no delta vertex", 3, 0, false},
        {"random paths with delta vertices (a quarter of them)", 3, 0.25, false},
        {"random paths from a delta light (point or directional)", 3, 0.25, true},
        {"densities over 16 decades", 16, 0.1, false},
    };
    for (const Family& f : families) {
        for (MisHeuristic h : {MisHeuristic::power, MisHeuristic::balance}) {
            log.category(std::string(f.name) + ", the " + to_string(h) + " heuristic");
            for (int k = 0; k < cases / 4; ++k) {
                const int n = 2 + int(rng.next_index(7));
                RandomPath p = random_path(rng, n, f.decades, f.delta_chance);
                if (f.delta_light) p.delta[0] = true, p.pf[0] = p.pr[0] = 1;
                double sum = 0;
                bool any = false, ok = true;
                std::string first;
                for (int s = 0; s < n; ++s) {
                    if (!can_make(p, s)) continue;
                    any = true;
                    std::vector<MisVertex> lv, cv;
                    mis_arrays(p, s, lv, cv);
                    const double got = env.student.bdpt.mis_weight(lv.data(), s, cv.data(), n - s, p.delta[0], h);
                    const double want = brute_force_weight(p, s, h);
                    sum += got;
                    if (!close(got, want, rel_tol) && ok) {
                        ok = false;
                        first = "strategy (" + std::to_string(s) + ", " + std::to_string(n - s) + ") of a path of " +
                                std::to_string(n) + " vertices: weight " + format_num(got) +
                                ", but p_s^b / sum_i p_i^b = " + format_num(want);
                    }
                }
                if (ok && any && !(std::fabs(sum - 1) <= 1e-9)) {
                    ok = false;
                    first = "the weights of a path of " + std::to_string(n) + " vertices sum to " + format_num(sum);
                }
                if (ok)
                    log.agreed();
                else
                    log.mismatch(first);
            }
        }
    }
    log.category("a path of two vertices (the light seen directly, (0, 2)): weight 1");
    for (MisHeuristic h : {MisHeuristic::power, MisHeuristic::balance}) {
        const MisVertex camera[2] = {{1, 0.5, false}, {1, 2, false}};
        const double got = env.student.bdpt.mis_weight(nullptr, 0, camera, 2, false, h);
        if (close(got, 1.0, rel_tol))
            log.agreed();
        else
            log.mismatch(std::string("(0, 2), the ") + to_string(h) + " heuristic: weight " + format_num(got));
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "brute force");
}

}  // namespace pt
