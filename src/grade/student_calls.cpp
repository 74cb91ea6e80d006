#include "grade/student_calls.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <type_traits>
#include <unordered_map>

#include "core/error.h"
#include "grade/performance_checks.h"

namespace pt {
namespace {

// ---- the log: little-endian host bytes, one record per outermost call ----

enum Tag : uint8_t {
    kThrewNotImplemented = 200,  ///< u32 part, string message
    kThrew = 201,                ///< string message
    kImage = 202,                ///< u32 width, u32 height, floats, u32 sample counts
    kTiming = 204,               ///< u64 answered rays, each: bool hit, f64 t, u32 primitive if hit
    kEnd = 255,
};

constexpr size_t kMaxString = 64 * 1024;

CallMode g_mode = CallMode::direct;
Stages g_inner;                       // the student functions the recorders run
std::string g_log;                    // record mode: what is written so far
std::mutex g_log_mutex;               // renders call student code from many threads
std::atomic<int> g_paused{0};         // renders and timings: log nothing
thread_local int g_depth = 0;         // > 0: inside a logged (or stand-in) call
std::string g_replay;                 // replay mode: the log
size_t g_at = 0;                      // replay mode: the read position
double g_runner_cpu = NAN;            // replay mode: the runner's CPU seconds

struct Depth {
    Depth() { ++g_depth; }
    ~Depth() { --g_depth; }
};
struct Pause {
    Pause() { ++g_paused; }
    ~Pause() { --g_paused; }
};

bool logging() { return g_mode == CallMode::record && g_depth == 0 && g_paused == 0; }

// Writing (record mode; the caller holds g_log_mutex).
void put_bytes(const void* p, size_t n) { g_log.append(static_cast<const char*>(p), n); }
void put(uint8_t v) { put_bytes(&v, 1); }
void put(uint32_t v) { put_bytes(&v, 4); }
void put(uint64_t v) { put_bytes(&v, 8); }
void put(int v) { put(uint32_t(v)); }
void put(double v) { put_bytes(&v, 8); }
void put(bool v) { put(uint8_t(v ? 1 : 0)); }
void put(const std::string& s) {
    std::string t = s.substr(0, kMaxString);
    put(uint32_t(t.size()));
    put_bytes(t.data(), t.size());
}
void put(const Vec2& v) { put(v.x), put(v.y); }
void put(const Vec3& v) { put(v.x), put(v.y), put(v.z); }
void put(const Color& c) { put(c.r), put(c.g), put(c.b); }
void put(const Ray& r) { put(r.o), put(r.d), put(r.t_min), put(r.t_max), put(r.depth); }
void put(const std::optional<Hit>& h) {
    put(h.has_value());
    if (h) put(h->t), put(h->n), put(h->b1), put(h->b2), put(h->primitive);
}
void put(const BSDFSample& s) { put(s.wi), put(s.f), put(s.pdf), put(s.is_delta), put(s.eta); }
void put(const PixelResult& p) { put(p.radiance), put(p.samples); }
void put(const DistanceSample& d) { put(d.t), put(d.pdf), put(d.scattered); }
void put(const EmittedPhoton& e) { put(e.ray), put(e.flux), put(e.valid); }
void put(const PathVertex& v) {
    put(uint8_t(v.kind)), put(v.p), put(v.ng), put(v.ns), put(v.w), put(v.beta), put(v.pdf_fwd), put(v.pdf_rev),
        put(v.delta);
}
void put(const Connection& c) {
    put(c.L), put(c.camera_vertex.has_value());
    if (c.camera_vertex) put(*c.camera_vertex);
    put(c.film);
}
void put(const KdTree& t) {
    put(uint64_t(t.points.size())), put(uint64_t(t.ids.size())), put(uint64_t(t.axis.size()));
    put_bytes(t.points.data(), t.points.size() * sizeof(Vec3));
    put_bytes(t.ids.data(), t.ids.size() * sizeof(uint32_t));
    put_bytes(t.axis.data(), t.axis.size());
}

// Reading (replay mode): every read is bounds-checked.
[[noreturn]] void bad(const std::string& what) {
    throw RunnerOutputError("the runner's output is not valid (" + what +
                            "); it must come from the student code");
}
void get_bytes(void* p, size_t n) {
    if (n > g_replay.size() - g_at) bad("it ends early");
    std::memcpy(p, g_replay.data() + g_at, n);
    g_at += n;
}
template <class T>
T get_raw() {
    T v;
    get_bytes(&v, sizeof v);
    return v;
}
void get(uint32_t& v) { v = get_raw<uint32_t>(); }
void get(uint64_t& v) { v = get_raw<uint64_t>(); }
void get(int& v) { v = int(get_raw<uint32_t>()); }
void get(double& v) { v = get_raw<double>(); }
void get(bool& v) {
    uint8_t b = get_raw<uint8_t>();
    if (b > 1) bad("a boolean is neither 0 nor 1");
    v = b == 1;
}
void get(std::string& s) {
    uint32_t n = get_raw<uint32_t>();
    if (n > kMaxString) bad("a message is longer than 64 KiB");
    s.resize(n);
    get_bytes(s.data(), n);
}
void get(Vec2& v) { get(v.x), get(v.y); }
void get(Vec3& v) { get(v.x), get(v.y), get(v.z); }
void get(Color& c) { get(c.r), get(c.g), get(c.b); }
void get(Ray& r) { get(r.o), get(r.d), get(r.t_min), get(r.t_max), get(r.depth); }
void get(std::optional<Hit>& h) {
    bool has = false;
    get(has);
    h.reset();
    if (!has) return;
    Hit x;
    get(x.t), get(x.n), get(x.b1), get(x.b2), get(x.primitive);
    h = x;
}
void get(BSDFSample& s) { get(s.wi), get(s.f), get(s.pdf), get(s.is_delta), get(s.eta); }
void get(PixelResult& p) { get(p.radiance), get(p.samples); }
void get(DistanceSample& d) { get(d.t), get(d.pdf), get(d.scattered); }
void get(EmittedPhoton& e) { get(e.ray), get(e.flux), get(e.valid); }
// A vertex as the log has it: what a check reads of it (no hit record, no
// BSDF: the grader finds those itself from the positions).
void get(PathVertex& v) {
    const uint8_t kind = get_raw<uint8_t>();
    if (kind > uint8_t(VertexKind::escaped)) bad("a path vertex of no known kind");
    v.kind = VertexKind(kind);
    get(v.p), get(v.ng), get(v.ns), get(v.w), get(v.beta), get(v.pdf_fwd), get(v.pdf_rev), get(v.delta);
}
void get(Connection& c) {
    get(c.L);
    bool has = false;
    get(has);
    c.camera_vertex.reset();
    if (has) {
        PathVertex z0;
        get(z0);
        c.camera_vertex = z0;
    }
    get(c.film);
}
// A kd-tree of at most 2^24 points (the checks build far smaller ones);
// kdtree_is_valid judges the rest, sizes included.
constexpr uint64_t kMaxTreePoints = uint64_t(1) << 24;
void get(KdTree& t) {
    uint64_t n = 0, ni = 0, na = 0;
    get(n), get(ni), get(na);
    if (n > kMaxTreePoints || ni > kMaxTreePoints || na > kMaxTreePoints)
        bad("a kd-tree of more than 2^24 points");
    t.points.resize(size_t(n)), t.ids.resize(size_t(ni)), t.axis.resize(size_t(na));
    get_bytes(t.points.data(), t.points.size() * sizeof(Vec3));
    get_bytes(t.ids.data(), t.ids.size() * sizeof(uint32_t));
    get_bytes(t.axis.data(), t.axis.size());
}

/// Logs the exception being handled (call inside a catch block).
void log_exception() {
    std::lock_guard<std::mutex> lock(g_log_mutex);
    try {
        throw;
    } catch (const NotImplemented& e) {
        put(uint8_t(kThrewNotImplemented)), put(uint32_t(e.part())), put(std::string(e.what()));
    } catch (const std::exception& e) {
        put(uint8_t(kThrew)), put(std::string(e.what()));
    } catch (...) {
        put(uint8_t(kThrew)), put(std::string("an exception that is not a std::exception"));
    }
}

/// NotImplemented rebuilt from its message "Part N, task T: F is not implemented yet".
[[noreturn]] void throw_not_implemented(int part, const std::string& message) {
    const std::string task_key = ", task ", tail = " is not implemented yet";
    size_t t = message.find(task_key), colon = message.find(": ", t == std::string::npos ? 0 : t);
    if (t == std::string::npos || colon == std::string::npos || message.size() < tail.size() ||
        message.compare(message.size() - tail.size(), tail.size(), tail) != 0 ||
        colon + 2 > message.size() - tail.size())
        throw NotImplemented(part, "?", printable(message));
    throw NotImplemented(part, printable(message.substr(t + task_key.size(), colon - t - 7)),
                         printable(message.substr(colon + 2, message.size() - tail.size() -
                                                                 colon - 2)));
}

/// Reads the next record's tag in replay mode: rethrows a logged
/// exception; otherwise it must be `expected`.
void begin_record(uint8_t expected, const char* what) {
    uint8_t tag = get_raw<uint8_t>();
    if (tag == kThrewNotImplemented) {
        uint32_t part = 0;
        std::string message;
        get(part), get(message);
        throw_not_implemented(int(std::min<uint32_t>(part, 99)), message);
    }
    if (tag == kThrew) {
        std::string message;
        get(message);
        throw std::runtime_error(printable(message));
    }
    if (tag != expected) bad(std::string("expected the output of ") + what);
}

// ---- one wrapper per student function ----

template <int Id, auto Get, class Fn>
struct Slot;
template <int Id, auto Get, class R, class... A>
struct Slot<Id, Get, R (*)(A...)> {
    static R call(A... a) { return Get(g_inner)(a...); }
    static R record(A... a) {
        if (!logging()) {
            Depth d;
            return call(a...);
        }
        Depth d;
        R r{};
        try {
            r = call(a...);
        } catch (...) {
            log_exception();
            throw;
        }
        std::lock_guard<std::mutex> lock(g_log_mutex);
        put(uint8_t(Id));
        put(r);
        return r;
    }
    // In the runner's reference table for a withheld function: never
    // logged, and it never throws, so that the check goes on to the logged
    // call of the student function, as it does in the grader.
    static R stand_in(A... a) {
        Depth d;
        try {
            return call(a...);
        } catch (...) {
            return R{};
        }
    }
    static R replay(A...) {
        begin_record(Id, "a student function");
        R r{};
        get(r);
        return r;
    }
};

// bbox_intersect also returns t0 and t1 through its arguments.
constexpr int kBboxId = 6;
bool record_bbox(const BBox& box, const Ray& ray, double& t0, double& t1) {
    Depth d;
    if (g_depth > 1 || g_mode != CallMode::record || g_paused != 0)
        return g_inner.bvh.tree.bbox_intersect(box, ray, t0, t1);
    bool hit = false;
    try {
        hit = g_inner.bvh.tree.bbox_intersect(box, ray, t0, t1);
    } catch (...) {
        log_exception();
        throw;
    }
    std::lock_guard<std::mutex> lock(g_log_mutex);
    put(uint8_t(kBboxId)), put(hit), put(t0), put(t1);
    return hit;
}
bool stand_in_bbox(const BBox& box, const Ray& ray, double& t0, double& t1) {
    Depth d;
    try {
        return g_inner.bvh.tree.bbox_intersect(box, ray, t0, t1);
    } catch (...) {
        return false;
    }
}
bool replay_bbox(const BBox&, const Ray&, double& t0, double& t1) {
    begin_record(kBboxId, "bbox_intersect");
    bool hit = false;
    get(hit), get(t0), get(t1);
    return hit;
}

// k_nearest returns its neighbours through `out`: the log holds their count
// (at most the tree's size, or the bound below) and each id and distance.
constexpr int kKNearestId = 26;
constexpr uint64_t kMaxNeighbors = uint64_t(1) << 24;
void record_k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2,
                      std::vector<Neighbor>& out) {
    Depth d;
    if (g_depth > 1 || g_mode != CallMode::record || g_paused != 0)
        return g_inner.photon.k_nearest(tree, p, k, max_dist2, out);
    try {
        g_inner.photon.k_nearest(tree, p, k, max_dist2, out);
    } catch (...) {
        log_exception();
        throw;
    }
    std::lock_guard<std::mutex> lock(g_log_mutex);
    put(uint8_t(kKNearestId));
    const uint64_t n = std::min<uint64_t>(out.size(), kMaxNeighbors);
    put(n);
    for (uint64_t i = 0; i < n; ++i)
        put(uint32_t(out[i].id)), put(out[i].dist2);
}
void stand_in_k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2,
                        std::vector<Neighbor>& out) {
    Depth d;
    try {
        g_inner.photon.k_nearest(tree, p, k, max_dist2, out);
    } catch (...) {
        out.clear();
    }
}
void replay_k_nearest(const KdTree& tree, const Vec3&, int, double, std::vector<Neighbor>& out) {
    begin_record(kKNearestId, "k_nearest");
    uint64_t n = 0;
    get(n);
    if (n > std::max<uint64_t>(tree.size(), 1024) || n > kMaxNeighbors)
        bad("k_nearest returned more neighbours than the tree has points");
    out.resize(size_t(n));
    for (Neighbor& x : out) {
        uint32_t id = 0;
        get(id), get(x.dist2);
        x.id = id;
    }
}

