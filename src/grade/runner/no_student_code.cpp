// The student functions as `grade` links them: it holds no student code
// (docs/grading.md "Trusted and untrusted halves"); the student's code runs
// only in the runners. Calling one of these is a bug of the grader.
#include <stdexcept>

#include "stages/bdpt.h"
#include "stages/media.h"
#include "stages/photon.h"
#include "stages/stages.h"

namespace pt::student {
namespace {
[[noreturn]] void absent(const char* name) {
    throw std::logic_error(std::string("grade holds no student code, yet called ") + name);
}
}  // namespace

Ray generate_ray(const Camera&, double, double, Vec2) { absent("generate_ray"); }
PixelResult raytrace_pixel(const RenderContext&, int, int) { absent("raytrace_pixel"); }
std::optional<Hit> intersect_triangle(const Triangle&, const Ray&) { absent("intersect_triangle"); }
std::optional<Hit> intersect_sphere(const Sphere&, const Ray&) { absent("intersect_sphere"); }
std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>&, size_t, size_t, size_t) {
    absent("construct_bvh");
}
bool bbox_intersect(const BBox&, const Ray&, double&, double&) { absent("bbox_intersect"); }
std::optional<Hit> bvh_intersect(const BVHTree&, const Ray&, const BVHNode*) {
    absent("bvh_intersect");
}
bool bvh_has_intersection(const BVHTree&, const Ray&, const BVHNode*) {
    absent("bvh_has_intersection");
}
std::optional<Hit> grid_intersect(const GridCells&, const Ray&) { absent("grid_intersect"); }
bool has_converged(const PixelStatistics&, double) { absent("has_converged"); }
Color diffuse_f(const Color&, const Vec3&, const Vec3&) { absent("diffuse_f"); }
BSDFSample diffuse_sample_f(const Color&, const Vec3&, Vec2) { absent("diffuse_sample_f"); }
Color zero_bounce_radiance(const RenderContext&, const Ray&, const SurfaceInteraction&) {
    absent("zero_bounce_radiance");
}
Color estimate_direct_lighting_hemisphere(const RenderContext&, const Ray&,
                                          const SurfaceInteraction&, Rng&) {
    absent("estimate_direct_lighting_hemisphere");
}
Color estimate_direct_lighting_importance(const RenderContext&, const Ray&,
                                          const SurfaceInteraction&, Rng&) {
    absent("estimate_direct_lighting_importance");
}
Color one_bounce_radiance(const RenderContext&, const Ray&, const SurfaceInteraction&, Rng&) {
    absent("one_bounce_radiance");
}
Color at_least_one_bounce_radiance(const RenderContext&, const Ray&, const SurfaceInteraction&,
                                   const Color&, Rng&) {
    absent("at_least_one_bounce_radiance");
}
Color est_radiance_global_illumination(const RenderContext&, const Ray&, Rng&) {
    absent("est_radiance_global_illumination");
}
double power_heuristic(double, double, double, double) { absent("power_heuristic"); }
double balance_heuristic(double, double, double, double) { absent("balance_heuristic"); }
Color estimate_direct_lighting_mis(const RenderContext&, const Ray&, const SurfaceInteraction&,
                                   Rng&) {
    absent("estimate_direct_lighting_mis");
}
EmittedPhoton emit_photon(const Light&, double, uint64_t, Vec2, Vec2) { absent("emit_photon"); }
KdTree build_kdtree(const std::vector<Vec3>&) { absent("build_kdtree"); }
void k_nearest(const KdTree&, const Vec3&, int, double, std::vector<Neighbor>&) {
    absent("k_nearest");
}
Color density_estimate(const std::vector<PhotonContribution>&, double, PhotonKernel) {
    absent("density_estimate");
}
Vec2 stratified_sample_2d(int, int, int, Vec2) { absent("stratified_sample_2d"); }
double scrambled_radical_inverse(uint64_t, const DigitPermutation&) {
    absent("scrambled_radical_inverse");
}
Color homogeneous_transmittance(const Color&, double) { absent("homogeneous_transmittance"); }
DistanceSample sample_distance(double, double, double) { absent("sample_distance"); }
double hg_phase(double, double) { absent("hg_phase"); }
Vec3 sample_hg(const Vec3&, double, Vec2) { absent("sample_hg"); }
Color in_scattered_radiance(const RenderContext&, const Vec3&, const Vec3&, int, Rng&) {
    absent("in_scattered_radiance");
}
int random_walk(const RenderContext&, const Ray&, const Color&, double, int, Transport, Rng&,
                std::vector<PathVertex>&) {
    absent("random_walk");
}
Connection connect(const RenderContext&, const std::vector<PathVertex>&, int, const std::vector<PathVertex>&, int,
                   Rng&) {
    absent("connect");
}
double mis_weight(const MisVertex*, int, const MisVertex*, int, bool, MisHeuristic) { absent("mis_weight"); }

}  // namespace pt::student
