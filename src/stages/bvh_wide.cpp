// Traversing the 4- and 8-wide BVH (stages/bvh_wide.h): closest hit with
// the children hit visited nearest first, any hit in lane order; the box
// tests are in stages/bvh_wide_slab.h, the leaves in stages/bvh_kernels.h.
#include "stages/bvh_wide.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/counters.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/bvh_kernels.h"
#include "stages/bvh_leaf_block.h"
#include "stages/bvh_packet_rays.h"
#include "stages/bvh_wide_slab.h"
#include "stages/huge_page_allocator.h"

namespace pt {
namespace {

using namespace bvh_kernels;

/// A child to visit: a wide node, or a leaf's slots.
struct ChildRef {
    uint32_t index;  ///< node index, or first slot of a leaf (kBlockLeaf: its first block)
    uint32_t count;  ///< 0: a node; else the leaf's primitive count
};

/// Set in a leaf's child index when the leaf is stored as TriangleBlocks
/// (bvh_leaf_block.h) and the rest is the index of its first block.
constexpr uint32_t kBlockLeaf = 0x80000000u;
/// Also set (with kBlockLeaf) when the leaf's blocks are FloatCornerBlocks.
constexpr uint32_t kFloatLeaf = 0x40000000u;
/// Set in a closest hit's block lane (4 * block + lane) for a FloatCornerBlock.
constexpr uint32_t kFloatLane = 0x80000000u;

template <class Tester, int W>
class WideReferenceBvh final : public Accelerator {
  public:
    using Node = WideBvhNode<W>;

    WideReferenceBvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh, bool simd)
        : generic_prims_(uses_blocks(bvh, simd) ? generic_primitives(scene) : std::vector<uint8_t>()),
          primitives_(leaf_order(bvh, generic_prims_, uses_blocks(bvh, simd), plan_)),
          tester_(make_tester(scene, stage, primitives_, uses_blocks(bvh, simd), generic_prims_)),
          split_(bvh.split), simd_(simd && PT_WIDE_BVH_X86 && (W == 4 || wide_bvh_has_avx())) {
        if (!bvh.nodes.empty()) {
            const FlatBvhNode& root = bvh.nodes[0];
            for (int a = 0; a < 3; ++a)
                float_scene_ = float_scene_ && std::fabs(root.bounds[a]) <= 1e30f &&
                               std::fabs(root.bounds[3 + a]) <= 1e30f;
            const std::vector<Node> nodes = collapse_to_wide<W>(bvh, &depth_, plan_.empty() ? nullptr : &plan_);
            plan_ = {};
            nodes_.assign(nodes.begin(), nodes.end());
            if constexpr (kBlocks) {
                if (simd_ && primitives_.size() < kFloatLeaf) make_blocks(scene);
            }
        }
        generic_prims_ = {};  // only needed until here
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        Hit best;
        uint32_t best_slot = 0, best_lane = kNoLane;
        if (nodes_.empty()) return std::nullopt;
        bool found = false;
#if PT_WIDE_BVH_X86
        if (simd_)
            found = W == 4 ? closest_hit_sse(ray, best, best_slot) : closest_hit_avx(ray, best, best_slot, best_lane);
        else
#endif
            found = closest_hit<ScalarWideSlab<W>>(ray, best, best_slot);
        if (!found) return std::nullopt;
        finish_hit(best_slot, best_lane, ray, best);
        best.primitive = primitives_[best_slot];
        return best;
    }

    bool shares_packet_traversal() const override { return !nodes_.empty(); }

    void intersect_packet(const Ray* rays, int count, std::optional<Hit>* hits) const override {
        if (nodes_.empty() || count <= 1) {
            for (int i = 0; i < count; ++i)
                hits[i] = intersect(rays[i]);
            return;
        }
        Packet p;
#if PT_WIDE_BVH_X86
        if (simd_) {
            if (W == 4) closest_hit_packet_sse(rays, count, p);
            else closest_hit_packet_avx(rays, count, p);
        } else
#endif
            closest_hit_packet<PerRayPacketSlab<W, ScalarWideSlab<W>>>(rays, count, p);
        for (int i = 0; i < count; ++i) {
            if (!(p.found >> i & 1)) {
                hits[i] = std::nullopt;
                continue;
            }
            finish_hit(p.best_slot[i], p.best_lane[i], rays[i], p.best[i]);
            p.best[i].primitive = primitives_[p.best_slot[i]];
            hits[i] = p.best[i];
        }
    }

    bool occluded(const Ray& ray) const override {
        if (nodes_.empty()) return false;
#if PT_WIDE_BVH_X86
        if (simd_) return W == 4 ? any_hit_sse(ray) : any_hit_avx(ray);
#endif
        return any_hit<ScalarWideSlab<W>>(ray);
    }

    AcceleratorInfo info() const override {
        uint64_t tree = nodes_.size() * sizeof(Node) + primitives_.size() * sizeof(uint32_t);
        uint64_t blocks = blocks_.size() * (sizeof(TriangleBlock) + sizeof(uint32_t)) +
                          float_blocks_.size() * (sizeof(FloatCornerBlock) + sizeof(uint32_t));
        return {"bvh" + std::to_string(W) + "-" + to_string(split_), nodes_.size(), depth_,
                tree + tester_.bytes() + blocks, tree};
    }

