// Part 2, bbox_intersect: the slab test against its exact answer, on
// random rays and boxes and on the hard cases: zero and -0.0 direction
// components with the origin inside, outside and exactly on a slab's plane
// (where 1/d is infinite and 0 * inf is NaN), origins on faces, edges and
// corners, origins inside the box, every placement of [t0, t1] around the
// box, tiny, huge and far boxes, and direction components of 1e-300 and
// 1e-320 (whose inverse overflows).
//
// The exact family: small integer boxes (often flat, min = max on an axis),
// origins on whole and half units (often exactly on a face) and direction
// components of 0, -0.0 and powers of two, so that every (min - o) / d is
// exact in double. There entry = exit is a real answer (a flat box crossed
// head-on, a ray touching an edge or starting on a face: the box is
// closed, so these hit), never the edge band: `entry < exit` instead of
// `entry <= exit` loses exactly this family.
//
// The exact answer: per axis the ray is inside the closed slab between
// (min - o) / d and (max - o) / d, computed in long double; an axis with
// d = 0 constrains nothing when min <= o <= max (the ray runs inside the
// slab, or along its face: the box is closed) and excludes everything
// otherwise. entry = the largest of t0 and the slab entries, exit = the
// smallest of t1 and the exits; a hit when entry <= exit. A verdict is in
// the edge band (either answer accepted) when |exit - entry| is within
// edge_band times the scale of the figures that decide it: |entry|,
// |exit|, and (|o| + |min| + |max|) / |d| of the deciding axes (rounding
// in (min - o) / d is relative to those). A zero component is never in the
// band: its answer involves no rounding.
#include <cmath>

#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "stages/bvh.h"

