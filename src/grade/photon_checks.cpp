// Part 8, photon mapping's functions (issue 19):
//
//   emit_photon       against the contract, photon by photon: the ray of
//                     light.sample_Le(u_pos, u_dir) and the flux of equation
//                     2 (stages/photon.h), for every light of the graded
//                     scenes (area quads and spheres, point lights); and the
//                     flux of N photons, each light chosen by power, sums to
//                     the lights' total power (a z-test, |z| <= 5, with a
//                     relative allowance of 1e-6 where the flux has no
//                     variance). u_dir on the square's edges gives area
//                     lights a grazing direction with pdf_dir 0: no photon.
//   build_kdtree      the layout of stages/kdtree.h (kdtree_is_valid: the
//                     split invariant at every node, ids a permutation),
//                     each point kept with its id, and the reference's
//                     k-nearest and radius queries on the student's tree
//                     equal to brute force.
//   k_nearest         the student's query on reference-built trees against
//                     brute force: the same distances, nearest first, each
//                     id a distinct input point at the distance it states;
//                     k = 0, k above n, radii 0 and negative, a point at
//                     exactly the maximum distance (found).
//   density_estimate  equation 1 for the three kernels on hand-made lists
//                     (closed form, rel_tol); black when empty; photons
//                     spread uniformly with density rho give rho x flux
//                     (within 2%, 10^6 photons over twice the radius).
// Point sets (k-d checks): uniform, clustered, duplicates, all on a plane,
// all on a line, one point, none; drawn from the seed.
#include <algorithm>
#include <cmath>
#include <memory>

#include "core/math.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "scene/light_set.h"
#include "scene/scene_loader.h"
#include "stages/photon.h"

