// Reading and writing images.
//
//   PNG  8-bit sRGB (image/tonemap.h): what students and graders look at.
//   PFM  32-bit float, linear, no clamping: what metrics should compare.
//        Portable Float Map, "PF" header, little-endian (negative scale),
//        rows stored bottom to top (Debevec's HDRShop convention).
//   HDR  Radiance RGBE (environment maps), via stb_image and stb_image_write.
//   EXR  OpenEXR, 32-bit float, linear (image/exr_io.h, tinyexr).
//
// Every failure throws InputError naming the file and the reason. Every
// write is checked and atomic (core/atomic_file.h): a failed or interrupted
// write leaves the old file as it was.
#pragma once

#include <string>

#include "image/image.h"

namespace pt {

void write_png(const Image& image, const std::string& path);
void write_pfm(const Image& image, const std::string& path);
void write_hdr(const Image& image, const std::string& path);  ///< Radiance RGBE
/// Writes PNG, PFM, HDR or EXR according to the extension of `path`.
void write_image(const Image& image, const std::string& path);

Image read_png(const std::string& path);  ///< decodes sRGB to linear
Image read_pfm(const std::string& path);
Image read_hdr(const std::string& path);
/// Reads PNG, PFM, HDR or EXR according to the extension of `path`.
Image read_image(const std::string& path);

/// Lower-case extension with its dot (".png"), or "" when there is none.
std::string file_extension(const std::string& path);

}  // namespace pt
