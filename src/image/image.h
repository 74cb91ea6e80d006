// Image: a float RGB image in linear radiance units, row-major with the top
// row first (y = 0 is the top of the picture, as in PNG).
#pragma once

#include <cstddef>
#include <vector>

#include "core/color.h"

namespace pt {

class Image {
public:
    Image() = default;
    Image(int width, int height) : width_(width), height_(height), data_(size_t(width) * height * 3, 0.f) {}

    int width() const { return width_; }
    int height() const { return height_; }
    size_t pixel_count() const { return size_t(width_) * height_; }
    bool empty() const { return data_.empty(); }

    Color at(int x, int y) const {
        const float* p = &data_[index(x, y)];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, const Color& c) {
        float* p = &data_[index(x, y)];
        p[0] = float(c.r);
        p[1] = float(c.g);
        p[2] = float(c.b);
    }
    /// Raw RGB floats, 3 per pixel.
    const std::vector<float>& data() const { return data_; }
    std::vector<float>& data() { return data_; }

private:
    size_t index(int x, int y) const { return (size_t(y) * width_ + x) * 3; }

    int width_ = 0;
    int height_ = 0;
    std::vector<float> data_;  ///< linear RGB, 3 floats per pixel
};

}  // namespace pt