  private:
    static constexpr uint32_t kNoLane = UINT32_MAX;
    /// A packet's results: per ray the closest hit so far and its slot.
    struct Packet {
        // Not initialised (that cost about a twentieth of a packet of
        // camera rays): ray i's entries are written before they are read,
        // when its found bit is set.
        Packet() {}
        union {
            Hit best[kPacketSize];
        };
        uint32_t best_slot[kPacketSize];
        /// For a closest hit found in a leaf block: 4 * block + lane (| kFloatLane); else kNoLane.
        uint32_t best_lane[kPacketSize] = {kNoLane, kNoLane, kNoLane, kNoLane, kNoLane, kNoLane, kNoLane, kNoLane};
        uint32_t found = 0;  ///< bit i: ray i has a hit
    };

#if PT_WIDE_BVH_X86
    // The SIMD entry points: each inlines the whole traversal (flatten), so
    // that the box test runs in registers; the AVX2 ones are compiled for
    // AVX2 and only called when the processor has it (simd_).
    [[gnu::flatten]] bool closest_hit_sse(const Ray& ray, Hit& best, uint32_t& best_slot) const {
        if constexpr (W == 4) return closest_hit<SseWideSlab>(ray, best, best_slot);
        return false;
    }
    [[gnu::flatten]] bool any_hit_sse(const Ray& ray) const {
        if constexpr (W == 4) return any_hit<SseWideSlab>(ray);
        return false;
    }
    [[gnu::flatten, gnu::target("avx2")]] bool closest_hit_avx(const Ray& ray, Hit& best, uint32_t& best_slot,
                                                               uint32_t& best_lane) const {
        if constexpr (W == 8) return closest_hit<AvxWideSlab, kBlocks>(ray, best, best_slot, &best_lane);
        return false;
    }
    [[gnu::flatten, gnu::target("avx2")]] bool any_hit_avx(const Ray& ray) const {
        if constexpr (W == 8) return any_hit<AvxWideSlab, kBlocks>(ray);
        return false;
    }
    [[gnu::flatten]] void closest_hit_packet_sse(const Ray* rays, int count, Packet& p) const {
        if constexpr (W == 4) closest_hit_packet<PerRayPacketSlab<4, SseWideSlab>>(rays, count, p);
    }
    [[gnu::flatten, gnu::target("avx2")]] void closest_hit_packet_avx(const Ray* rays, int count, Packet& p) const {
        if constexpr (W == 8) closest_hit_packet<AvxPacketSlab, kBlocks>(rays, count, p);
    }
#endif

    /// Closest hit: at each node the W boxes are tested at once. One child
    /// hit: go on into it. More: push them all, sort the pushed run so the
    /// nearest is on top (insertion sort of at most W), and go on into it;
    /// the others wait on the stack with their entry distances and are
    /// skipped once the closest hit lies before them (as in the binary
    /// traversal, bvh_traverse.cpp).
    template <class Slab, bool Blocks = false>
    bool closest_hit(const Ray& ray, Hit& best, uint32_t& best_slot, uint32_t* best_lane = nullptr) const {
        const SlabRay slab = slab_ray<Slab>(ray);
        const Slab boxes(slab);
        const typename Tester::RayData query = tester_.prepare(ray);
        Ray r = ray;
        float t_box = box_t_max(r.t_max), t_cull = t_box * kFarScale;
        bool found = false;
        uint64_t visited = 0, tests = 0;

        struct Entry {
            ChildRef ref;
            float t;  ///< where the ray enters the child's box
        };
        Entry stack[(W - 1) * kMaxBvhDepth + W];  // at most W - 1 kept per level
        int size = 0;
        ChildRef current{0, 0};
        Hit hit;
        for (;;) {
            if (current.count == 0) {
                const Node& node = nodes_[current.index];
                alignas(32) float t_enter[W];
                unsigned mask = boxes.test(node, t_box, t_enter);
                visited += W;
                if (mask != 0) {
                    int i = __builtin_ctz(mask);
                    mask &= mask - 1;
                    if (mask == 0) {  // one child hit: no stack, no sort
                        current = {node.child[i], node.count[i]};
                        continue;
                    }
                    if ((mask & (mask - 1)) == 0) {  // two: the farther kept, the nearer entered (the sort's order)
                        const int k = __builtin_ctz(mask);
                        const bool i_first = t_enter[i] < t_enter[k];
                        const int near = i_first ? i : k, far = i_first ? k : i;
                        stack[size++] = {{node.child[far], node.count[far]}, t_enter[far]};
                        current = {node.child[near], node.count[near]};
                        continue;
                    }
                    // More: the nearest (the one the sort below would leave on
                    // top: ties to the later lane) entered, the others sorted.
                    int n = i;
                    for (unsigned m = mask; m != 0; m &= m - 1)
                        if (t_enter[__builtin_ctz(m)] <= t_enter[n]) n = __builtin_ctz(m);
                    mask = (mask | 1u << i) & ~(1u << n);
                    const int run = size;
                    for (; mask != 0; mask &= mask - 1) {
                        i = __builtin_ctz(mask);
                        Entry e{{node.child[i], node.count[i]}, t_enter[i]};
                        int j = size++;
                        for (; j > run && stack[j - 1].t < e.t; --j)  // farthest at the bottom
                            stack[j] = stack[j - 1];
                        stack[j] = e;
                    }
                    current = {node.child[n], node.count[n]};
                    continue;
                }
            } else if (Blocks && (current.index & kBlockLeaf)) {
                tests += current.count;
                if (block_leaf_closest(current, r, best, best_slot, best_lane, found)) {
                    t_box = box_t_max(r.t_max);
                    t_cull = t_box * kFarScale;
                }
            } else {
                for (uint32_t slot = current.index, end = current.index + current.count; slot < end; ++slot) {
                    ++tests;
                    if (!tester_.intersect(slot, r, query, hit)) continue;
                    // hit.t <= r.t_max = best.t here; at equal t the larger id wins.
                    if (found && hit.t == best.t && primitives_[slot] < primitives_[best_slot]) continue;
                    best = hit;
                    best_slot = slot;
                    if (best_lane) *best_lane = kNoLane;
                    found = true;
                    r.t_max = hit.t;
                    t_box = box_t_max(r.t_max);
                    t_cull = t_box * kFarScale;
                }
            }
            // Next: the most recently kept child that the closest hit has not passed.
            bool next = false;
            while (size > 0) {
                const Entry& e = stack[--size];
                if (e.t <= t_cull) {
                    current = e.ref;
                    next = true;
                    break;
                }
            }
            if (!next) break;
        }
        add_counts(visited, tests);
        return found;
    }

