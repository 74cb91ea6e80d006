// Camera rays in packets (`--packets on`): the renderer traces the camera
// rays of eight neighbouring pixels of a row together, one packet per sample
// index, through Accelerator::intersect_packet (the wide BVH's shared
// traversal: Wald, Slusallek, Benthin and Wagner, "Interactive Rendering
// with Coherent Ray Tracing", Eurographics 2001), before the pixels are
// rendered one by one as usual. The hits wait in the thread's
// TracedCameraRays (stages/render_context.h), where RenderContext::intersect
// finds them when the integrator asks for the same rays; so every hit, and
// the image, is the same bit for bit as with single rays.
//
// Where it pays (docs/bvh.md, "Where packets pay"): camera rays of scenes
// that fill the view; bounce rays never, so only camera rays are packed.
#pragma once

#include "stages/render_context.h"

namespace pt {

/// Pixels in a packet: a 1x8 strip of a row.
constexpr int kPacketPixels = 8;
/// Samples per pixel traced ahead at most (memory: about 150 bytes each);
/// later samples are traced one ray at a time.
constexpr int kPacketSamples = 64;

/// Whether packets can serve this render: the reference camera stage
/// (whose rays reference::sample_camera_ray reproduces) and an accelerator
/// whose intersect_packet shares a traversal.
bool camera_packets_apply(const RenderContext& context);

/// Traces the camera rays of pixels (x0 + i, y), i < count <= kPacketPixels,
/// for the first samples that raytrace_pixel will draw, into lists[i].
void trace_camera_packets(const RenderContext& context, int x0, int y, int count, TracedCameraRays* lists);

}  // namespace pt