// random_walk appends to `path` (and sets pdf_rev of the vertex it starts
// from): the log holds the count it returned and the whole path after the
// call, at most max_vertices + 1 longer than before.
constexpr int kRandomWalkId = 32;
int record_random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                       int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path) {
    Depth d;
    if (g_depth > 1 || g_mode != CallMode::record || g_paused != 0)
        return g_inner.bdpt.random_walk(context, ray, beta, pdf_dir, max_vertices, mode, rng, path);
    int added = 0;
    try {
        added = g_inner.bdpt.random_walk(context, ray, beta, pdf_dir, max_vertices, mode, rng, path);
    } catch (...) {
        log_exception();
        throw;
    }
    std::lock_guard<std::mutex> lock(g_log_mutex);
    put(uint8_t(kRandomWalkId)), put(added), put(uint64_t(path.size()));
    for (const PathVertex& v : path)
        put(v);
    return added;
}
int stand_in_random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                         int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path) {
    Depth d;
    try {
        return g_inner.bdpt.random_walk(context, ray, beta, pdf_dir, max_vertices, mode, rng, path);
    } catch (...) {
        return 0;
    }
}
int replay_random_walk(const RenderContext&, const Ray&, const Color&, double, int max_vertices, Transport,
                       Rng&, std::vector<PathVertex>& path) {
    begin_record(kRandomWalkId, "random_walk");
    int added = 0;
    uint64_t n = 0;
    get(added), get(n);
    if (n > path.size() + uint64_t(std::max(max_vertices, 0)) + 1 || n > kMaxNeighbors)
        bad("random_walk made a longer path than max_vertices allows");
    // Vertices the caller made keep their hit and BSDF; their figures are the log's.
    const size_t before = path.size();
    path.resize(size_t(n));
    for (size_t i = 0; i < path.size(); ++i) {
        PathVertex v;
        get(v);
        if (i < before) {
            PathVertex& kept = path[i];
            kept.kind = v.kind, kept.p = v.p, kept.ng = v.ng, kept.ns = v.ns, kept.w = v.w;
            kept.beta = v.beta, kept.pdf_fwd = v.pdf_fwd, kept.pdf_rev = v.pdf_rev, kept.delta = v.delta;
        } else {
            path[i] = v;
        }
    }
    return added;
}

