// OpenEXR images through Debian's tinyexr (libtinyexr-dev).
//
// What the renderer writes (`-f out.exr`, `--hdr out.exr`) is its linear
// radiance, unclamped, as three 32-bit float channels B, G, R (the order
// OpenEXR viewers expect), ZIP-compressed, with no tone curve: an EXR is
// what metrics compare, like PFM. What it reads (`-e sky.exr`, an image
// texture, imgdiff) is any single-part scanline or tiled RGB(A) or
// luminance image in half, float or uint channels; alpha is dropped.
// CS184's environment maps (lat-long .exr) load unchanged.
//
// Bad files are bad input: every failure throws InputError naming the file
// and tinyexr's reason, and a pixel that is NaN or infinite is an error
// (it would reach the film through an environment map or a texture).
//
// Tests: tests/unit/test_exr.cpp (a float round trip bit for bit, half
// files, errors), tests/cli/test_image_outputs.cpp (the flags).
#pragma once

#include <string>

#include "image/image.h"

namespace pt {

/// Writes `image` (linear RGB) as a float OpenEXR file, through the checked,
/// atomic writer (core/atomic_file.h); throws InputError.
void write_exr(const Image& image, const std::string& path);

/// Reads an OpenEXR file into linear RGB; throws InputError.
Image read_exr(const std::string& path);

}  // namespace pt
