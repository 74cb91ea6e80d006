#include "stages/embree_accel.h"

#include "core/counters.h"
#include "core/error.h"
#include "scene/scene.h"
#include "stages/spatial_subdivision.h"

#if PT_WITH_EMBREE
#include <embree3/rtcore.h>
#endif

namespace pt {

#if PT_WITH_EMBREE

namespace {

/// The ray as Embree takes it: single precision. A t_max of infinity stays
/// infinite; finite ones round up so that no hit the double ray sees is cut.
RTCRay to_embree(const Ray& r) {
    RTCRay e{};
    e.org_x = float(r.o.x), e.org_y = float(r.o.y), e.org_z = float(r.o.z);
    e.dir_x = float(r.d.x), e.dir_y = float(r.d.y), e.dir_z = float(r.d.z);
    e.tnear = float(r.t_min);
    e.tfar = float(r.t_max) * (1.0f + 1e-6f);
    e.mask = ~0u;
    return e;
}

class EmbreeAccelerator final : public Accelerator {
  public:
    EmbreeAccelerator(const Scene& scene, const IntersectStage& stage) : scene_(scene), stage_(stage) {
        device_ = rtcNewDevice(nullptr);
        if (!device_) throw InputError("--accel embree: Embree could not create a device");
        scene_handle_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_handle_, RTC_BUILD_QUALITY_MEDIUM);
        if (!scene.triangles.empty()) {
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), scene.positions.size()));
            for (size_t i = 0; i < scene.positions.size(); ++i)
                for (int a = 0; a < 3; ++a)
                    v[3 * i + a] = float(scene.positions[i][a]);
            auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), scene.triangles.size()));
            for (size_t i = 0; i < scene.triangles.size(); ++i)
                for (int k = 0; k < 3; ++k)
                    idx[3 * i + k] = scene.triangles[i].v[k];
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene_handle_, g);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(scene_handle_);
    }
    ~EmbreeAccelerator() override {
        rtcReleaseScene(scene_handle_);
        rtcReleaseDevice(device_);
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray = to_embree(ray);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_handle_, &context, &rh);
        ClosestHit closest(ray);
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
            closest.offer(intersect_primitive(scene_, stage_, rh.hit.primID, ray));
        test_spheres(closest);
        return closest.best;
    }

    bool occluded(const Ray& ray) const override {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay r = to_embree(ray);
        rtcOccluded1(scene_handle_, &context, &r);
        if (r.tfar < 0) return true;  // Embree marks an occluded ray with tfar = -inf
        for (uint32_t p = uint32_t(scene_.triangles.size()); p < scene_.primitive_count(); ++p)
            if (intersect_primitive(scene_, stage_, p, ray)) return true;
        return false;
    }

    AcceleratorInfo info() const override { return {"embree", 0, 0, 0}; }

  private:
    void test_spheres(ClosestHit& closest) const {
        for (uint32_t p = uint32_t(scene_.triangles.size()); p < scene_.primitive_count(); ++p)
            closest.offer(intersect_primitive(scene_, stage_, p, closest.ray));
        thread_counters().primitive_tests += scene_.spheres.size();
    }

    const Scene& scene_;
    IntersectStage stage_;
    RTCDevice device_ = nullptr;
    RTCScene scene_handle_ = nullptr;
};

}  // namespace

bool embree_available() {
    return true;
}

std::unique_ptr<Accelerator> make_embree_accelerator(const Scene& scene, const IntersectStage& stage) {
    return std::make_unique<EmbreeAccelerator>(scene, stage);
}

#else

bool embree_available() {
    return false;
}

std::unique_ptr<Accelerator> make_embree_accelerator(const Scene&, const IntersectStage&) {
    throw InputError("--accel embree: this build has no Embree (configure with -DPT_WITH_EMBREE=ON and "
                     "Debian's libembree-dev)");
}

#endif

}  // namespace pt