    /// Closest hits of a packet: one traversal for all its rays. Each node
    /// is fetched and decided once; the active rays test its W boxes (each
    /// ray exactly as the single-ray test, so the same answers; PacketSlab
    /// is one of bvh_wide_slab.h's packet tests), and a child is visited by
    /// the rays that hit its box, nearest first by the smallest entry
    /// distance among them. A kept child is skipped, for each of its rays, once that
    /// ray's closest hit lies before the child's smallest entry distance (a
    /// conservative cull: a ray kept too long only tests boxes it then misses).
    template <class PacketSlab, bool Blocks = false>
    void closest_hit_packet(const Ray* rays, int count, Packet& p) const {
        typename Tester::RayData query[kPacketSize];
        double t_max[kPacketSize];  // each ray's interval ends here (its closest hit so far)
        // Unused lanes: an empty interval, so that no box test passes.
        alignas(32) float t_box[kPacketSize], t_cull[kPacketSize];
        SlabRay slabs[kPacketSize];  // the per-ray box tests keep a pointer to these
        const PacketSlab boxes = prepare_packet_slab<PacketSlab>(rays, count, slabs, t_box);
        for (int k = count; k < kPacketSize; ++k)
            t_box[k] = -INFINITY;
        for (int k = 0; k < kPacketSize; ++k)
            t_cull[k] = t_box[k] * kFarScale;
        for (int k = 0; k < count; ++k) {
            query[k] = tester_.prepare(rays[k]);
            t_max[k] = rays[k].t_max;
        }
        uint64_t visited = 0, tests = 0;

        struct Entry {
            ChildRef ref;
            uint32_t rays;  ///< bit k: ray k entered the child's box
            float t;        ///< the smallest entry distance among those rays
        };
        Entry stack[(W - 1) * kMaxBvhDepth + W];
        int size = 0;
        ChildRef current{0, 0};
        uint32_t active = (1u << count) - 1;
        Hit hit;
        for (;;) {
            if (current.count == 0) {
                const Node& node = nodes_[current.index];
                uint32_t lane_rays[W];
                float lane_t[W];
                unsigned any = boxes.test(node, active, t_box, lane_rays, lane_t);
                visited += uint64_t(W) * uint64_t(__builtin_popcount(active));
                if (any != 0) {
                    // As the single-ray traversal: push the children hit,
                    // farthest at the bottom, and go on into the nearest.
                    const int run = size;
                    for (; any != 0; any &= any - 1) {
                        int i = __builtin_ctz(any);
                        Entry e{{node.child[i], node.count[i]}, lane_rays[i], lane_t[i]};
                        prefetch_child(e.ref);
                        int j = size++;
                        for (; j > run && stack[j - 1].t < e.t; --j)
                            stack[j] = stack[j - 1];
                        stack[j] = e;
                    }
                    --size;
                    current = stack[size].ref;
                    active = stack[size].rays;
                    continue;
                }
            } else if (Blocks && (current.index & kBlockLeaf)) {
                tests += uint64_t(current.count) * uint64_t(__builtin_popcount(active));
                for (uint32_t changed = block_leaf_closest_packet(current, active, rays, t_max, p); changed != 0;
                     changed &= changed - 1) {
                    const int k = __builtin_ctz(changed);
                    t_box[k] = box_t_max(t_max[k]);
                    t_cull[k] = t_box[k] * kFarScale;
                }
            } else {
                const uint32_t first_slot = leaf_slot(current.index);
                for (uint32_t a = active; a != 0; a &= a - 1) {
                    int k = __builtin_ctz(a);
                    Ray r = rays[k];
                    r.t_max = t_max[k];
                    for (uint32_t slot = first_slot, end = first_slot + current.count; slot < end; ++slot) {
                        ++tests;
                        if (!tester_.intersect(slot, r, query[k], hit)) continue;
                        // As the single-ray traversal: at equal t the larger id wins.
                        if ((p.found >> k & 1) && hit.t == p.best[k].t &&
                            primitives_[slot] < primitives_[p.best_slot[k]])
                            continue;
                        p.best[k] = hit;
                        p.best_slot[k] = slot;
                        p.best_lane[k] = kNoLane;
                        p.found |= 1u << k;
                        r.t_max = t_max[k] = hit.t;
                        t_box[k] = box_t_max(t_max[k]);
                        t_cull[k] = t_box[k] * kFarScale;
                    }
                }
            }
            // Next: the most recently kept child with a ray that has not passed it.
            bool next = false;
            while (size > 0) {
                const Entry& e = stack[--size];
                const uint32_t rays_left = boxes.not_passed(e.t, t_cull) & e.rays;
                if (rays_left != 0) {
                    current = e.ref;
                    active = rays_left;
                    next = true;
                    break;
                }
            }
            if (!next) break;
        }
        add_counts(visited, tests);
    }