// construct_bvh reorders primitives[start, end) and returns a tree: the log
// holds the new order as positions in the old one, and the tree in
// preorder (1, box, start, end, left, right; 0 for no node).
constexpr int kConstructId = 5;
constexpr uint64_t kNotGiven = ~uint64_t(0);

bool same_primitive(const BVHPrimitive& a, const BVHPrimitive& b) {
    return a.id == b.id && a.bb.min == b.bb.min && a.bb.max == b.bb.max &&
           a.centroid == b.centroid;
}

void put_tree(const BVHNode* root) {
    std::vector<const BVHNode*> stack{root};
    while (!stack.empty()) {
        const BVHNode* n = stack.back();
        stack.pop_back();
        put(n != nullptr);
        if (!n) continue;
        put(n->bb.min), put(n->bb.max), put(uint64_t(n->start)), put(uint64_t(n->end));
        stack.push_back(n->r.get());
        stack.push_back(n->l.get());
    }
}

std::unique_ptr<BVHNode> get_tree(size_t max_nodes) {
    std::unique_ptr<BVHNode> root;
    std::vector<std::unique_ptr<BVHNode>*> stack{&root};
    size_t nodes = 0;
    while (!stack.empty()) {
        std::unique_ptr<BVHNode>* slot = stack.back();
        stack.pop_back();
        bool present = false;
        get(present);
        if (!present) continue;
        if (++nodes > max_nodes) bad("the tree has more than " + std::to_string(max_nodes) + " nodes");
        auto n = std::make_unique<BVHNode>();
        uint64_t start = 0, end = 0;
        get(n->bb.min), get(n->bb.max), get(start), get(end);
        n->start = size_t(start);
        n->end = size_t(end);
        *slot = std::move(n);
        stack.push_back(&(*slot)->r);
        stack.push_back(&(*slot)->l);
    }
    return root;
}

