// Stage `camera` (Part 1): camera rays and the per-pixel sampling loop.
//
// generate_ray maps normalised image coordinates (x, y) in [0, 1]^2, with
// (0, 0) at the bottom-left corner of the image and (1, 1) at the top-right
// (CS184's convention), to a world-space ray. In camera space the sensor
// point is
//     ((2x - 1) tan(hfov/2), (2y - 1) tan(vfov/2), -1)
// and the ray leaves the centre of projection through it, rotated to world
// space by the camera-to-world matrix. Ray parameters are distances along
// the unit direction, limited to [near_clip, far_clip].
//
// Thin lens (camera.lens_radius > 0; Part 4 of CS184's second homework):
// the ray starts at a point of the lens disk chosen by lens_sample and
// passes through the point where the pinhole ray meets the plane of focus,
// so that only that plane is sharp.
//
// raytrace_pixel estimates the pixel's radiance: the mean of the
// integrator's radiance over -s camera rays at random positions in the
// pixel square (one ray through the pixel centre when -s is 1).
//
// Tests: tests/unit/test_camera.cpp (centre and corner rays against
// hand-computed directions), tests/cli (determinism across -t).
#pragma once

#include <cstdint>

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "core/vec3.h"
#include "scene/camera.h"

namespace pt {

struct RenderContext;

/// What raytrace_pixel returns for one pixel.
struct PixelResult {
    Color radiance;   ///< estimate of the pixel's mean radiance (linear RGB)
    int samples = 0;  ///< camera rays traced for this pixel
};

using GenerateRayFn = Ray (*)(const Camera& camera, double x, double y, Vec2 lens_sample);
using RaytracePixelFn = PixelResult (*)(const RenderContext& context, int x, int y);

struct CameraStage {
    /// World-space camera ray through normalised image point (x, y); unit
    /// direction; t in [near_clip, far_clip]; lens_sample in [0, 1)^2 picks
    /// the point on the lens when camera.lens_radius > 0 (ignored otherwise).
    GenerateRayFn generate_ray;
    /// Radiance estimate of pixel (x, y), x rightwards from 0 and y
    /// downwards from 0 (the top row), as the film stores it.
    RaytracePixelFn raytrace_pixel;
};

namespace reference {
Ray generate_ray(const Camera& camera, double x, double y, Vec2 lens_sample);
PixelResult raytrace_pixel(const RenderContext& context, int x, int y);
/// The camera ray of sample `index` of pixel (x, y) as raytrace_pixel draws
/// it, from `rng` = context.sample_generator(x, y, index), which is left at
/// dimension 4, where the bounces start. The renderer's packets of camera
/// rays (--packets on, render/camera_packets.h) draw their rays here too.
Ray sample_camera_ray(const RenderContext& context, int x, int y, int index, Rng& rng);
}  // namespace reference

namespace student {
Ray generate_ray(const Camera& camera, double x, double y, Vec2 lens_sample);
PixelResult raytrace_pixel(const RenderContext& context, int x, int y);
}  // namespace student

}  // namespace pt