    /// Asks for a child's node or first leaf block ahead of its visit.
    void prefetch_child(ChildRef c) const {
#if PT_WIDE_BVH_X86
        const char* p = nullptr;
        size_t bytes = 0;
        if (c.count == 0) {
            p = reinterpret_cast<const char*>(&nodes_[c.index]);
            bytes = sizeof(Node);
        } else if (kBlocks && (c.index & kFloatLeaf)) {
            p = reinterpret_cast<const char*>(&float_blocks_[c.index & ~(kBlockLeaf | kFloatLeaf)]);
            bytes = sizeof(FloatCornerBlock);
        } else if (kBlocks && (c.index & kBlockLeaf)) {
            p = reinterpret_cast<const char*>(&blocks_[c.index & ~kBlockLeaf]);
            bytes = sizeof(TriangleBlock);
        }
        for (size_t o = 0; o < bytes; o += 64)
            _mm_prefetch(p + o, _MM_HINT_T0);
#else
        (void)c;
#endif
    }

    /// The packet's box test, its rays prepared (unused lanes repeat ray 0;
    /// in `slabs`, which must outlive it, when prepared one by one), and
    /// each ray's box_t_max in t_box. AVX2: all rays at once
    /// (bvh_packet_rays.h), unless one needs SlabRay's special cases.
    template <class PacketSlab>
    PacketSlab prepare_packet_slab(const Ray* rays, int count, SlabRay* slabs, float* t_box) const {
#if PT_WIDE_BVH_X86
        if constexpr (std::is_same_v<PacketSlab, AvxPacketSlab>)
            return prepare_packet_slab_avx(rays, count, slabs, t_box);
        else
#endif
            return prepare_packet_slab_scalar<PacketSlab>(rays, count, slabs, t_box);
    }
#if PT_WIDE_BVH_X86
    [[gnu::target("avx2")]] AvxPacketSlab prepare_packet_slab_avx(const Ray* rays, int count, SlabRay* slabs,
                                                                  float* t_box) const {
        AvxPacketRays prepared;
        if (!prepare_packet(rays, count, float_scene_, prepared))
            return prepare_packet_slab_scalar<AvxPacketSlab>(rays, count, slabs, t_box);
        _mm256_store_ps(t_box, prepared.t_box);
        return AvxPacketSlab(prepared);
    }
#endif
    template <class PacketSlab>
    PacketSlab prepare_packet_slab_scalar(const Ray* rays, int count, SlabRay* slabs, float* t_box) const {
        for (int k = 0; k < kPacketSize; ++k) {
            slabs[k] = SlabRay(rays[k < count ? k : 0], float_scene_);
            t_box[k] = box_t_max(rays[k < count ? k : 0].t_max);
        }
        return PacketSlab(slabs);
    }