std::unique_ptr<BVHNode> record_construct(std::vector<BVHPrimitive>& p, size_t start, size_t end,
                                          size_t max_leaf) {
    Depth d;
    if (g_depth > 1 || g_mode != CallMode::record || g_paused != 0)
        return g_inner.bvh.tree.construct_bvh(p, start, end, max_leaf);
    const bool range = start <= end && end <= p.size();
    std::vector<BVHPrimitive> before;
    if (range) before.assign(p.begin() + long(start), p.begin() + long(end));
    std::unique_ptr<BVHNode> root;
    try {
        root = g_inner.bvh.tree.construct_bvh(p, start, end, max_leaf);
    } catch (...) {
        log_exception();
        throw;
    }
    std::lock_guard<std::mutex> lock(g_log_mutex);
    put(uint8_t(kConstructId));
    put(uint64_t(before.size()));
    std::unordered_multimap<uint32_t, size_t> where;
    for (size_t i = 0; i < before.size(); ++i)
        where.emplace(before[i].id, i);
    std::vector<bool> used(before.size(), false);
    for (size_t i = 0; i < before.size(); ++i) {
        uint64_t from = kNotGiven;
        if (range && start + before.size() <= p.size()) {
            const BVHPrimitive& now = p[start + i];
            auto [lo, hi] = where.equal_range(now.id);
            for (auto it = lo; it != hi && from == kNotGiven; ++it)
                if (!used[it->second] && same_primitive(before[it->second], now)) from = it->second;
        }
        if (from != kNotGiven) used[from] = true;
        put(from);
    }
    put_tree(root.get());
    return root;
}
std::unique_ptr<BVHNode> stand_in_construct(std::vector<BVHPrimitive>& p, size_t start, size_t end,
                                            size_t max_leaf) {
    Depth d;
    try {
        return g_inner.bvh.tree.construct_bvh(p, start, end, max_leaf);
    } catch (...) {
        return nullptr;
    }
}
std::unique_ptr<BVHNode> replay_construct(std::vector<BVHPrimitive>& p, size_t start, size_t end,
                                          size_t) {
    begin_record(kConstructId, "construct_bvh");
    uint64_t n = 0;
    get(n);
    const bool range = start <= end && end <= p.size();
    if (n != (range ? end - start : 0)) bad("construct_bvh's primitive count");
    std::vector<BVHPrimitive> before;
    if (n > 0) before.assign(p.begin() + long(start), p.begin() + long(start + n));
    std::vector<bool> used(n, false);
    for (uint64_t i = 0; i < n; ++i) {
        uint64_t from = 0;
        get(from);
        if (from == kNotGiven)
            throw std::runtime_error("construct_bvh changed or replaced a primitive it was given");
        if (from >= n || used[from]) bad("construct_bvh's order of the primitives");
        used[from] = true;
        p[start + i] = before[from];
    }
    return get_tree(16 * n + 1024);
}

