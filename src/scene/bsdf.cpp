#include "scene/bsdf.h"

#include "core/sampling.h"
#include "scene/material.h"

namespace pt {

Color BSDF::f(const Vec3& wo, const Vec3& wi) const {
    switch (material_->type) {
        case MaterialType::diffuse:
            return diffuse_.f(material_->albedo, wo, wi);
        case MaterialType::mirror:
        case MaterialType::glass:
            break;  // deltas: f is zero for every given pair
    }
    return Color(0);
}

BSDFSample BSDF::sample_f(const Vec3& wo, Vec2 u) const {
    switch (material_->type) {
        case MaterialType::diffuse:
            return diffuse_.sample_f(material_->albedo, wo, u);
        case MaterialType::mirror:
        case MaterialType::glass:
            break;  // Part 4 samples the mirror and glass deltas here
    }
    BSDFSample none;
    none.is_delta = true;
    return none;
}

double BSDF::pdf(const Vec3& wo, const Vec3& wi) const {
    (void)wo;
    switch (material_->type) {
        // The density of cosine-weighted sampling, which the Lambertian
        // sample_f contract prescribes (stages/direct.h).
        case MaterialType::diffuse:
            return wi.z > 0 ? cosine_hemisphere_pdf(wi.z) : 0.0;
        case MaterialType::mirror:
        case MaterialType::glass:
            break;
    }
    return 0.0;
}

bool BSDF::is_delta() const {
    return material_->type != MaterialType::diffuse;
}

}  // namespace pt