namespace pt {
namespace {

struct SlabTruth {
    bool hit = false;
    long double entry = 0, exit = 0;  ///< the exact interval (when hit)
    long double width = 0;            ///< the edge band around entry = exit
};

SlabTruth slab_truth(const BBox& box, const Ray& ray, double t0, double t1, double edge_band) {
    SlabTruth s;
    long double entry = t0, exit = t1, scale_entry = 0, scale_exit = 0;
    for (int a = 0; a < 3; ++a) {
        long double o = ray.o[a], d = ray.d[a], lo = box.min[a], hi = box.max[a];
        if (d == 0) {
            if (o < lo || o > hi) return s;  // outside the slab for every t: exact
            continue;
        }
        long double near = (lo - o) / d, far = (hi - o) / d;
        if (d < 0) std::swap(near, far);
        long double scale = (fabsl(o) + fabsl(lo) + fabsl(hi)) / fabsl(d);
        if (near > entry) entry = near, scale_entry = scale;
        if (far < exit) exit = far, scale_exit = scale;
    }
    s.entry = entry;
    s.exit = exit;
    s.hit = entry <= exit;
    s.width = edge_band * (fabsl(entry) + fabsl(exit) + scale_entry + scale_exit);
    return s;
}

struct SlabInput {
    BBox box;
    Ray ray;  ///< [t_min, t_max] is the interval [t0, t1] passed in
};

BBox random_box(Rng& rng, double scale = 1) {
    Vec3 c = random_in_cube(rng) * (10 * scale);
    Vec3 h(log_uniform(rng, 1e-3, 10) * scale, log_uniform(rng, 1e-3, 10) * scale,
           log_uniform(rng, 1e-3, 10) * scale);
    if (rng.next_1d() < 0.1) h[int(rng.next_index(3))] = 0;  // a flat box (one triangle's)
    return BBox(c - h, c + h);
}

Vec3 point_in(const BBox& b, Rng& rng) {
    return {uniform(rng, b.min.x, b.max.x), uniform(rng, b.min.y, b.max.y),
            uniform(rng, b.min.z, b.max.z)};
}

/// A point outside b: in the box three times as large, not in b.
Vec3 point_around(const BBox& b, Rng& rng) {
    BBox big(b.min - b.extent() - Vec3(1e-3), b.max + b.extent() + Vec3(1e-3));
    for (;;) {
        Vec3 p = point_in(big, rng);
        if (!b.contains(p)) return p;
    }
}

double signed_zero(Rng& rng) {
    return rng.next_1d() < 0.5 ? 0.0 : -0.0;
}

/// A direction towards `target` from `o`, of a random length.
Vec3 towards(const Vec3& o, const Vec3& target, Rng& rng) {
    return (target - o).unit() * log_uniform(rng, 0.01, 100);
}

std::string describe(const SlabInput& in) {
    return "box " + format_vec(in.box.min) + " .. " + format_vec(in.box.max) +
           ", ray o = " + format_vec(in.ray.o) + " d = " + format_vec(in.ray.d) + ", [t0, t1] = [" +
           format_num(in.ray.t_min) + ", " + format_num(in.ray.t_max) + "]";
}

/// `exact`: every slab parameter of the input is exact in double, so no
/// verdict lies in the edge band.
void check_one(const SlabInput& in, BboxIntersectFn student, double rel_tol, double edge_band,
               CaseLog& log, bool exact = false) {
    double t0 = in.ray.t_min, t1 = in.ray.t_max;
    const bool hit = student(in.box, in.ray, t0, t1);
    const SlabTruth truth = slab_truth(in.box, in.ray, in.ray.t_min, in.ray.t_max, edge_band);
    const long double gap = truth.exit - truth.entry;
    const bool in_band = !exact && fabsl(gap) <= truth.width;
    if (hit && (std::isnan(t0) || std::isnan(t1) || t0 > t1)) {
        log.mismatch(describe(in) + ": says hit with the interval [" + format_num(t0) + ", " +
                     format_num(t1) + "]");
        return;
    }
    if (in_band && hit != truth.hit) {
        log.allowed();
        return;
    }
    if (hit != truth.hit) {
        log.mismatch(describe(in) + ": says " + (hit ? "hit" : "miss") + " where the ray " +
                     (truth.hit ? "is inside the box for t in [" + format_num(double(truth.entry)) +
                                      ", " + format_num(double(truth.exit)) + "]"
                                : std::string("misses it")));
        return;
    }
    if (!hit) {
        log.agreed();
        return;
    }
    auto near = [&](double got, long double want) {
        return fabsl(got - want) <= rel_tol * std::max(1.0L, fabsl(want)) + truth.width;
    };
    if (near(t0, truth.entry) && near(t1, truth.exit)) {
        log.agreed();
    } else {
        log.mismatch(describe(in) + ": narrows [t0, t1] to [" + format_num(t0) + ", " +
                     format_num(t1) + "] instead of [" + format_num(double(truth.entry)) + ", " +
                     format_num(double(truth.exit)) + "]");
    }
}

/// A slab input whose answer involves no rounding (see the header): box
/// corners on whole units, flat on one or two axes in most cases, origins
/// on half units or on a face, direction components 0, -0.0 or +-2^k, and
/// [t0, t1] = [0, inf], pinned to the exact entry or exit, or ending 1/64
/// before the entry (dyadic, so still exact).
SlabInput exact_slab_input(Rng& rng, int i) {
    auto whole = [&](int lo, int hi) { return double(lo + int(rng.next_index(hi - lo + 1))); };
    Vec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
        lo[a] = whole(-4, 3);
        hi[a] = lo[a] + (i % 3 == a || (i % 5 == 0 && (i + 1) % 3 == a) ? 0 : whole(0, 3));
    }
    BBox box(lo, hi);
    Vec3 o;
    for (int a = 0; a < 3; ++a)
        o[a] = whole(-12, 12) / 2;
    if (i % 2 == 1) {  // on a face (or an edge or a corner) of the box
        int a = int(rng.next_index(3));
        o[a] = rng.next_1d() < 0.5 ? lo[a] : hi[a];
    }
    Vec3 d;
    const double powers[] = {0.25, 0.5, 1, 2, 4};
    for (int a = 0; a < 3; ++a) {
        if (rng.next_1d() < 0.3) {
            d[a] = signed_zero(rng);
            continue;
        }
        double towards_box = 0.5 * (lo[a] + hi[a]) - o[a];
        double sign = rng.next_1d() < 0.8 ? (towards_box < 0 ? -1 : 1) : (rng.next_1d() < 0.5 ? -1 : 1);
        d[a] = sign * powers[rng.next_index(5)];
    }
    if (d == Vec3(0)) d[i % 3] = 1;
    double t0 = 0, t1 = INFINITY;
    SlabTruth t = slab_truth(box, Ray(o, d), 0, INFINITY, 0);
    if (t.hit) {
        switch (i % 6) {
            case 1: t1 = double(t.entry); break;            // ends exactly at the entry: a hit
            case 2: t0 = double(t.exit); break;             // starts exactly at the exit: a hit
            case 3: t0 = t1 = double(t.entry); break;       // one point, the entry
            case 4:  // ends 1/64 before the entry: a miss (robust tests widen t1 by ulps, not this)
                t0 = std::min(0.0, double(t.entry) - 1.0);
                t1 = double(t.entry) - 1.0 / 64;
                break;
            default: break;
        }
    }
    return {box, Ray(o, d, t0, t1)};
}

}  // namespace