// The table of slots: stage_mix's names, and how to set each variant.
using Setter = void (*)(Stages& s, int variant);  // 0 record, 1 replay, 2 stand-in

template <class SlotT, class Fn>
void assign(Fn& f, int variant) {
    f = variant == 0 ? SlotT::record : variant == 1 ? SlotT::replay : SlotT::stand_in;
}

#define PT_ACCESS(NAME, PATH) \
    auto& NAME(Stages& s) { return s.PATH; }
PT_ACCESS(generate_ray, camera.generate_ray)
PT_ACCESS(raytrace_pixel, camera.raytrace_pixel)
PT_ACCESS(intersect_triangle, intersect.intersect_triangle)
PT_ACCESS(intersect_sphere, intersect.intersect_sphere)
PT_ACCESS(bvh_intersect, bvh.tree.bvh_intersect)
PT_ACCESS(bvh_has_intersection, bvh.tree.bvh_has_intersection)
PT_ACCESS(grid_intersect, bvh.grid_intersect)
PT_ACCESS(has_converged, adaptive.has_converged)
PT_ACCESS(diffuse_f, direct.diffuse_f)
PT_ACCESS(diffuse_sample_f, direct.diffuse_sample_f)
PT_ACCESS(zero_bounce_radiance, direct.zero_bounce_radiance)
PT_ACCESS(estimate_direct_lighting_hemisphere, direct.estimate_direct_lighting_hemisphere)
PT_ACCESS(estimate_direct_lighting_importance, direct.estimate_direct_lighting_importance)
PT_ACCESS(one_bounce_radiance, direct.one_bounce_radiance)
PT_ACCESS(at_least_one_bounce_radiance, global.at_least_one_bounce_radiance)
PT_ACCESS(est_radiance_global_illumination, global.est_radiance_global_illumination)
PT_ACCESS(power_heuristic, direct.power_heuristic)
PT_ACCESS(balance_heuristic, direct.balance_heuristic)
PT_ACCESS(estimate_direct_lighting_mis, direct.estimate_direct_lighting_mis)
PT_ACCESS(stratified_sample_2d, sampler.stratified_sample_2d)
PT_ACCESS(scrambled_radical_inverse, sampler.scrambled_radical_inverse)
PT_ACCESS(emit_photon, photon.emit_photon)
PT_ACCESS(build_kdtree, photon.build_kdtree)
PT_ACCESS(density_estimate, photon.density_estimate)
PT_ACCESS(homogeneous_transmittance, media.homogeneous_transmittance)
PT_ACCESS(sample_distance, media.sample_distance)
PT_ACCESS(hg_phase, media.hg_phase)
PT_ACCESS(sample_hg, media.sample_hg)
PT_ACCESS(in_scattered_radiance, media.in_scattered_radiance)
PT_ACCESS(connect, bdpt.connect)
PT_ACCESS(mis_weight, bdpt.mis_weight)
#undef PT_ACCESS