    /// Any hit: the children hit are all kept, in lane order; stops at the
    /// first primitive hit.
    template <class Slab, bool Blocks = false>
    bool any_hit(const Ray& ray) const {
        const SlabRay slab = slab_ray<Slab>(ray);
        const Slab boxes(slab);
        const typename Tester::RayData query = tester_.prepare(ray);
        const float t_box = box_t_max(ray.t_max);
        uint64_t visited = 0, tests = 0;
        ChildRef stack[(W - 1) * kMaxBvhDepth + W];
        int size = 0;
        ChildRef current{0, 0};
        Hit hit;
        for (;;) {
            if (current.count == 0) {
                const Node& node = nodes_[current.index];
                alignas(32) float t_enter[W];
                unsigned mask = boxes.test(node, t_box, t_enter);
                visited += W;
                if (mask != 0) {
                    int first = __builtin_ctz(mask);
                    for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
                        int i = __builtin_ctz(mask);
                        stack[size++] = {node.child[i], node.count[i]};
                    }
                    current = {node.child[first], node.count[first]};
                    continue;
                }
            } else if (Blocks && (current.index & kBlockLeaf)) {
                if (current.index & kFloatLeaf ? block_leaf_any(float_blocks_, current, ray, tests)
                                               : block_leaf_any(blocks_, current, ray, tests)) {
                    add_counts(visited, tests);
                    return true;
                }
            } else {
                for (uint32_t slot = current.index, end = current.index + current.count; slot < end; ++slot) {
                    ++tests;
                    if (tester_.intersect(slot, ray, query, hit)) {
                        add_counts(visited, tests);
                        return true;
                    }
                }
            }
            if (size == 0) break;
            current = stack[--size];
        }
        add_counts(visited, tests);
        return false;
    }

    /// Whether one of a block leaf's triangles is hit (any hit), counting
    /// the triangles tested. Blocks: blocks_ or float_blocks_, as the
    /// leaf's kFloatLeaf bit says.
    template <class Blocks>
    static bool block_leaf_any(const Blocks& blocks, ChildRef leaf, const Ray& ray, uint64_t& tests) {
#if PT_WIDE_BVH_X86
        const uint32_t first = leaf.index & ~(kBlockLeaf | kFloatLeaf);
        for (uint32_t b = first; (b - first) * 4 < leaf.count; ++b) {
            alignas(32) double t[4], b1[4], b2[4];
            tests += std::min<uint32_t>(4, leaf.count - (b - first) * 4);
            if (intersect_block(blocks[b], ray.o, ray.d, ray.t_min, ray.t_max, t, b1, b2) != 0) return true;
        }
#else
        (void)blocks, (void)leaf, (void)ray, (void)tests;
#endif
        return false;
    }

    /// A block leaf's triangles four at a time against one ray; the lanes'
    /// hits are then taken in slot order with the slot-by-slot loop's rules
    /// (a lane beyond a t_max lowered by an earlier lane dropped, the larger
    /// id at equal t), so the answer is that loop's. Returns whether the
    /// closest hit changed (then r.t_max is its t). Only inlined into the
    /// AVX2 entry points (flatten).
    bool block_leaf_closest(ChildRef leaf, Ray& r, Hit& best, uint32_t& best_slot, uint32_t* best_lane,
                            bool& found) const {
        if (leaf.index & kFloatLeaf)
            return block_leaf_closest(float_blocks_, float_block_slot_, kFloatLane, leaf, r, best, best_slot,
                                      best_lane, found);
        return block_leaf_closest(blocks_, block_slot_, 0, leaf, r, best, best_slot, best_lane, found);
    }
    /// The same for one kind of block (`lane_tag`: kFloatLane or 0, set in best_lane).
    template <class Blocks>
    bool block_leaf_closest(const Blocks& blocks, const std::vector<uint32_t>& block_slot, uint32_t lane_tag,
                            ChildRef leaf, Ray& r, Hit& best, uint32_t& best_slot, uint32_t* best_lane,
                            bool& found) const {
        bool changed = false;
#if PT_WIDE_BVH_X86
        const uint32_t first = leaf.index & ~(kBlockLeaf | kFloatLeaf);
        for (uint32_t b = first; (b - first) * 4 < leaf.count; ++b) {
            alignas(32) double t[4], b1[4], b2[4];
            unsigned m = intersect_block(blocks[b], r.o, r.d, r.t_min, r.t_max, t, b1, b2);
            for (; m != 0; m &= m - 1) {
                const int lane = __builtin_ctz(m);
                if (!(t[lane] <= r.t_max)) continue;
                const uint32_t slot = block_slot[b] + uint32_t(lane);
                if (found && t[lane] == best.t && primitives_[slot] < primitives_[best_slot]) continue;
                best = Hit{};
                best.t = t[lane];
                best.b1 = b1[lane];
                best.b2 = b2[lane];
                best_slot = slot;
                if (best_lane) *best_lane = (b * 4 + uint32_t(lane)) | lane_tag;
                found = changed = true;
                r.t_max = t[lane];
            }
        }
#else
        (void)blocks, (void)block_slot, (void)lane_tag, (void)leaf, (void)r, (void)best, (void)best_slot,
            (void)best_lane, (void)found;
#endif
        return changed;
    }

