// The reference functions a runner withholds (grade/runners.h): strong
// definitions that replace the reference's, which the runner's engine
// archive holds only as weak symbols (objcopy --weaken-symbol, see
// src/CMakeLists.txt). Each is compiled in only when its PT_WITHHOLD_*
// macro is defined for the runner. Calling one throws: student code that
// calls the reference of the function it is graded on fails that task.
#include <stdexcept>

#include "stages/bdpt.h"
#include "stages/mis.h"
#include "stages/stages.h"

namespace pt::reference {
namespace {
[[noreturn]] void withheld(const char* name) {
    throw std::runtime_error(std::string("the reference ") + name +
                             " is not available to the code it grades");
}
}  // namespace

#ifdef PT_WITHHOLD_GENERATE_RAY
Ray generate_ray(const Camera&, double, double, Vec2) { withheld("generate_ray"); }
#endif
#ifdef PT_WITHHOLD_RAYTRACE_PIXEL
PixelResult raytrace_pixel(const RenderContext&, int, int) { withheld("raytrace_pixel"); }
#endif
#ifdef PT_WITHHOLD_INTERSECT_TRIANGLE
std::optional<Hit> intersect_triangle(const Triangle&, const Ray&) { withheld("intersect_triangle"); }
std::optional<Hit> intersect_triangle_watertight(const Triangle&, const Ray&) {
    withheld("intersect_triangle_watertight");
}
#endif
#ifdef PT_WITHHOLD_INTERSECT_SPHERE
std::optional<Hit> intersect_sphere(const Sphere&, const Ray&) { withheld("intersect_sphere"); }
#endif
#ifdef PT_WITHHOLD_CONSTRUCT_BVH
std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>&, size_t, size_t, size_t) {
    withheld("construct_bvh");
}
#endif
#ifdef PT_WITHHOLD_BBOX_INTERSECT
bool bbox_intersect(const BBox&, const Ray&, double&, double&) { withheld("bbox_intersect"); }
#endif
#ifdef PT_WITHHOLD_BVH_INTERSECT
std::optional<Hit> bvh_intersect(const BVHTree&, const Ray&, const BVHNode*) {
    withheld("bvh_intersect");
}
#endif
#ifdef PT_WITHHOLD_BVH_HAS_INTERSECTION
bool bvh_has_intersection(const BVHTree&, const Ray&, const BVHNode*) {
    withheld("bvh_has_intersection");
}
#endif
#ifdef PT_WITHHOLD_GRID_INTERSECT
std::optional<Hit> grid_intersect(const GridCells&, const Ray&) { withheld("grid_intersect"); }
#endif
#ifdef PT_WITHHOLD_HAS_CONVERGED
bool has_converged(const PixelStatistics&, double) { withheld("has_converged"); }
#endif
#ifdef PT_WITHHOLD_DIFFUSE_F
Color diffuse_f(const Color&, const Vec3&, const Vec3&) { withheld("diffuse_f"); }
#endif
#ifdef PT_WITHHOLD_DIFFUSE_SAMPLE_F
BSDFSample diffuse_sample_f(const Color&, const Vec3&, Vec2) { withheld("diffuse_sample_f"); }
#endif
#ifdef PT_WITHHOLD_ZERO_BOUNCE
Color zero_bounce_radiance(const RenderContext&, const Ray&, const SurfaceInteraction&) {
    withheld("zero_bounce_radiance");
}
#endif
#ifdef PT_WITHHOLD_HEMISPHERE
Color estimate_direct_lighting_hemisphere(const RenderContext&, const Ray&,
                                          const SurfaceInteraction&, Rng&) {
    withheld("estimate_direct_lighting_hemisphere");
}
#endif
#ifdef PT_WITHHOLD_IMPORTANCE
Color estimate_direct_lighting_importance(const RenderContext&, const Ray&,
                                          const SurfaceInteraction&, Rng&) {
    withheld("estimate_direct_lighting_importance");
}
#endif
#ifdef PT_WITHHOLD_ONE_BOUNCE
Color one_bounce_radiance(const RenderContext&, const Ray&, const SurfaceInteraction&, Rng&) {
    withheld("one_bounce_radiance");
}
#endif
#ifdef PT_WITHHOLD_MIS_HEURISTICS
double power_heuristic(double, double, double, double) { withheld("power_heuristic"); }
double balance_heuristic(double, double, double, double) { withheld("balance_heuristic"); }
#endif
#ifdef PT_WITHHOLD_ESTIMATE_MIS
Color estimate_direct_lighting_mis(const RenderContext&, const Ray&, const SurfaceInteraction&,
                                   Rng&) {
    withheld("estimate_direct_lighting_mis");
}
#endif
#ifdef PT_WITHHOLD_AT_LEAST_ONE_BOUNCE
Color at_least_one_bounce_radiance(const RenderContext&, const Ray&, const SurfaceInteraction&,
                                   const Color&, Rng&) {
    withheld("at_least_one_bounce_radiance");
}
#endif
#ifdef PT_WITHHOLD_EST_RADIANCE
Color est_radiance_global_illumination(const RenderContext&, const Ray&, Rng&) {
    withheld("est_radiance_global_illumination");
}
#endif

