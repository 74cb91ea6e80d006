// Part 3, tasks 1 and 2, written from the TODO steps.
#include "core/math.h"
#include "core/sampling.h"
#include "stages/direct.h"

namespace pt::student {

Color diffuse_f(const Color& albedo, const Vec3& wo, const Vec3& wi) {
    (void)wo;
    if (wi.z > 0) return albedo * kInvPi;
    return Color(0);
}

BSDFSample diffuse_sample_f(const Color& albedo, const Vec3& wo, Vec2 u) {
    BSDFSample s;
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(s.wi.z);
    if (s.pdf == 0) return BSDFSample{};
    s.f = diffuse_f(albedo, wo, s.wi);
    return s;
}

}  // namespace pt::student