// The slots by stage_mix's names; the ids are the log's tags.
#define PT_SLOT(ID, STAGE, FN)                                                      \
    {                                                                               \
        #STAGE "." #FN, [](Stages& s, int v) {                                      \
            using F = std::remove_reference_t<decltype(FN(s))>;                     \
            assign<Slot<ID, FN, F>>(FN(s), v);                                      \
        }                                                                           \
    }

using Setter = void (*)(Stages& s, int variant);  // 0 record, 1 replay, 2 stand-in
struct SlotEntry {
    const char* name;
    Setter set;
};

const SlotEntry kSlots[] = {
    PT_SLOT(1, camera, generate_ray),
    PT_SLOT(2, camera, raytrace_pixel),
    PT_SLOT(3, intersect, intersect_triangle),
    PT_SLOT(4, intersect, intersect_sphere),
    {"bvh.construct_bvh",
     [](Stages& s, int v) {
         s.bvh.tree.construct_bvh = v == 0 ? record_construct : v == 1 ? replay_construct
                                                                         : stand_in_construct;
     }},
    {"bvh.bbox_intersect",
     [](Stages& s, int v) {
         s.bvh.tree.bbox_intersect = v == 0 ? record_bbox : v == 1 ? replay_bbox : stand_in_bbox;
     }},
    PT_SLOT(7, bvh, bvh_intersect),
    PT_SLOT(8, bvh, bvh_has_intersection),
    PT_SLOT(9, adaptive, has_converged),
    PT_SLOT(10, direct, diffuse_f),
    PT_SLOT(11, direct, diffuse_sample_f),
    PT_SLOT(12, direct, zero_bounce_radiance),
    PT_SLOT(13, direct, estimate_direct_lighting_hemisphere),
    PT_SLOT(14, direct, estimate_direct_lighting_importance),
    PT_SLOT(15, direct, one_bounce_radiance),
    PT_SLOT(16, global, at_least_one_bounce_radiance),
    PT_SLOT(17, global, est_radiance_global_illumination),
    PT_SLOT(18, sampler, stratified_sample_2d),
    PT_SLOT(19, sampler, scrambled_radical_inverse),
    PT_SLOT(20, direct, power_heuristic),
    PT_SLOT(21, direct, balance_heuristic),
    PT_SLOT(22, direct, estimate_direct_lighting_mis),
    PT_SLOT(23, photon, emit_photon),
    PT_SLOT(24, photon, build_kdtree),
    PT_SLOT(25, photon, density_estimate),
    {"photon.k_nearest",
     [](Stages& s, int v) {
         s.photon.k_nearest = v == 0 ? record_k_nearest : v == 1 ? replay_k_nearest
                                                                  : stand_in_k_nearest;
     }},
    PT_SLOT(27, media, homogeneous_transmittance),
    PT_SLOT(28, media, sample_distance),
    PT_SLOT(29, media, hg_phase),
    PT_SLOT(30, media, sample_hg),
    PT_SLOT(31, media, in_scattered_radiance),
    {"bdpt.random_walk",
     [](Stages& s, int v) {
         s.bdpt.random_walk = v == 0 ? record_random_walk : v == 1 ? replay_random_walk : stand_in_random_walk;
     }},
    PT_SLOT(33, bdpt, connect),
    PT_SLOT(34, bdpt, mis_weight),
    PT_SLOT(35, bvh, grid_intersect),
};