    /// block_leaf_closest for each active ray of a packet (per ray the
    /// blocks in slot order, so the same answers), the blocks in the outer
    /// loop so that each is fetched once for the packet. Also notes the
    /// block and lane of each new closest hit in p.best_lane, from which
    /// finish_hit takes the triangle's edges. Returns the rays whose
    /// closest hit changed.
    uint32_t block_leaf_closest_packet(ChildRef leaf, uint32_t active, const Ray* rays, double* t_max,
                                       Packet& p) const {
        if (leaf.index & kFloatLeaf)
            return block_leaf_closest_packet(float_blocks_, float_block_slot_, kFloatLane, leaf, active, rays,
                                             t_max, p);
        return block_leaf_closest_packet(blocks_, block_slot_, 0, leaf, active, rays, t_max, p);
    }
    template <class Blocks>
    uint32_t block_leaf_closest_packet(const Blocks& blocks, const std::vector<uint32_t>& block_slot,
                                       uint32_t lane_tag, ChildRef leaf, uint32_t active, const Ray* rays,
                                       double* t_max, Packet& p) const {
        uint32_t changed = 0;
#if PT_WIDE_BVH_X86
        const uint32_t first = leaf.index & ~(kBlockLeaf | kFloatLeaf);
        for (uint32_t b = first; (b - first) * 4 < leaf.count; ++b) {
            const BlockLanes lanes = load_lanes(blocks[b]);  // a float block widened once for all rays
            for (uint32_t a = active; a != 0; a &= a - 1) {
                const int k = __builtin_ctz(a);
                alignas(32) double t[4], b1[4], b2[4];
                unsigned m = intersect_lanes(lanes, rays[k].o, rays[k].d, rays[k].t_min, t_max[k], t, b1, b2);
                for (; m != 0; m &= m - 1) {
                    const int lane = __builtin_ctz(m);
                    if (!(t[lane] <= t_max[k])) continue;
                    const uint32_t slot = block_slot[b] + uint32_t(lane);
                    if ((p.found >> k & 1) && t[lane] == p.best[k].t && primitives_[slot] < primitives_[p.best_slot[k]])
                        continue;
                    Hit& best = p.best[k];
                    best = Hit{};
                    best.t = t[lane];
                    best.b1 = b1[lane];
                    best.b2 = b2[lane];
                    p.best_slot[k] = slot;
                    p.best_lane[k] = (b * 4 + uint32_t(lane)) | lane_tag;
                    p.found |= 1u << k;
                    changed |= 1u << k;
                    t_max[k] = t[lane];
                }
            }
        }
#else
        (void)blocks, (void)block_slot, (void)lane_tag, (void)leaf, (void)active, (void)rays, (void)t_max, (void)p;
#endif
        return changed;
    }

    /// tester_.finish for a closest hit; for a hit found in a block
    /// (best_lane: 4 * block + lane), with the block's edges (the same bits
    /// as the tester's, bvh_leaf_block.h), so that the triangle is not
    /// fetched through the scene.
    void finish_hit(uint32_t slot, uint32_t best_lane, const Ray& ray, Hit& hit) const {
        if constexpr (kBlocks) {
            if (best_lane != kNoLane && (best_lane & kFloatLane)) {
                const FloatCornerBlock& block = float_blocks_[(best_lane & ~kFloatLane) / 4];
                const int l = int(best_lane % 4);
                const Vec3 p0 = block.corner(0, l);  // e1 = p1 - p0 in double, as the block test's
                tester_.finish_from_edges(slot, block.corner(1, l) - p0, block.corner(2, l) - p0, hit);
                return;
            }
            if (best_lane != kNoLane) {
                const TriangleBlock& block = blocks_[best_lane / 4];
                const int l = int(best_lane % 4);
                tester_.finish_from_edges(slot, Vec3(block.e1[0][l], block.e1[1][l], block.e1[2][l]),
                                          Vec3(block.e2[0][l], block.e2[1][l], block.e2[2][l]), hit);
                return;
            }
        }
        tester_.finish(slot, ray, hit);
    }

    /// The ray prepared for slab tests; the 8-wide AVX traversal's without
    /// branches (the same fields, bvh_wide_slab.h).
    template <class Slab>
    SlabRay slab_ray(const Ray& ray) const {
#if PT_WIDE_BVH_X86
        if constexpr (std::is_same_v<Slab, AvxWideSlab>) return make_slab_ray_avx(ray, float_scene_);
#endif
        return SlabRay(ray, float_scene_);
    }

    /// The tester; the Moller-Trumbore one told whether the leaf blocks will
    /// hold its triangles (then it keeps no per-slot copy of them).
    static Tester make_tester(const Scene& scene, const IntersectStage& stage, const std::vector<uint32_t>& order,
                              bool blocks, const std::vector<uint8_t>& generic_prims) {
        if constexpr (std::is_same_v<Tester, InlineMollerTrumbore>)
            return Tester(scene, stage, order, blocks, generic_prims.empty() ? nullptr : &generic_prims);
        else return Tester(scene, stage, order);
    }

    /// Whether the leaves will be stored as blocks (make_blocks).
    static bool uses_blocks(const FlatBvh& bvh, bool simd) {
        return kBlocks && simd && wide_bvh_has_avx() && !bvh.nodes.empty() && bvh.primitives.size() < kFloatLeaf;
    }