TaskResult check_bbox_intersect(const TaskSpec& spec, const GradeEnvironment& env) {
    const BboxIntersectFn student = env.student.bvh.tree.bbox_intersect;
    const double rel_tol = param(spec, "rel_tol", 1e-6);
    const double band = param(spec, "edge_band", 1e-9);
    const int n = param(spec, "cases", 3000);
    Rng rng = check_rng(env.seed, "bbox_intersect");
    CaseLog log;
    auto run = [&](const BBox& box, const Vec3& o, const Vec3& d, double t0 = 0,
                   double t1 = INFINITY) {
        check_one({box, Ray(o, d, t0, t1)}, student, rel_tol, band, log);
    };
    auto run_exact = [&](const SlabInput& in) {
        check_one(in, student, rel_tol, band, log, true);
    };

    log.category("random rays");
    for (int i = 0; i < n; ++i) {
        BBox box = random_box(rng);
        BBox region(box.min - 2.0 * box.extent() - Vec3(1), box.max + 2.0 * box.extent() + Vec3(1));
        double t0 = 0, t1 = INFINITY;
        if (i % 4 == 3) t0 = uniform(rng, -5, 5), t1 = t0 + log_uniform(rng, 1e-3, 100);
        run(box, point_in(region, rng), random_unit(rng) * log_uniform(rng, 0.01, 100), t0, t1);
    }

    log.category("rays aimed at the box, and just beside it");
    for (int i = 0; i < n; ++i) {
        BBox box = random_box(rng);
        Vec3 o = point_around(box, rng);
        Vec3 target = point_in(box, rng);
        if (i % 2 == 1) {  // a point on a face, then moved off it by a relative offset
            int a = int(rng.next_index(3));
            bool high = rng.next_1d() < 0.5;
            target[a] = high ? box.max[a] : box.min[a];
            const double offsets[] = {0, 1e-13, 1e-7, 1e-4, -1e-13, -1e-7, -1e-4};
            double off = offsets[rng.next_index(7)] * std::max(1.0, box.extent()[a]);
            target[a] += high ? off : -off;
        }
        run(box, o, towards(o, target, rng));
    }

    log.category("origins inside the box");
    for (int i = 0; i < n / 4; ++i) {
        BBox box = random_box(rng);
        run(box, point_in(box, rng), random_unit(rng) * log_uniform(rng, 0.01, 100));
    }

    log.category("zero and -0.0 direction components");
    for (int i = 0; i < n; ++i) {
        BBox box = random_box(rng);
        Vec3 o = point_around(box, rng);
        Vec3 d = towards(o, point_in(box, rng), rng);
        int zeros = 1 + int(rng.next_index(2));
        int first = int(rng.next_index(3));
        for (int k = 0; k < zeros; ++k) {
            int a = (first + k) % 3;
            d[a] = signed_zero(rng);
            switch (rng.next_index(5)) {  // where the origin lies along the zero axis
                case 0:
                    o[a] = box.min[a];
                    break;  // on the slab's plane: 0 * inf
                case 1:
                    o[a] = box.max[a];
                    break;
                case 2:
                    o[a] = uniform(rng, box.min[a], box.max[a]);
                    break;
                case 3:
                    o[a] = box.min[a] - log_uniform(rng, 1e-9, 10);
                    break;
                default:
                    o[a] = box.max[a] + log_uniform(rng, 1e-9, 10);
                    break;
            }
        }
        if (d == Vec3(0)) d[first] = 1;
        run(box, o, d);
    }

    log.category("origins on faces, edges and corners");
    for (int i = 0; i < n / 2; ++i) {
        BBox box = random_box(rng);
        Vec3 o = point_in(box, rng);
        int on = 1 + int(rng.next_index(3));  // 1 face, 2 edge, 3 corner
        int first = int(rng.next_index(3));
        for (int k = 0; k < on; ++k) {
            int a = (first + k) % 3;
            o[a] = rng.next_1d() < 0.5 ? box.min[a] : box.max[a];
        }
        Vec3 d = random_unit(rng);
        if (i % 3 == 0) d[first] = signed_zero(rng);  // along the face it starts on
        if (d == Vec3(0)) d.z = 1;
        run(box, o, d);
    }

    log.category("[t0, t1] before, after, inside and around the box");
    for (int i = 0; i < n / 2; ++i) {
        BBox box = random_box(rng);
        Vec3 o = point_around(box, rng);
        Vec3 d = towards(o, point_in(box, rng), rng);
        SlabTruth t = slab_truth(box, Ray(o, d), -INFINITY, INFINITY, 0);
        if (!t.hit) continue;
        double entry = double(t.entry), exit = double(t.exit), len = exit - entry;
        switch (i % 8) {
            case 0:
                run(box, o, d, 0, entry - 0.5 * len);
                break;  // ends before
            case 1:
                run(box, o, d, exit + 0.5 * len, INFINITY);
                break;  // starts after
            case 2:
                run(box, o, d, entry + 0.25 * len, entry + 0.5 * len);
                break;  // inside
            case 3:
                run(box, o, d, entry - len, entry + 0.5 * len);
                break;  // overlaps the entry
            case 4:
                run(box, o, d, entry + 0.5 * len, exit + len);
                break;  // overlaps the exit
            case 5:
                run(box, o, d, -exit - len, -entry);
                break;  // box ahead, t < 0
            case 6:
                run(box, o, -d, -INFINITY, 0);
                break;  // box behind, t <= 0
            default:
                run(box, o, d, 0, entry);
                break;  // ends exactly at the entry: the band
        }
    }

    for (int i = 0; i < n / 4; ++i) {
        const double scales[] = {1e-6, 1e6};
        BBox box = random_box(rng, scales[i % 2]);
        if (i % 3 == 0) box = BBox(box.min + Vec3(1e6), box.max + Vec3(1e6));
        Vec3 o = point_around(box, rng);
        Vec3 d = towards(o, point_in(box, rng), rng);
        log.category("tiny, huge and far boxes");
        if (i % 4 == 1) {
            // 1e-320 is subnormal: 1 / d overflows to inf, so a slab test
            // that multiplies by a precomputed 1 / d (pbrt-v3's
            // Bounds3::IntersectP) gets 0 * inf = NaN or a wrong side here.
            log.category("direction components of 1e-300 and 1e-320 (1 / d overflows)");
            int a = int(rng.next_index(3));
            d[a] = std::copysign(i % 8 == 1 ? 1e-300 : 1e-320, rng.next_1d() - 0.5);
            if (rng.next_1d() < 0.5) o[a] = rng.next_1d() < 0.5 ? box.min[a] : box.max[a];
        }
        run(box, o, d);
    }

    log.category("exact answers: flat boxes, touching rays, origins on faces");
    for (int i = 0; i < n / 2; ++i) {
        run_exact(exact_slab_input(rng, i));
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "the exact answer");
}

}  // namespace pt