#undef PT_SLOT

[[noreturn]] std::unique_ptr<Accelerator> no_build(const Scene&, const IntersectStage&,
                                                   const AcceleratorSettings&) {
    throw RunnerOutputError("the grader cannot build the student's BVH itself");
}

}  // namespace

CallMode call_mode() { return g_mode; }

Stages start_recording(const Stages& student) {
    g_inner = student;
    g_mode = CallMode::record;
    g_log.clear();
    Stages s = student;
    for (const SlotEntry& e : kSlots)
        e.set(s, 0);
    return s;
}

std::string finish_recording() {
    std::lock_guard<std::mutex> lock(g_log_mutex);
    put(uint8_t(kEnd));
    std::string log;
    log.swap(g_log);
    g_mode = CallMode::direct;
    return log;
}

Stages stand_in_reference(const Stages& reference, const std::vector<std::string>& withheld) {
    Stages s = reference;
    for (const SlotEntry& e : kSlots)
        for (const std::string& w : withheld)
            if (w == e.name || w + "." == std::string(e.name).substr(0, w.size() + 1))
                e.set(s, 2);
    return s;
}

Stages start_replay(std::string log) {
    if (log.empty() || uint8_t(log.back()) != kEnd) bad("it has no end marker");
    log.pop_back();
    g_replay = std::move(log);
    g_at = 0;
    g_mode = CallMode::replay;
    Stages s = make_stages(StageSet::none());
    s.student = StageSet::all();
    for (const SlotEntry& e : kSlots)
        e.set(s, 1);
    s.bvh.build = no_build;
    return s;
}

