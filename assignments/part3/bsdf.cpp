// Part 3, tasks 1 and 2: the Lambertian (diffuse) BSDF, CS184's
// DiffuseBSDF::f and DiffuseBSDF::sample_f. Read assignments/part3/README.md
// first; the contract of each function is in src/stages/direct.h.
//
// Both work in the local shading frame: the normal is +z, so cos(theta) of
// a unit direction w is w.z. wo points back along the incoming ray, wi
// towards where light comes from; both point away from the surface.
#include "core/error.h"
#include "core/math.h"
#include "core/sampling.h"
#include "stages/direct.h"

namespace pt::student {

Color diffuse_f(const Color& albedo, const Vec3& wo, const Vec3& wi) {
    // TODO(part3.1): diffuse_f, as src/stages/direct.h states its contract.
    // [guided]
    // return the Lambertian BSDF value albedo / pi (kInvPi is
    // in core/math.h) when wi is in the upper hemisphere (wi.z > 0), and
    // black (Color(0)) below it. A diffuse surface does not care about wo.
    // [/guided]
    (void)albedo, (void)wo, (void)wi;
    throw NotImplemented(3, "1", "diffuse_f");
}

BSDFSample diffuse_sample_f(const Color& albedo, const Vec3& wo, Vec2 u) {
    // TODO(part3.2): diffuse_sample_f, as src/stages/direct.h states its contract.
    // [guided]
    // draw wi cosine-weighted on the upper hemisphere from u
    // (sample_cosine_hemisphere in core/sampling.h), and return a BSDFSample
    // with that wi, f = diffuse_f(albedo, wo, wi) and pdf = cos(theta) / pi
    // (cosine_hemisphere_pdf). When the pdf is 0 (wi on the horizon) return
    // BSDFSample{} (pdf 0 means "no sample").
    // [/guided]
    (void)albedo, (void)wo, (void)u;
    throw NotImplemented(3, "2", "diffuse_sample_f");
}

}  // namespace pt::student
