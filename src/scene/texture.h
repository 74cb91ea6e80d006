// Textures: a colour that varies over a surface, looked up by the surface's
// (u, v) coordinates. Used for the diffuse albedo (scene "albedo":
// {"texture": "file.png"} or {"checkerboard": [...]}, MTL map_Kd).
//
//   image         an image file (PNG, PFM, HDR, EXR). PNG texels are sRGB-
//                 encoded and decoded to linear reflectance on load (IEC
//                 61966-2-1, image/tonemap.h); the float formats are linear.
//                 Filtering is bilinear between the four nearest texel
//                 centres (texel (i, j) has its centre at ((i + 0.5) / w,
//                 1 - (j + 0.5) / h): v runs up, image rows down, as in OBJ),
//                 and the texture repeats outside [0, 1]^2.
//   checkerboard  two colours in squares of 1 / scale in (u, v): even when
//                 floor(u scale) + floor(v scale) is even.
//
// (u, v) come from the OBJ's vt coordinates (barycentric interpolation), a
// quad's corners ((0, 0) at "corner", (1, 0) at corner + edge1, (0, 1) at
// corner + edge2), or a sphere's longitude and latitude (Scene::uv_at).
//
// Tests: tests/unit/test_textures.cpp (texel centres exact, bilinear
// midpoints, wrapping, sRGB decoding, the checkerboard, OBJ and JSON
// loading, a rendered texture against the point-light formula).
#pragma once

#include <memory>
#include <string>

#include "core/color.h"
#include "core/vec3.h"
#include "image/image.h"

namespace pt {

class Texture {
  public:
    virtual ~Texture() = default;
    /// The colour at surface coordinates uv (any real numbers: textures repeat).
    virtual Color evaluate(Vec2 uv) const = 0;
};

class ImageTexture final : public Texture {
  public:
    /// `image` holds linear values; `scale` multiplies (u, v) (tiling).
    ImageTexture(Image image, Vec2 scale = Vec2(1, 1)) : image_(std::move(image)), scale_(scale) {}
    Color evaluate(Vec2 uv) const override;
    const Image& image() const { return image_; }

  private:
    Image image_;
    Vec2 scale_;
};

class CheckerboardTexture final : public Texture {
  public:
    CheckerboardTexture(const Color& even, const Color& odd, Vec2 scale) : even_(even), odd_(odd), scale_(scale) {}
    Color evaluate(Vec2 uv) const override;

  private:
    Color even_, odd_;
    Vec2 scale_;  ///< squares per unit of u and of v
};

/// Reads an image texture for a diffuse albedo: every texel must be finite
/// and in [0, 1] (a reflectance). Throws InputError naming `where` and the file.
std::shared_ptr<const Texture> load_albedo_texture(const std::string& path, const std::string& where,
                                                   Vec2 scale = Vec2(1, 1));

}  // namespace pt
