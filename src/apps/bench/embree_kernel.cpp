#include "apps/bench/embree_kernel.h"

#include <algorithm>
#include <stdexcept>

#include "core/timer.h"
#include "scene/scene.h"

#if PT_WITH_EMBREE
#include <embree3/rtcore.h>
#endif

namespace pt::bench {

#if PT_WITH_EMBREE

namespace {

/// A ray as Embree takes it: single precision, no hit yet.
RTCRayHit to_embree(const Ray& r) {
    RTCRayHit rh{};
    rh.ray.org_x = float(r.o.x);
    rh.ray.org_y = float(r.o.y);
    rh.ray.org_z = float(r.o.z);
    rh.ray.dir_x = float(r.d.x);
    rh.ray.dir_y = float(r.d.y);
    rh.ray.dir_z = float(r.d.z);
    rh.ray.tnear = float(r.t_min);
    rh.ray.tfar = float(r.t_max);
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

/// Embree's memory monitor: called with +bytes before each allocation and
/// -bytes after each release, `user` the running sum (one thread builds).
bool count_device_bytes(void* user, ssize_t bytes, bool) {
    *static_cast<int64_t*>(user) += int64_t(bytes);
    return true;
}

}  // namespace

struct EmbreeKernel::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    double build_seconds = 0;
    int64_t live_bytes = 0;       ///< what the device holds now (its memory monitor's running sum)
    int64_t structure_bytes = 0;  ///< held after the commit beyond what the buffers took before it
};

bool EmbreeKernel::available() {
    return true;
}

std::string EmbreeKernel::version() {
    return "Embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) +
           "." + std::to_string(RTC_VERSION_PATCH);
}

EmbreeKernel::EmbreeKernel(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice("threads=1,set_affinity=0");
    if (!impl_->device) throw std::runtime_error("Embree: rtcNewDevice failed");
    rtcSetDeviceMemoryMonitorFunction(impl_->device, count_device_bytes, &impl_->live_bytes);
    // The first commit in a process starts Embree's task system: do it
    // outside the timed build.
    static bool warmed_up = false;
    if (!warmed_up) {
        RTCScene warm = rtcNewScene(impl_->device);
        RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, 3));
        auto* i = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, 1));
        const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        std::copy(corners, corners + 9, v);
        i[0] = 0, i[1] = 1, i[2] = 2;
        rtcCommitGeometry(g);
        rtcAttachGeometry(warm, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(warm);
        rtcReleaseScene(warm);
        warmed_up = true;
    }
    CpuTimer timer;  // CPU time of the (one-thread) build, as for the reference BVH
    impl_->scene = rtcNewScene(impl_->device);
    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), scene.positions.size()));
    for (size_t i = 0; i < scene.positions.size(); ++i)
        for (int a = 0; a < 3; ++a)
            vertices[3 * i + a] = float(scene.positions[i][a]);
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), scene.triangles.size()));
    for (size_t i = 0; i < scene.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k)
            indices[3 * i + k] = scene.triangles[i].v[k];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(impl_->scene, geometry);
    rtcReleaseGeometry(geometry);
    const int64_t before_commit = impl_->live_bytes;  // the vertex and index buffers
    rtcCommitScene(impl_->scene);
    impl_->build_seconds = timer.seconds();
    impl_->structure_bytes = impl_->live_bytes - before_commit;
}

EmbreeKernel::~EmbreeKernel() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

double EmbreeKernel::build_seconds() const {
    return impl_->build_seconds;
}

uint64_t EmbreeKernel::structure_bytes() const {
    return uint64_t(std::max<int64_t>(0, impl_->structure_bytes));
}

KernelPass EmbreeKernel::trace(const std::vector<Ray>& rays, bool any_hit) const {
    std::vector<RTCRayHit> prepared;
    prepared.reserve(rays.size());
    for (const Ray& r : rays)
        prepared.push_back(to_embree(r));
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    KernelPass pass;
    uint64_t hits = 0;
    CpuTimer timer;  // as trace_pass: the kernel's own CPU time
    if (any_hit) {
        for (const RTCRayHit& p : prepared) {
            RTCRay ray = p.ray;
            rtcOccluded1(impl_->scene, &context, &ray);
            hits += ray.tfar < 0 ? 1 : 0;  // Embree marks an occluded ray with tfar = -inf
        }
    } else {
        for (const RTCRayHit& p : prepared) {
            RTCRayHit rh = p;
            rtcIntersect1(impl_->scene, &context, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? 1 : 0;
        }
    }
    pass.seconds = timer.seconds();
    pass.hits = hits;
    return pass;
}

std::vector<uint32_t> EmbreeKernel::closest_triangles(const std::vector<Ray>& rays) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::vector<uint32_t> out;
    out.reserve(rays.size());
    for (const Ray& r : rays) {
        RTCRayHit rh = to_embree(r);
        rtcIntersect1(impl_->scene, &context, &rh);
        out.push_back(rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.hit.primID : UINT32_MAX);
    }
    return out;
}

#else  // without Embree: the bench leaves its columns out

struct EmbreeKernel::Impl {};
bool EmbreeKernel::available() {
    return false;
}
std::string EmbreeKernel::version() {
    return "";
}
EmbreeKernel::EmbreeKernel(const Scene&) {
    throw std::runtime_error(
        "this bench was built without Embree (configure with -DPT_WITH_EMBREE=ON)");
}
EmbreeKernel::~EmbreeKernel() = default;
double EmbreeKernel::build_seconds() const {
    return 0;
}
uint64_t EmbreeKernel::structure_bytes() const {
    return 0;
}
KernelPass EmbreeKernel::trace(const std::vector<Ray>&, bool) const {
    return {};
}
std::vector<uint32_t> EmbreeKernel::closest_triangles(const std::vector<Ray>&) const {
    return {};
}

#endif

}  // namespace pt::bench
