// Part 2, grid_intersect (optional task 6): the student's 3D-DDA walk of a
// grid built by the reference (stages/uniform_grid.h), against brute force
// over every primitive, on the rays a DDA gets wrong: axis-aligned rays
// (two direction components 0, of either sign), rays parallel to a face
// (one component 0), rays lying in a plane between cells, rays through
// cell corners (the three crossings tie), origins inside and outside the
// grid, and ordinary rays through the scene; and the grid of a scene with
// no primitives (no cells, an empty box), where every ray misses.
//
// The classic bugs and the rays that catch them: tMax of a negative step
// taken at the upper plane (every ray with a negative component); a hit
// beyond the current cell accepted (rays crossing a large primitive listed
// in several cells); the walk stopped one cell before the far side; the
// first cell taken at the box's entry when the origin is inside.
#include <cmath>

#include "grade/bvh_inputs.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "stages/spatial_subdivision.h"
#include "stages/uniform_grid.h"

namespace pt {
namespace {

std::string hit_text(const std::optional<Hit>& h) {
    return h ? "a hit on primitive " + std::to_string(h->primitive) + " at t = " + format_num(h->t)
             : std::string("a miss");
}

/// Brute force: the closest hit over every primitive (ties to the larger id).
std::optional<Hit> brute_force(const GridCells& grid, const Ray& ray) {
    ClosestHit closest(ray);
    for (uint32_t p = 0; p < grid.primitive_count(); ++p)
        closest.offer(grid.intersect_primitive(p, closest.ray));
    return closest.best;
}

/// A random point of the grid's box.
Vec3 inside(const GridCells& g, Rng& rng) {
    Vec3 p;
    for (int a = 0; a < 3; ++a)
        p[a] = g.bounds.min[a] + rng.next_1d() * (g.bounds.max[a] - g.bounds.min[a]);
    return p;
}

/// The coordinate of a random inner plane between cells along axis a
/// (a face of the box when the axis has one cell).
double cell_plane(const GridCells& g, int a, Rng& rng) {
    int k = g.res[a] > 1 ? 1 + int(rng.next_index(uint32_t(g.res[a] - 1))) : 0;
    return g.bounds.min[a] + k * g.cell_size[a];
}

/// A point of the box's surroundings outside it (up to one box size away).
Vec3 outside(const GridCells& g, Rng& rng) {
    Vec3 e = g.bounds.extent(), p = inside(g, rng);
    int a = int(rng.next_index(3));
    p[a] = rng.next_1d() < 0.5 ? g.bounds.min[a] - (0.05 + rng.next_1d()) * e[a]
                               : g.bounds.max[a] + (0.05 + rng.next_1d()) * e[a];
    return p;
}

/// A random sign, for zero components too (+0.0 or -0.0).
double random_sign(Rng& rng) { return rng.next_1d() < 0.5 ? -1.0 : 1.0; }

struct Case {
    const char* category;
    Ray ray;
};

/// `count` rays of each kind, through the grid `g` of a scene.
std::vector<Case> hard_rays(const GridCells& g, const Scene& scene, const Stages& reference, int count,
                            Rng& rng) {
    std::vector<Case> cases;
    for (const Ray& r : scene_rays(scene, reference, count, rng))
        cases.push_back({"ordinary rays through the scene", r});
    for (int i = 0; i < count; ++i) {
        // Axis-aligned: d = +-e_a, the other components +0.0 or -0.0.
        int a = int(rng.next_index(3));
        Vec3 d(0.0 * random_sign(rng), 0.0 * random_sign(rng), 0.0 * random_sign(rng));
        d[a] = random_sign(rng);
        Vec3 o = rng.next_1d() < 0.7 ? inside(g, rng) : outside(g, rng);
        if (!(o[(a + 1) % 3] >= g.bounds.min[(a + 1) % 3])) o = inside(g, rng);
        cases.push_back({"axis-aligned rays (two zero components, +0.0 and -0.0)", Ray(o, d)});

        // Parallel to a face: one zero component.
        Vec3 u = random_unit(rng);
        u[a] = 0.0 * random_sign(rng);
        if (u.norm() > 1e-3) cases.push_back({"rays parallel to a face (one zero component)", Ray(inside(g, rng), u.unit())});

        // In a plane between cells (the zero component's coordinate on a cell plane).
        Vec3 op = inside(g, rng);
        op[a] = cell_plane(g, a, rng);
        if (rng.next_1d() < 0.5) {  // on the line where two planes meet
            int b = (a + 1) % 3;
            op[b] = cell_plane(g, b, rng);
            Vec3 dl(0, 0, 0);
            dl[3 - a - b] = random_sign(rng);
            cases.push_back({"rays along cell boundaries (in planes and edges between cells)", Ray(op, dl)});
        } else if (u.norm() > 1e-3) {
            cases.push_back({"rays along cell boundaries (in planes and edges between cells)", Ray(op, u.unit())});
        }

        // Through cell corners: from a grid vertex along the cell diagonal
        // (every crossing is a three-way tie), and through a vertex from afar.
        Vec3 v;
        for (int b = 0; b < 3; ++b)
            v[b] = g.bounds.min[b] + int(rng.next_index(uint32_t(g.res[b] + 1))) * g.cell_size[b];
        Vec3 diag(g.cell_size[0] * random_sign(rng), g.cell_size[1] * random_sign(rng),
                  g.cell_size[2] * random_sign(rng));
        cases.push_back({"rays through cell corners", Ray(v, diag.unit())});
        Vec3 w = random_unit(rng);
        cases.push_back({"rays through cell corners", Ray(v - w * (g.bounds.extent().norm() * rng.next_1d()), w)});

        // Origins inside (with t_min past 0 sometimes) and outside.
        Ray in(inside(g, rng), random_unit(rng));
        if (rng.next_1d() < 0.3) in.t_min = 0.1 * g.bounds.extent().norm() * rng.next_1d();
        cases.push_back({"origins inside the grid", in});
        Vec3 from = outside(g, rng);
        cases.push_back({"origins outside the grid", Ray(from, (inside(g, rng) - from).unit())});
    }
    return cases;
}

/// Rays for the empty grid: from the origin and from points up to 10 away,
/// in random and axis-aligned directions (zero components of either sign),
/// a third with a finite interval [t_min, t_max].
std::vector<Ray> empty_grid_rays(int count, Rng& rng) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Vec3 o = (rng.next_1d() < 0.25) ? Vec3(0, 0, 0) : 10.0 * random_unit(rng) * rng.next_1d();
        Vec3 d = random_unit(rng);
        if (i % 2 == 1) {
            int a = int(rng.next_index(3));
            d = Vec3(0.0 * random_sign(rng), 0.0 * random_sign(rng), 0.0 * random_sign(rng));
            d[a] = random_sign(rng);
        }
        Ray r(o, d);
        if (i % 3 == 2) r.t_min = rng.next_1d(), r.t_max = r.t_min + 10.0 * rng.next_1d();
        rays.push_back(r);
    }
    return rays;
}

}  // namespace

