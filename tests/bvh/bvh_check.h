// Checks shared by the BVH tests: answers of the linear scan, agreement of
// an accelerator with them, and the structural invariants of a FlatBvh.
#pragma once

#include <algorithm>

#include <doctest/doctest.h>

#include <cstring>

#include "bvh_test_scenes.h"
#include "stages/bvh.h"
#include "stages/flat_bvh.h"
#include "stages/stages.h"

namespace pt::test {

inline bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The reference triangle routine behind a different function pointer:
/// makes the reference BVH call through the stage table (the student path).
inline std::optional<Hit> called_triangle(const Triangle& t, const Ray& r) {
    return reference::intersect_triangle(t, r);
}

inline const IntersectStage kReference{reference::intersect_triangle, reference::intersect_sphere};
inline const IntersectStage kCalled{called_triangle, reference::intersect_sphere};

struct Expected {
    std::vector<std::optional<Hit>> hits;
    std::vector<bool> occluded;
};

inline const IntersectStage kWatertight{reference::intersect_triangle_watertight, reference::intersect_sphere};

inline Expected linear_answers(const Scene& scene, const std::vector<Ray>& rays,
                               const IntersectStage& stage = kReference) {
    auto linear = make_linear_scan(scene, stage);
    Expected e;
    for (const Ray& r : rays) {
        e.hits.push_back(linear->intersect(r));
        e.occluded.push_back(linear->occluded(r));
    }
    return e;
}

/// Checks `accel` against the expected answers; reports the first mismatch.
inline void check_agrees(const Accelerator& accel, const std::vector<Ray>& rays,
                         const Expected& expected, bool compare_bits = true) {
    int mismatches = 0, any_hit_mismatches = 0;
    auto compare = [&](const std::optional<Hit>& got, size_t i, const char* query) {
        const std::optional<Hit>& want = expected.hits[i];
        bool ok = got.has_value() == want.has_value();
        if (ok && got) {
            ok = got->primitive == want->primitive && same_bits(got->t, want->t);
            if (compare_bits)
                ok = ok && same_bits(got->b1, want->b1) && same_bits(got->b2, want->b2) &&
                     got->n == want->n;
        }
        if (!ok && mismatches++ == 0) {
            const Ray& r = rays[i];
            INFO(query << ": ray " << i << " o=(" << r.o.x << "," << r.o.y << "," << r.o.z << ") d=(" << r.d.x
                       << "," << r.d.y << "," << r.d.z << ") t=[" << r.t_min << "," << r.t_max << "]");
            INFO("linear: " << (want ? std::to_string(want->primitive) + " t=" + std::to_string(want->t)
                                     : "miss"));
            INFO("bvh:    " << (got ? std::to_string(got->primitive) + " t=" + std::to_string(got->t)
                                    : "miss"));
            CHECK(ok);
        }
    };
    for (size_t i = 0; i < rays.size(); ++i) {
        compare(accel.intersect(rays[i]), i, "intersect");
        if (accel.occluded(rays[i]) != expected.occluded[i]) ++any_hit_mismatches;
        if (expected.occluded[i] != expected.hits[i].has_value()) ++any_hit_mismatches;
    }
    // The same rays in packets of every size from 1 to kPacketSize, in turn.
    std::optional<Hit> packet[kPacketSize];
    for (size_t i = 0, size = 1; i < rays.size(); i += size, size = size % kPacketSize + 1) {
        int count = int(std::min(size, rays.size() - i));
        accel.intersect_packet(&rays[i], count, packet);
        for (int k = 0; k < count; ++k)
            compare(packet[k], i + k, "intersect_packet");
    }
    CHECK(mismatches == 0);
    CHECK(any_hit_mismatches == 0);
}

/// The invariants of a built FlatBvh over `scene`: every primitive in
/// exactly one leaf, every node reachable, child boxes inside their parent,
/// leaf boxes around their primitives, leaves of 1 to max_leaf primitives,
/// depth within kMaxBvhDepth.
inline void check_structure(const FlatBvh& bvh, const Scene& scene, int max_leaf) {
    const uint32_t n = scene.primitive_count();
    REQUIRE(bvh.primitives.size() == n);
    if (n == 0) {
        CHECK(bvh.nodes.empty());
        return;
    }
    std::vector<int> seen(n, 0);
    std::vector<int> reached(bvh.nodes.size(), 0);
    int deepest = 0, bad_children = 0, bad_leaves = 0, bad_boxes = 0;
    std::vector<std::pair<uint32_t, int>> stack{{0, 0}};
    while (!stack.empty()) {
        auto [index, depth] = stack.back();
        stack.pop_back();
        REQUIRE(index < bvh.nodes.size());
        ++reached[index];
        deepest = std::max(deepest, depth);
        const FlatBvhNode& node = bvh.nodes[index];
        BBox box = node.box();
        if (node.is_leaf()) {
            if (node.count > max_leaf || node.offset + node.count > n) ++bad_leaves;
            for (uint32_t i = node.offset; i < node.offset + node.count && i < n; ++i) {
                uint32_t prim = bvh.primitives[i];
                REQUIRE(prim < n);
                ++seen[prim];
                if (!box.contains(padded_primitive_bounds(scene, prim))) ++bad_boxes;
            }
            continue;
        }
        uint32_t left = index + 1, right = node.offset;
        if (!(right > left && right < bvh.nodes.size())) {
            ++bad_children;
            continue;
        }
        for (uint32_t child : {left, right}) {
            if (!box.contains(bvh.nodes[child].box())) ++bad_boxes;
            stack.push_back({child, depth + 1});
        }
    }
    CHECK(bad_children == 0);
    CHECK(bad_leaves == 0);
    CHECK(bad_boxes == 0);
    CHECK(deepest == bvh.depth);
    CHECK(bvh.depth <= kMaxBvhDepth);
    CHECK(std::count(seen.begin(), seen.end(), 1) == long(n));
    CHECK(std::count(reached.begin(), reached.end(), 1) == long(bvh.nodes.size()));
}

}  // namespace pt::test