#ifdef PT_WITHHOLD_STRATIFIED_SAMPLE_2D
Vec2 stratified_sample_2d(int, int, int, Vec2) { withheld("stratified_sample_2d"); }
#endif
#ifdef PT_WITHHOLD_SCRAMBLED_RADICAL_INVERSE
double scrambled_radical_inverse(uint64_t, const DigitPermutation&) {
    withheld("scrambled_radical_inverse");
}
#endif
#ifdef PT_WITHHOLD_EMIT_PHOTON
EmittedPhoton emit_photon(const Light&, double, uint64_t, Vec2, Vec2) { withheld("emit_photon"); }
#endif
#ifdef PT_WITHHOLD_BUILD_KDTREE
KdTree build_kdtree(const std::vector<Vec3>&) { withheld("build_kdtree"); }
#endif
#ifdef PT_WITHHOLD_K_NEAREST
void k_nearest(const KdTree&, const Vec3&, int, double, std::vector<Neighbor>&) {
    withheld("k_nearest");
}
#endif
#ifdef PT_WITHHOLD_DENSITY_ESTIMATE
Color density_estimate(const std::vector<PhotonContribution>&, double, PhotonKernel) {
    withheld("density_estimate");
}
#endif
#ifdef PT_WITHHOLD_HOMOGENEOUS_TRANSMITTANCE
Color homogeneous_transmittance(const Color&, double) { withheld("homogeneous_transmittance"); }
#endif
#ifdef PT_WITHHOLD_SAMPLE_DISTANCE
DistanceSample sample_distance(double, double, double) { withheld("sample_distance"); }
#endif
#ifdef PT_WITHHOLD_HG_PHASE
double hg_phase(double, double) { withheld("hg_phase"); }
#endif
#ifdef PT_WITHHOLD_SAMPLE_HG
Vec3 sample_hg(const Vec3&, double, Vec2) { withheld("sample_hg"); }
#endif
#ifdef PT_WITHHOLD_IN_SCATTERED_RADIANCE
Color in_scattered_radiance(const RenderContext&, const Vec3&, const Vec3&, int, Rng&) {
    withheld("in_scattered_radiance");
}
#endif
#ifdef PT_WITHHOLD_RANDOM_WALK
int random_walk(const RenderContext&, const Ray&, const Color&, double, int, Transport, Rng&,
                std::vector<PathVertex>&) {
    withheld("random_walk");
}
#endif
#ifdef PT_WITHHOLD_CONNECT
Connection connect(const RenderContext&, const std::vector<PathVertex>&, int, const std::vector<PathVertex>&, int,
                   Rng&) {
    withheld("connect");
}
#endif
#ifdef PT_WITHHOLD_MIS_WEIGHT
double mis_weight(const MisVertex*, int, const MisVertex*, int, bool, MisHeuristic) { withheld("mis_weight"); }
#endif

}  // namespace pt::reference

// Engine helpers that compute a graded answer whole (scripts/weaken_reference.sh):
// task 3.5's light-sampling estimator, and the BSDF half of task 3.8's weights.
#if defined(PT_WITHHOLD_IMPORTANCE) || defined(PT_WITHHOLD_ESTIMATE_MIS)
namespace pt {
Color sample_lights_mis(const RenderContext&, const SurfaceInteraction&, const BSDF&, const Vec3&, int, Rng&) {
    throw std::runtime_error("the engine's sample_lights_mis is not available to the code it grades");
}
double bsdf_sample_mis_weight(const RenderContext&, const LightSampleContext&, const Vec3&,
                              const std::optional<SurfaceInteraction>&, double, int) {
    throw std::runtime_error("the engine's bsdf_sample_mis_weight is not available to the code it grades");
}
}  // namespace pt
#endif