namespace pt {
namespace {

std::string format_color(const Color& c) { return format_vec(Vec3(c.r, c.g, c.b)); }

bool close(double a, double b, double rel_tol) { return std::fabs(a - b) <= rel_tol * std::max(1.0, std::fabs(b)); }
bool close_rel(double a, double b, double rel_tol) { return std::fabs(a - b) <= rel_tol * std::fabs(b) + 1e-300; }
bool close(const Vec3& a, const Vec3& b, double rel_tol) {
    return close(a.x, b.x, rel_tol) && close(a.y, b.y, rel_tol) && close(a.z, b.z, rel_tol);
}
bool close_rel(const Color& a, const Color& b, double rel_tol) {
    return close_rel(a.r, b.r, rel_tol) && close_rel(a.g, b.g, rel_tol) && close_rel(a.b, b.b, rel_tol);
}

struct PointSet {
    std::string name;
    std::vector<Vec3> points;
};

/// The graded point sets, from the seed.
std::vector<PointSet> point_sets(Rng& rng, int n) {
    std::vector<PointSet> sets;
    PointSet uniform_set{"uniform in a cube", {}};
    for (int i = 0; i < n; ++i)
        uniform_set.points.push_back(random_in_cube(rng) * 10.0);
    sets.push_back(uniform_set);
    PointSet clusters{"three tight clusters", {}};
    const Vec3 centres[] = {Vec3(0, 0, 0), Vec3(5, 0, 0), Vec3(0, 5, 5)};
    for (int i = 0; i < n; ++i)
        clusters.points.push_back(centres[i % 3] + random_in_cube(rng) * 0.01);
    sets.push_back(clusters);
    PointSet duplicates{"duplicates: 20 distinct points, each many times", {}};
    std::vector<Vec3> distinct;
    for (int i = 0; i < 20; ++i)
        distinct.push_back(random_in_cube(rng));
    for (int i = 0; i < n / 2; ++i)
        duplicates.points.push_back(distinct[rng.next_index(20)]);
    sets.push_back(duplicates);
    PointSet same{"every point the same", std::vector<Vec3>(size_t(std::max(1, n / 10)), Vec3(1, 2, 3))};
    sets.push_back(same);
    PointSet plane{"all on the plane z = 0.5", {}};
    for (int i = 0; i < n / 2; ++i) {
        Vec3 p = random_in_cube(rng);
        plane.points.push_back(Vec3(p.x, p.y, 0.5));
    }
    sets.push_back(plane);
    PointSet line{"all on a line", {}};
    for (int i = 0; i < n / 4; ++i)
        line.points.push_back(Vec3(1, 1, 1) * uniform(rng, -1, 1));
    sets.push_back(line);
    PointSet grid{"integer grid (exact distances)", {}};
    for (int x = 0; x < 8; ++x)
        for (int y = 0; y < 8; ++y)
            for (int z = 0; z < 4; ++z)
                grid.points.push_back(Vec3(x, y, z));
    sets.push_back(grid);
    sets.push_back({"one point", {Vec3(0.25, -0.5, 2)}});
    sets.push_back({"two points", {Vec3(0, 0, 0), Vec3(0, 0, 1)}});
    sets.push_back({"no points", {}});
    return sets;
}

/// Brute force: the points within max_dist2, nearest first, at most k.
std::vector<double> brute_force(const std::vector<Vec3>& points, const Vec3& p, int k, double max_dist2) {
    std::vector<double> d;
    if (k <= 0 || max_dist2 < 0) return d;
    for (const Vec3& q : points)
        if (double d2 = (q - p).norm2(); d2 <= max_dist2) d.push_back(d2);
    std::sort(d.begin(), d.end());
    if (d.size() > size_t(k)) d.resize(size_t(k));
    return d;
}

/// "" when `found` is the answer brute force gives (the same distances,
/// nearest first, each id a distinct input point at the distance it
/// states); else what differs. Ties at equal distance may pick either id.
std::string compare_neighbors(const std::vector<Vec3>& points, const Vec3& p, int k, double max_dist2,
                              const std::vector<Neighbor>& found) {
    const std::vector<double> want = brute_force(points, p, k, max_dist2);
    if (found.size() != want.size())
        return "found " + std::to_string(found.size()) + " points instead of " + std::to_string(want.size());
    std::vector<bool> used(points.size(), false);
    for (size_t i = 0; i < found.size(); ++i) {
        const Neighbor& x = found[i];
        if (x.id >= points.size()) return "neighbour " + std::to_string(i) + " has id " + std::to_string(x.id) + ", not a point";
        if (used[x.id]) return "point " + std::to_string(x.id) + " found twice";
        used[x.id] = true;
        const double d2 = (points[x.id] - p).norm2();
        if (!close_rel(x.dist2, d2, 1e-12))
            return "neighbour " + std::to_string(i) + " (point " + std::to_string(x.id) + ") states dist2 " +
                   format_num(x.dist2) + ", but it is " + format_num(d2) + " away";
        if (i > 0 && found[i].dist2 < found[i - 1].dist2) return "not sorted nearest first (at neighbour " + std::to_string(i) + ")";
        if (!close_rel(d2, want[i], 1e-12))
            return "neighbour " + std::to_string(i) + " is at dist2 " + format_num(d2) + ", but the " +
                   std::to_string(i + 1) + "-th nearest is at " + format_num(want[i]);
    }
    return "";
}

struct Query {
    Vec3 p;
    int k;
    double max_dist2;
    std::string what;
};

/// The graded queries of a point set: random points near and far, the
/// points themselves, k from 0 to above n, radii from none to everything.
std::vector<Query> queries(Rng& rng, const std::vector<Vec3>& points, int count) {
    std::vector<Query> q;
    const double inf = INFINITY;
    for (int i = 0; i < count; ++i) {
        Vec3 p = points.empty() || i % 3 == 0 ? random_in_cube(rng) * 12.0 : points[rng.next_index(uint32_t(points.size()))];
        const int ks[] = {1, 5, 50, int(points.size()) + 10};
        const int k = ks[i % 4];
        // A radius halfway between two neighbours' distinct distances, so
        // that no point lies within rounding of it (a distance summed in
        // another order may differ in its last bit), or none.
        double max_dist2 = inf;
        std::string what = "k = " + std::to_string(k) + ", no radius";
        if (i % 2 == 1) {
            std::vector<double> all = brute_force(points, p, int(points.size()) + 1, inf);
            std::vector<size_t> gaps;  // j with a clear gap between all[j] and all[j + 1]
            for (size_t j = 0; j + 1 < all.size(); ++j)
                if (all[j + 1] - all[j] > 1e-9 * all[j + 1]) gaps.push_back(j);
            if (!gaps.empty()) {
                const size_t j = gaps[rng.next_index(uint32_t(gaps.size()))];
                max_dist2 = 0.5 * (all[j] + all[j + 1]);
                what = "k = " + std::to_string(k) + ", max_dist2 " + format_num(max_dist2);
            }
        }
        q.push_back({p, k, max_dist2, what});
    }
    if (!points.empty()) {
        const Vec3 p = points[0];
        q.push_back({p, 0, inf, "k = 0 (none)"});
        q.push_back({p, 10, -1, "a negative max_dist2 (none)"});
        q.push_back({p, 10, 0, "max_dist2 = 0 (the points equal to p)"});
        q.push_back({p + Vec3(3, 4, 0), 1000000, 1e4, "every point within the radius (all lie within 50), k above n"});
    }
    return q;
}

}  // namespace

TaskResult check_emit_photon(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int photons = param(spec, "photons", 20000);
    const std::vector<std::string> scenes =
        param(spec, "scenes", std::vector<std::string>{"scenes/cbox.json", "scenes/light_bulb.json"});
    Rng rng = check_rng(env.seed, "emit_photon");
    Rng edge_rng = check_rng(env.seed, "emit_photon: edges");
    CaseLog log;
    std::string sums;
    for (const std::string& name : scenes) {
        Scene scene = load_scene(env.assets_dir + "/" + name);
        LightSet lights(scene);
        for (const std::unique_ptr<Light>& light : lights.all()) {
            // 500 random photons, then u_dir on the edges of the square
            // (their own stream): (0, 0.5) and (0.5, 0) map to the rim of
            // the concentric disk, a direction in the plane of an area light
            // (cos 0, pdf_dir 0), for which sample_Le draws no ray.
            const Vec2 edges[] = {{0, 0.5}, {0.5, 0}, {0, 0.25}, {0.75, 0}};
            for (int i = 0; i < 500 + 4 * 8; ++i) {
                const bool edge = i >= 500;
                log.category(edge ? "u_dir on the edges of the square (grazing: an area light draws no ray)"
                                  : "the ray of light.sample_Le and the flux of equation 2, photon by photon");
                const Vec2 u_pos = edge ? edge_rng.next_2d() : rng.next_2d();
                const Vec2 u_dir = edge ? edges[(i - 500) % 4] : rng.next_2d();
                Rng& r = edge ? edge_rng : rng;
                const double probability = uniform(r, 0.05, 1);
                const uint64_t count = 1 + r.next_index(100000);
                const EmittedPhoton got = env.student.photon.emit_photon(*light, probability, count, u_pos, u_dir);
                const LightEmission e = light->sample_Le(u_pos, u_dir);
                const std::string where = name + ", u_pos (" + format_num(u_pos.x) + ", " + format_num(u_pos.y) +
                                          "), u_dir (" + format_num(u_dir.x) + ", " + format_num(u_dir.y) +
                                          "), P(light) " + format_num(probability) + ", N " + std::to_string(count) + ": ";
                if (!e.valid()) {
                    if (got.valid)
                        log.mismatch(where + "a valid photon where sample_Le draws no ray");
                    else
                        log.agreed();
                    continue;
                }
                const Ray ray = e.ray();
                const Color flux = e.flux() / (probability * double(count));
                if (!got.valid)
                    log.mismatch(where + "no photon, but sample_Le drew a ray");
                else if (!close(got.ray.o, ray.o, rel_tol) || !close(got.ray.d, ray.d, rel_tol))
                    log.mismatch(where + "the ray " + format_vec(got.ray.o) + " + t " + format_vec(got.ray.d) +
                                 " is not sample_Le's " + format_vec(ray.o) + " + t " + format_vec(ray.d));
                else if (!close_rel(got.flux, flux, rel_tol))
                    log.mismatch(where + "flux " + format_color(got.flux) + " instead of Le |cos| / (pdf_pos pdf_dir P N) = " +
                                 format_color(flux));
                else
                    log.agreed();
            }
        }
        log.category("the flux of N photons sums to the lights' power (z-test, |z| <= 5)");
        Color total_power, sum, sum2;
        for (const std::unique_ptr<Light>& light : lights.all())
            total_power += light->power();
        for (int i = 0; i < photons; ++i) {
            double probability = 0;
            const Light* light = lights.sample_by_power(rng.next_1d(), &probability);
            if (!light || !(probability > 0)) continue;
            const Vec2 u_pos = rng.next_2d(), u_dir = rng.next_2d();
            const EmittedPhoton e = env.student.photon.emit_photon(*light, probability, uint64_t(photons), u_pos, u_dir);
            if (!e.valid) continue;
            sum += e.flux;
            sum2 += e.flux * e.flux;
        }
        bool ok = true;
        std::string figures;
        for (int c = 0; c < 3; ++c) {
            // The sum's standard error from the photons' spread: N var = N (E[x^2] - E[x]^2), x = flux.
            const double mean = sum[c] / photons, var = std::max(0.0, sum2[c] / photons - mean * mean);
            const double se = std::sqrt(var * photons);
            const double diff = std::fabs(sum[c] - total_power[c]);
            ok = ok && std::isfinite(sum[c]) && diff <= 5 * se + 1e-6 * std::fabs(total_power[c]);
            if (c == 0)
                figures = format_num(sum[c]) + " W (standard error " + format_num(se) + ") against the power " +
                          format_num(total_power[c]) + " W (red)";
        }
        sums += (sums.empty() ? "" : "; ") + name + ": " + figures;
        if (ok)
            log.agreed();
        else
            log.mismatch(name + ", " + std::to_string(photons) + " photons: the flux sums to " + format_color(sum) +
                         ", the lights' power is " + format_color(total_power));
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "equation 2");
    r.details.insert(r.details.begin(), "sum of the photons' flux: " + sums);
    return r;
}

TaskResult check_build_kdtree(const TaskSpec& spec, const GradeEnvironment& env) {
    const int n = param(spec, "points", 2000);
    const int per_set = param(spec, "queries", 200);
    Rng rng = check_rng(env.seed, "build_kdtree");
    CaseLog log;
    for (const PointSet& set : point_sets(rng, n)) {
        log.category("the layout of stages/kdtree.h and every point kept with its id");
        const KdTree tree = env.student.photon.build_kdtree(set.points);
        std::string problem;
        if (tree.points.size() != set.points.size())
            problem = "the tree holds " + std::to_string(tree.points.size()) + " points, not " + std::to_string(set.points.size());
        else if (!kdtree_is_valid(tree))
            problem = "the split invariant, the sizes of ids and axis, or ids as a permutation do not hold "
                      "(kdtree_is_valid)";
        for (size_t i = 0; problem.empty() && i < tree.size(); ++i)
            if (!(tree.points[i] == set.points[tree.ids[i]]))
                problem = "points[" + std::to_string(i) + "] = " + format_vec(tree.points[i]) + " is not input point ids[" +
                          std::to_string(i) + "] = " + std::to_string(tree.ids[i]);
        if (!problem.empty()) {
            log.mismatch(set.name + " (" + std::to_string(set.points.size()) + " points): " + problem);
            continue;
        }
        log.agreed();
        log.category("the reference's queries on the student's tree equal brute force");
        std::vector<Neighbor> found;
        for (const Query& q : queries(rng, set.points, per_set)) {
            env.reference.photon.k_nearest(tree, q.p, q.k, q.max_dist2, found);
            std::string d = compare_neighbors(set.points, q.p, q.k, q.max_dist2, found);
            if (d.empty() && q.max_dist2 < INFINITY) {
                within_radius(tree, q.p, q.max_dist2, found);
                std::sort(found.begin(), found.end(), [](const Neighbor& a, const Neighbor& b) { return a.dist2 < b.dist2; });
                d = compare_neighbors(set.points, q.p, int(set.points.size()) + 1, q.max_dist2, found);
                if (!d.empty()) d = "radius query: " + d;
            }
            if (d.empty())
                log.agreed();
            else
                log.mismatch(set.name + ", query " + format_vec(q.p) + ", " + q.what + ": " + d);
        }
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "brute force");
}

TaskResult check_k_nearest(const TaskSpec& spec, const GradeEnvironment& env) {
    const int n = param(spec, "points", 2000);
    const int per_set = param(spec, "queries", 300);
    Rng rng = check_rng(env.seed, "k_nearest");
    CaseLog log;
    std::vector<Neighbor> found;
    for (const PointSet& set : point_sets(rng, n)) {
        const KdTree tree = env.reference.photon.build_kdtree(set.points);
        log.category("k nearest within max_dist2 against brute force: " + set.name);
        for (const Query& q : queries(rng, set.points, per_set)) {
            env.student.photon.k_nearest(tree, q.p, q.k, q.max_dist2, found);
            const std::string d = compare_neighbors(set.points, q.p, q.k, q.max_dist2, found);
            if (d.empty())
                log.agreed();
            else
                log.mismatch(set.name + " (" + std::to_string(set.points.size()) + " points), query " + format_vec(q.p) +
                             ", " + q.what + ": " + d);
        }
    }
    log.category("a point at exactly max_dist2 is found (integer grid, exact distances)");
    {
        std::vector<Vec3> grid;
        for (int x = 0; x < 6; ++x)
            for (int y = 0; y < 6; ++y)
                grid.push_back(Vec3(x, y, 0));
        const KdTree tree = env.reference.photon.build_kdtree(grid);
        for (int r2 : {1, 2, 4, 5, 8, 9}) {
            const Vec3 p(2, 3, 0);
            env.student.photon.k_nearest(tree, p, 100, double(r2), found);
            const std::string d = compare_neighbors(grid, p, 100, double(r2), found);
            if (d.empty())
                log.agreed();
            else
                log.mismatch("6 x 6 integer grid, query (2, 3, 0), max_dist2 " + std::to_string(r2) + ": " + d);
        }
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "brute force");
}

TaskResult check_density_estimate(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int lists = param(spec, "cases", 500);
    Rng rng = check_rng(env.seed, "density_estimate");
    CaseLog log;
    const std::pair<PhotonKernel, const char*> kernels[] = {
        {PhotonKernel::box, "box"}, {PhotonKernel::cone, "cone"}, {PhotonKernel::epanechnikov, "epanechnikov"}};
    auto weight = [](PhotonKernel k, double s2) {  // K(d) pi r^2, s2 = d^2 / r^2
        switch (k) {
            case PhotonKernel::box: return 1.0;
            case PhotonKernel::cone: return 3 * (1 - std::sqrt(s2));
            case PhotonKernel::epanechnikov: return 2 * (1 - s2);
        }
        return 0.0;
    };
    for (auto [kernel, name] : kernels) {
        log.category(std::string(name) + " kernel: equation 1 on hand-made lists");
        for (int i = 0; i < lists; ++i) {
            const double r2 = log_uniform(rng, 1e-4, 1e2);
            std::vector<PhotonContribution> found(1 + rng.next_index(60));
            Color want;
            for (PhotonContribution& c : found) {
                c.dist2 = i % 5 == 0 && &c == &found[0] ? r2 : r2 * rng.next_1d();  // one on the rim now and then
                c.weighted_flux = Color(rng.next_1d(), rng.next_1d(), rng.next_1d()) * log_uniform(rng, 1e-3, 1e3);
                want += c.weighted_flux * weight(kernel, c.dist2 / r2);
            }
            want = want / (kPi * r2);
            const Color got = env.student.photon.density_estimate(found, r2, kernel);
            if (close_rel(got, want, rel_tol))
                log.agreed();
            else
                log.mismatch(std::string(name) + " kernel, " + std::to_string(found.size()) + " photons, radius2 " +
                             format_num(r2) + ": " + format_color(got) + " instead of " + format_color(want));
        }
        const Color empty = env.student.photon.density_estimate({}, 1.0, kernel);
        if (empty.r == 0 && empty.g == 0 && empty.b == 0)
            log.agreed();
        else
            log.mismatch(std::string(name) + " kernel, no photons: " + format_color(empty) + " instead of black");
    }
    log.category("photons spread uniformly (density rho): the estimate is rho x flux within 2%");
    std::string figures;
    for (auto [kernel, name] : kernels) {
        // 10^6 photons of flux 1e-6 uniform over a disk of radius 2, the
        // estimate at its centre with radius 1: rho flux = 1e6 / (4 pi) 1e-6.
        // About 250,000 photons inside: the relative standard deviation is
        // about 0.2%, so 2% is about 10 of them.
        const int m = 1000000;
        std::vector<PhotonContribution> found;
        for (int i = 0; i < m; ++i) {
            const double d2 = 4 * rng.next_1d();  // uniform in area: d^2 uniform
            if (d2 <= 1) found.push_back({d2, Color(1e-6)});
        }
        const double want = 1.0 / (4 * kPi);
        const Color got = env.student.photon.density_estimate(found, 1.0, kernel);
        figures += (figures.empty() ? "" : ", ") + std::string(name) + " " + format_num(got.r / want);
        if (std::fabs(got.r / want - 1) <= 0.02 && std::fabs(got.g / want - 1) <= 0.02 && std::fabs(got.b / want - 1) <= 0.02)
            log.agreed();
        else
            log.mismatch(std::string(name) + " kernel, uniform photons: " + format_color(got) + " instead of about " +
                         format_num(want));
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "equation 1");
    r.details.insert(r.details.begin(), "uniform photons, estimate / (rho flux): " + figures);
    return r;
}

}  // namespace pt
