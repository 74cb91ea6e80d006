// The 8-wide packet traversal's two shortcuts (stages/bvh_packet_rays.h,
// stages/bvh_packet_frustum.h): the eight rays prepared at once give every
// SlabRay field bit for bit, and the packet's frustum never clears a child
// box that one of its rays hits. Deterministic (fixed seeds); skipped on a
// processor without AVX2, where neither runs.
#include <doctest/doctest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <random>

#include "stages/bvh_packet_frustum.h"
#include "stages/bvh_packet_rays.h"
#include "stages/bvh_wide_slab.h"

using namespace pt;
using namespace pt::bvh_kernels;

#if PT_WIDE_BVH_X86

namespace {

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The prepared lanes, stored; false when prepare_packet declined.
struct Lanes {
    float o_near[3][8], o_far[3][8], inv[3][8], t_min[8], t_box[8];
};
[[gnu::target("avx2")]] bool prepare_lanes(const Ray* rays, int count, Lanes& out) {
    AvxPacketRays p;
    if (!prepare_packet(rays, count, true, p)) return false;
    for (int a = 0; a < 3; ++a) {
        _mm256_storeu_ps(out.o_near[a], p.o_near[a]);
        _mm256_storeu_ps(out.o_far[a], p.o_far[a]);
        _mm256_storeu_ps(out.inv[a], p.inv[a]);
    }
    _mm256_storeu_ps(out.t_min, p.t_min);
    _mm256_storeu_ps(out.t_box, p.t_box);
    return true;
}

/// A value of the kinds that exercise the directed roundings: exact floats,
/// -0 and +0, tiny values that round to 0 or to subnormals, large ones,
/// and general doubles of either sign.
double awkward(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    switch (rng() % 8) {
        case 0: return double(float(u(rng) * 10));  // exactly a float
        case 1: return rng() % 2 ? 0.0 : -0.0;
        case 2: return u(rng) * 1e-44;  // near the smallest subnormal float
        case 3: return u(rng) * 1e-300;  // rounds to a signed zero
        case 4: return u(rng) * 1e30;
        default: return u(rng) * 100;
    }
}

/// The frustum's and the per-ray answers for one node: bit i of `any_ray`
/// when some ray of the packet hits child i, `frustum` the test's mask.
struct NodeAnswers {
    unsigned any_ray = 0, frustum = 0;
};
[[gnu::target("avx2")]] NodeAnswers node_answers(const Ray* rays, const WideBvhNode<8>& node) {
    NodeAnswers n;
    AvxPacketRays p;
    REQUIRE(prepare_packet(rays, kPacketSize, true, p));
    const AvxPacketFrustum frustum(p);
    REQUIRE(frustum.usable);
    alignas(32) float t_box[8];
    _mm256_store_ps(t_box, p.t_box);
    float t_max = -INFINITY;
    for (int k = 0; k < kPacketSize; ++k) {
        const SlabRay slab(rays[k], true);
        float t_enter[8];
        n.any_ray |= ScalarWideSlab<8>(slab).test(node, t_box[k], t_enter);
        t_max = std::max(t_max, t_box[k]);
    }
    n.frustum = frustum.test(node, t_max);
    return n;
}

}  // namespace

TEST_CASE("packet rays prepared at once equal SlabRay bit for bit") {
    if (!wide_bvh_has_avx()) return;
    std::mt19937_64 rng(20261203);
    int prepared = 0, declined = 0, mismatches = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Ray rays[kPacketSize];
        const int count = 1 + int(rng() % kPacketSize);
        for (int k = 0; k < count; ++k) {
            Vec3 o(awkward(rng), awkward(rng), awkward(rng)), d(awkward(rng), awkward(rng), awkward(rng));
            double t_min = rng() % 2 ? 0.0 : std::fabs(awkward(rng));
            double t_max = rng() % 3 == 0 ? kInfinity : t_min + std::fabs(awkward(rng)) * 1e10;
            rays[k] = Ray(o, d, t_min, t_max);
        }
        Lanes lanes;
        if (!prepare_lanes(rays, count, lanes)) {
            ++declined;
            continue;
        }
        ++prepared;
        for (int k = 0; k < kPacketSize; ++k) {
            const Ray& ray = rays[k < count ? k : 0];
            const SlabRay s(ray, true);
            bool same = same_bits(lanes.t_min[k], s.t_min) && same_bits(lanes.t_box[k], box_t_max(ray.t_max));
            for (int a = 0; a < 3; ++a) {
                same = same && same_bits(lanes.o_near[a][k], s.o_near[a]) &&
                       same_bits(lanes.o_far[a][k], s.o_far[a]) && same_bits(lanes.inv[a][k], s.inv_near[a]) &&
                       same_bits(lanes.inv[a][k], s.inv_far[a]) && std::signbit(lanes.inv[a][k]) == s.negative[a];
            }
            if (!same) ++mismatches;
        }
    }
    CHECK(mismatches == 0);
    CHECK(prepared > 500);  // both paths taken (823 with this seed)
    CHECK(declined > 1000);
}