    /// The binary tree's slot order (bvh.primitives, moved out), with each
    /// leaf's generic slots (spheres, degenerate triangles; `generic`: per
    /// primitive, empty when the leaves are not blocks) moved to its end, so
    /// that make_blocks can split them off. The closest hit does not depend
    /// on the order of a leaf's slots (the smallest t, then the largest id,
    /// as the linear scan's).
    /// With blocks, chooses the wide nodes and leaves first (plan_wide_nodes).
    static std::vector<uint32_t> leaf_order(FlatBvh& bvh, const std::vector<uint8_t>& generic, bool blocks,
                                            WidePlan& plan) {
        if constexpr (W == 8)
            if (blocks) plan_wide_nodes(bvh, plan);
        if (std::find(generic.begin(), generic.end(), 1) != generic.end()) {
            // Last to first, so that a merged leaf is ordered after the
            // unreachable leaves inside it.
            for (size_t i = bvh.nodes.size(); i-- > 0;) {
                const FlatBvhNode& n = bvh.nodes[i];
                if (!n.is_leaf()) continue;
                auto first = bvh.primitives.begin() + n.offset;
                std::stable_partition(first, first + n.count, [&](uint32_t prim) { return generic[prim] == 0; });
            }
        }
        return std::move(bvh.primitives);
    }

    /// The first slot of a leaf from its child index (a block leaf's or not).
    uint32_t leaf_slot(uint32_t index) const {
        if (index & kFloatLeaf) return float_block_slot_[index & ~(kBlockLeaf | kFloatLeaf)];
        return (index & kBlockLeaf) ? block_slot_[index & ~kBlockLeaf] : index;
    }

    /// Stores the inline triangles of every leaf as TriangleBlocks of four
    /// and marks the leaf's child index with kBlockLeaf; only the AVX2
    /// traversal reads them (the packet traversal maps them back to slots
    /// with leaf_slot). A leaf's generic slots, last in it (leaf_order),
    /// become a leaf of their own with the same box, tested slot by slot
    /// through the stage's routines: in a free lane of the node, or else
    /// both parts go to a new node of two lanes in the leaf's place. So the
    /// tester keeps no per-slot copy of the triangles (the ogre's 4
    /// degenerate ones cost 72 bytes for each of its 124,008), and the
    /// traversal loops are not touched: a test of the generic slots after
    /// a block leaf's, tried first, made every mesh's rays 2 to 10% slower.
    /// A leaf whose corners are all exactly floats (an OBJ mesh as loaded)
    /// gets FloatCornerBlocks, half the bytes, and kFloatLeaf; others
    /// TriangleBlocks. Both give the same bits (bvh_leaf_block.h).
    void make_blocks(const Scene& scene) {
        size_t count = 0;  // an upper bound on the blocks, so that they are written once
        for (const Node& node : nodes_)
            for (int i = 0; i < W; ++i)
                count += (node.count[i] + 3u) / 4u;
        // All the scene's points floats: every leaf is a float leaf, no check
        // per leaf (a sequential pass; the leaves' corners are scattered).
        const bool all_float = std::all_of(scene.positions.begin(), scene.positions.end(),
                                           [](const Vec3& v) { return FloatCornerBlock::exact(v); });
        if (all_float) {
            float_blocks_.reserve(count);
            float_block_slot_.reserve(count);
        } else {
            blocks_.reserve(count);
            block_slot_.reserve(count);
        }
        std::vector<Node> added;  // the new two-lane nodes, appended after the loop
        for (size_t index = 0; index < nodes_.size(); ++index) {
            Node& node = nodes_[index];
            for (int i = 0; i < W; ++i) {
                const uint32_t first = node.child[i];
                uint32_t n = node.count[i];
                if (n == 0) continue;
                uint32_t inline_count = 0;
                while (inline_count < n && tester_.is_inline(first + inline_count))
                    ++inline_count;
                if (inline_count == 0) continue;  // only generic slots: a leaf of slots as it is
                if (inline_count < n) {
                    const uint32_t generic_count = n - inline_count;
                    n = inline_count;
                    const unsigned free_lanes = ~unsigned(node.valid) & ((1u << W) - 1);
                    Node* block_node = &node;
                    int block_lane = i, generic_lane = free_lanes ? __builtin_ctz(free_lanes) : -1;
                    if (generic_lane < 0) {  // no free lane: a new node for both parts
                        Node& two = added.emplace_back();
                        for (int p = 0; p < 6; ++p)
                            for (int l = 0; l < W; ++l)
                                two.bounds[p][l] = l < 2 ? node.bounds[p][i] : (p < 3 ? INFINITY : -INFINITY);
                        two.valid = 3;
                        node.child[i] = uint32_t(nodes_.size() + added.size() - 1);
                        node.count[i] = 0;
                        block_node = &two;
                        block_lane = 0;
                        generic_lane = 1;
                    } else {
                        for (int p = 0; p < 6; ++p)
                            block_node->bounds[p][generic_lane] = node.bounds[p][i];
                        block_node->valid |= uint8_t(1u << generic_lane);
                    }
                    block_node->child[generic_lane] = first + n;
                    block_node->count[generic_lane] = uint8_t(generic_count);
                    block_node->count[block_lane] = uint8_t(n);
                    block_node->child[block_lane] = add_blocks(first, n, all_float);
                } else {
                    node.child[i] = add_blocks(first, n, all_float);
                }
            }
        }
        nodes_.insert(nodes_.end(), added.begin(), added.end());
    }