void stop_replay() {
    g_mode = CallMode::direct;
    g_runner_cpu = NAN;
    g_replay.clear();
    g_at = 0;
}

RenderResult student_render(const Scene& scene, const ImageCase& c, const Stages& stages, int spp,
                            uint64_t seed, int threads) {
    if (g_mode == CallMode::direct) return render_case(scene, c, stages, spp, seed, threads);
    if (g_mode == CallMode::record) {
        RenderResult r;
        try {
            Pause p;
            r = render_case(scene, c, stages, spp, seed, threads);
        } catch (...) {
            log_exception();
            throw;
        }
        std::lock_guard<std::mutex> lock(g_log_mutex);
        put(uint8_t(kImage)), put(uint32_t(r.image.width())), put(uint32_t(r.image.height()));
        put_bytes(r.image.data().data(), r.image.data().size() * sizeof(float));
        put_bytes(r.sample_counts.data(), r.sample_counts.size() * sizeof(uint32_t));
        return r;
    }
    begin_record(kImage, "a render");
    uint32_t w = 0, h = 0;
    get(w), get(h);
    if (int(w) != c.width || int(h) != c.height)
        bad("an image of " + std::to_string(w) + "x" + std::to_string(h) + " pixels, not " +
            std::to_string(c.width) + "x" + std::to_string(c.height));
    RenderResult r;
    r.image = Image(int(w), int(h));
    get_bytes(r.image.data().data(), r.image.data().size() * sizeof(float));
    for (float v : r.image.data())
        if (!std::isfinite(v) || v < 0) bad("an image with a negative, NaN or infinite value");
    r.sample_counts.resize(size_t(w) * h);
    get_bytes(r.sample_counts.data(), r.sample_counts.size() * sizeof(uint32_t));
    return r;
}

TraversalTiming student_traversal_timing(const BVHTree& tree, BvhIntersectFn traverse,
                                         const std::vector<Ray>& rays, double max_seconds) {
    if (g_mode == CallMode::direct) return time_traversal(tree, traverse, rays, max_seconds);
    if (g_mode == CallMode::record) {
        // The runner's own clock is worth nothing to the grader: only the answers are logged.
        TraversalTiming m;
        try {
            Pause p;
            m = time_traversal(tree, traverse, rays, max_seconds);
        } catch (...) {
            log_exception();
            throw;
        }
        std::lock_guard<std::mutex> lock(g_log_mutex);
        put(uint8_t(kTiming)), put(uint64_t(m.answers.size()));
        for (const std::optional<Hit>& h : m.answers) {
            put(h.has_value());
            if (h) put(h->t), put(h->primitive);
        }
        return m;
    }
    begin_record(kTiming, "a timed traversal");
    uint64_t n = 0;
    get(n);
    if (n > rays.size()) bad("more answers than rays");
    TraversalTiming m;
    m.answers.resize(size_t(n));
    for (std::optional<Hit>& h : m.answers) {
        bool hit = false;
        get(hit);
        if (!hit) continue;
        Hit x;
        get(x.t), get(x.primitive);
        h = x;
    }
    if (!(g_runner_cpu >= 0)) bad("the runner's CPU time is unknown");
    m.seconds = g_runner_cpu;
    m.whole_runner = true;
    return m;
}

void set_runner_cpu_seconds(double seconds) { g_runner_cpu = seconds; }

std::string printable(const std::string& text, size_t limit) {
    std::string out;
    for (char ch : text.substr(0, limit))
        out += (ch >= 32 && ch < 127) ? ch : '?';
    if (text.size() > limit) out += "...";
    return out;
}

}  // namespace pt