TEST_CASE("packet rays: SlabRay's special cases are declined") {
    if (!wide_bvh_has_avx()) return;
    Ray base(Vec3(0.1, 0.2, 0.3), Vec3(0.3, -0.4, 0.8));
    Lanes lanes;
    Ray rays[kPacketSize];
    for (Ray& r : rays)
        r = base;
    CHECK(prepare_lanes(rays, kPacketSize, lanes));
    rays[5].d.y = 0;  // 1/d infinite
    CHECK_FALSE(prepare_lanes(rays, kPacketSize, lanes));
    CHECK(prepare_lanes(rays, 5, lanes));  // the ray is not in the packet
    rays[5].d.y = 1e-40;  // 1/d overflows float
    CHECK_FALSE(prepare_lanes(rays, kPacketSize, lanes));
    rays[5] = base;
    rays[2].o.z = 2e30;  // visit every box
    CHECK_FALSE(prepare_lanes(rays, kPacketSize, lanes));
    rays[2] = base;
    rays[7].d = Vec3(1e-8, 0, 0);  // visit every box (and 1/0)
    CHECK_FALSE(prepare_lanes(rays, kPacketSize, lanes));
}

TEST_CASE("packet frustum never clears a child box that a ray of the packet hits") {
    if (!wide_bvh_has_avx()) return;
    // Camera-like packets (one origin or nearby ones, directions within a
    // narrow cone, every axis one sign) against nodes of small random boxes
    // around the rays' paths, some touching a ray exactly at a corner.
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    int missed = 0, cleared = 0, hit = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Vec3 eye(u(rng) * 5, u(rng) * 5, u(rng) * 5);
        Vec3 dir(0.3 + std::fabs(u(rng)), -(0.3 + std::fabs(u(rng))), 0.3 + std::fabs(u(rng)));
        if (rng() % 2) dir.x = -dir.x;
        if (rng() % 2) dir.z = -dir.z;
        const double spread = trial % 2 ? 1e-3 : 0.05, lens = trial % 3 == 0 ? 1e-2 : 0;
        Ray rays[kPacketSize];
        for (Ray& r : rays) {
            Vec3 o = eye + lens * Vec3(u(rng), u(rng), u(rng));
            r = Ray(o, dir + spread * Vec3(u(rng), u(rng), u(rng)), 0.0, rng() % 4 ? kInfinity : 5.0 + u(rng));
        }
        WideBvhNode<8> node;
        node.valid = 0;
        for (int c = 0; c < 8; ++c) {
            if (rng() % 8 == 0) {  // an unused lane: the empty box
                for (int a = 0; a < 3; ++a) {
                    node.bounds[a][c] = INFINITY;
                    node.bounds[3 + a][c] = -INFINITY;
                }
                continue;
            }
            node.valid |= uint8_t(1u << c);
            const Ray& r = rays[rng() % kPacketSize];
            Vec3 centre = r.o + (std::fabs(u(rng)) * 10) * r.d + (rng() % 2 ? 0.0 : 0.3) * Vec3(u(rng), u(rng), u(rng));
            double half = rng() % 4 == 0 ? 0.0 : std::fabs(u(rng)) * 0.1;  // some boxes are points
            for (int a = 0; a < 3; ++a) {
                node.bounds[a][c] = float(centre[a] - half);
                node.bounds[3 + a][c] = float(centre[a] + half);
            }
        }
        const NodeAnswers n = node_answers(rays, node);
        missed += __builtin_popcount(n.any_ray & ~n.frustum);
        cleared += __builtin_popcount(node.valid & ~n.frustum);
        hit += __builtin_popcount(n.any_ray);
    }
    CHECK(missed == 0);
    CHECK(cleared > 10000);  // the test does clear boxes
    CHECK(hit > 10000);      // and rays do hit some
}

#endif