    /// Stores slots first .. first + n - 1 (inline triangles) as blocks of
    /// four, float ones when every corner is a float (`all_float`: known so);
    /// returns the leaf's child index.
    uint32_t add_blocks(uint32_t first, uint32_t n, bool all_float) {
        bool floats = true;
        for (uint32_t k = 0; k < n && floats && !all_float; ++k) {
            Vec3 p0, p1, p2;
            tester_.corners(first + k, p0, p1, p2);
            floats = FloatCornerBlock::exact(p0) && FloatCornerBlock::exact(p1) && FloatCornerBlock::exact(p2);
        }
        if (floats)
            return append_blocks(float_blocks_, float_block_slot_, kBlockLeaf | kFloatLeaf, first, n,
                                 [&](FloatCornerBlock& block, int lane, uint32_t slot) {
                                     Vec3 p0, p1, p2;
                                     tester_.corners(slot, p0, p1, p2);
                                     block.set(lane, p0, p1, p2);
                                 });
        return append_blocks(blocks_, block_slot_, kBlockLeaf, first, n,
                             [&](TriangleBlock& block, int lane, uint32_t slot) {
                                 Vec3 p0, e1, e2;
                                 tester_.stored(slot, p0, e1, e2);
                                 block.set(lane, p0, e1, e2);
                             });
    }

    /// Appends blocks of four for slots first .. first + n - 1 to `blocks`
    /// (`set_lane(block, lane, slot)` fills a lane) and their first slots to
    /// `block_slot`; returns the leaf's child index (the first block | `tag`).
    template <class Blocks, class SetLane>
    static uint32_t append_blocks(Blocks& blocks, std::vector<uint32_t>& block_slot, uint32_t tag, uint32_t first,
                                  uint32_t n, SetLane set_lane) {
        const uint32_t index = uint32_t(blocks.size()) | tag;
        for (uint32_t k = 0; k < n; k += 4) {
            auto& block = blocks.emplace_back();
            for (uint32_t l = 0; l < 4 && k + l < n; ++l) set_lane(block, int(l), first + k + l);
            block_slot.push_back(first + k);
        }
        return index;
    }

    static void add_counts(uint64_t visited, uint64_t tests) {
        RayCounters& c = thread_counters();
        c.nodes_visited += visited;
        c.primitive_tests += tests;
    }

    WidePlan plan_;  ///< during construction: the wide nodes' lanes (plan_wide_nodes)
    std::vector<uint8_t> generic_prims_;  ///< during construction: generic_primitives, when blocks are made
    std::vector<uint32_t> primitives_;  ///< slot -> primitive id (FlatBvh::primitives)
    Tester tester_;                     ///< holds a reference to primitives_: declared after it
    std::vector<Node, HugePageAllocator<Node>> nodes_;
    /// Leaves of inline triangles four at a time, for the 8-wide AVX2
    /// traversal (Moller-Trumbore only); block_slot_: the slot of each block's lane 0.
    static constexpr bool kBlocks = W == 8 && PT_WIDE_BVH_X86 && std::is_same_v<Tester, InlineMollerTrumbore>;
    std::vector<TriangleBlock, HugePageAllocator<TriangleBlock>> blocks_;
    std::vector<uint32_t> block_slot_;
    /// Leaves whose corners are all floats, stored so (kFloatLeaf; 144 bytes
    /// a block instead of 288); float_block_slot_ as block_slot_.
    std::vector<FloatCornerBlock, HugePageAllocator<FloatCornerBlock>> float_blocks_;
    std::vector<uint32_t> float_block_slot_;
    BvhSplit split_;
    bool simd_;  ///< use the SIMD box test (else the scalar loop; same answers)
    int depth_ = 0;
    bool float_scene_ = true;  ///< all coordinates within 1e30 (SlabRay)
};

template <int W>
std::unique_ptr<Accelerator> make_wide(const Scene& scene, const IntersectStage& stage, FlatBvh bvh, bool simd) {
    if (stage.intersect_triangle == &reference::intersect_triangle)
        return std::make_unique<WideReferenceBvh<InlineMollerTrumbore, W>>(scene, stage, std::move(bvh), simd);
    if (stage.intersect_triangle == &reference::intersect_triangle_watertight)
        return std::make_unique<WideReferenceBvh<InlineWatertight, W>>(scene, stage, std::move(bvh), simd);
    return std::make_unique<WideReferenceBvh<StageRoutines, W>>(scene, stage, std::move(bvh), simd);
}

}  // namespace

bool wide_bvh_has_avx() {
#if PT_WIDE_BVH_X86
    // Checks the processor and that the operating system saves AVX registers.
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return has;
#else
    return false;
#endif
}

std::unique_ptr<Accelerator> make_wide_bvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh, int width,
                                           bool simd) {
    if (width == 8) return make_wide<8>(scene, stage, std::move(bvh), simd);
    return make_wide<4>(scene, stage, std::move(bvh), simd);
}

}  // namespace pt