TaskResult check_grid_intersect(const TaskSpec& spec, const GradeEnvironment& env) {
    const double tol = param(spec, "rel_tol", 1e-9);
    const int ray_count = param(spec, "rays", 300);
    std::vector<std::string> scenes =
        param(spec, "scenes", std::vector<std::string>{"scenes/cbox_spheres.json", "scenes/grading_knot.json"});
    const GridIntersectFn student = env.student.bvh.grid_intersect;
    Rng rng = check_rng(env.seed, "grid_intersect");
    CaseLog log;
    for (const std::string& path : scenes) {
        Scene scene = load_graded_scene(env, path);
        GridCells grid(scene, env.reference.intersect);
        for (const Case& c : hard_rays(grid, scene, env.reference, ray_count, rng)) {
            log.category(c.category);
            std::optional<Hit> want = brute_force(grid, c.ray);
            std::optional<Hit> got = student(grid, c.ray);
            bool ok = bool(got) == bool(want) &&
                      (!want || std::fabs(got->t - want->t) <= tol * std::max(1.0, want->t));
            if (ok)
                log.agreed();  // equal t on two primitives (a shared edge) is a tie
            else
                log.mismatch(path + ": ray o = " + format_vec(c.ray.o) + " d = " + format_vec(c.ray.d) +
                             " t_min = " + format_num(c.ray.t_min) + ": " + hit_text(got) + " instead of " +
                             hit_text(want) + " (brute force over all " +
                             std::to_string(grid.primitive_count()) + " primitives)");
        }
    }
    // A scene without primitives: res 0, an empty box, no cells to walk
    // (GridCells::empty()). Every ray misses; a walk that clips to the empty
    // box and then looks up a cell reads outside the grid.
    const Scene nothing;
    const GridCells empty(nothing, env.reference.intersect);
    for (const Ray& r : empty_grid_rays(param(spec, "empty_grid_rays", 50), rng)) {
        log.category("an empty grid (no primitives: every ray misses)");
        std::optional<Hit> got = student(empty, r);
        if (!got)
            log.agreed();
        else
            log.mismatch("the empty grid (a scene without primitives): ray o = " + format_vec(r.o) +
                         " d = " + format_vec(r.d) + " t_min = " + format_num(r.t_min) + " t_max = " +
                         format_num(r.t_max) + ": " + hit_text(got) + " instead of a miss");
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "brute force");
}

}  // namespace pt
