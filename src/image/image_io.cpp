#include "image/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/exr_io.h"
#include "image/tonemap.h"

namespace pt {
namespace {

std::string system_reason() { return std::strerror(errno); }

void check_not_empty(const Image& image, const std::string& path) {
    if (image.empty()) throw InputError(path + ": cannot write an empty image");
}

}  // namespace

std::string file_extension(const std::string& path) {
    size_t slash = path.find_last_of('/');
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

namespace {

/// stb's encoders hand their output to a callback; collect it, then write it
/// with the checked, atomic writer (core/atomic_file.h).
void append_bytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

void write_png(const Image& image, const std::string& path) {
    check_not_empty(image, path);
    std::vector<uint8_t> bytes(image.pixel_count() * 3);
    const std::vector<float>& data = image.data();
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = to_srgb8(data[i]);
    AtomicFile file(path);  // fails now, before encoding, on a path it cannot write
    std::string encoded;
    if (!stbi_write_png_to_func(append_bytes, &encoded, image.width(), image.height(), 3, bytes.data(),
                                image.width() * 3))
        throw InputError("cannot write " + path + ": PNG encoder failed");
    file.write(encoded);
    file.commit();
}

void write_pfm(const Image& image, const std::string& path) {
    check_not_empty(image, path);
    AtomicFile file(path);
    // Negative scale means little-endian, which is what x86 and ARM store.
    file.write("PF\n" + std::to_string(image.width()) + " " + std::to_string(image.height()) + "\n-1.0\n");
    const std::vector<float>& data = image.data();
    size_t row = size_t(image.width()) * 3;
    for (int y = image.height() - 1; y >= 0; --y) file.write(&data[size_t(y) * row], row * sizeof(float));
    file.commit();
}

void write_hdr(const Image& image, const std::string& path) {
    check_not_empty(image, path);
    AtomicFile file(path);
    std::string encoded;
    if (!stbi_write_hdr_to_func(append_bytes, &encoded, image.width(), image.height(), 3, image.data().data()))
        throw InputError("cannot write " + path + ": HDR encoder failed");
    file.write(encoded);
    file.commit();
}

void write_image(const Image& image, const std::string& path) {
    std::string ext = file_extension(path);
    if (ext == ".png") return write_png(image, path);
    if (ext == ".pfm") return write_pfm(image, path);
    if (ext == ".hdr") return write_hdr(image, path);
    if (ext == ".exr") return write_exr(image, path);
    throw InputError(path + ": unknown image type '" + ext + "' (expected .png, .pfm, .hdr or .exr)");
}

Image read_png(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 3),
                                                      stbi_image_free);
    if (!pixels) {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw InputError("cannot read " + path + ": " + system_reason());
        std::fclose(f);
        throw InputError(path + ": not a readable PNG image (" + stbi_failure_reason() + ")");
    }
    Image image(w, h);
    std::vector<float>& data = image.data();
    for (size_t i = 0; i < data.size(); ++i) data[i] = float(from_srgb8(pixels.get()[i]));
    return image;
}

Image read_pfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read " + path + ": " + system_reason());
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    if (!in || (magic != "PF" && magic != "Pf"))
        throw InputError(path + ": not a PFM image (expected a 'PF' or 'Pf' header)");
    if (w <= 0 || h <= 0 || w > 65536 || h > 65536 || scale == 0 || !std::isfinite(scale))
        throw InputError(path + ": PFM header has a bad size or scale");
    in.get();  // the single whitespace character after the scale
    int channels = magic == "PF" ? 3 : 1;
    size_t row = size_t(w) * channels;
    // The header may promise 50 GB: check the file holds the pixels before allocating them.
    std::streampos data_start = in.tellg();
    in.seekg(0, std::ios::end);
    if (!in || uint64_t(in.tellg() - data_start) < uint64_t(row) * uint64_t(h) * sizeof(float))
        throw InputError(path + ": PFM pixel data is truncated");
    in.seekg(data_start);
    std::vector<float> raw(row * h);
    in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * sizeof(float)));
    if (in.gcount() != std::streamsize(raw.size() * sizeof(float)))
        throw InputError(path + ": PFM pixel data is truncated");
    if (scale > 0) {  // big-endian data: swap bytes
        for (float& v : raw) {
            uint32_t u;
            std::memcpy(&u, &v, 4);
            u = __builtin_bswap32(u);
            std::memcpy(&v, &u, 4);
        }
    }
    Image image(w, h);
    for (int y = 0; y < h; ++y) {
        const float* src = &raw[size_t(h - 1 - y) * row];  // stored bottom row first
        for (int x = 0; x < w; ++x) {
            const float* p = src + size_t(x) * channels;
            image.set(x, y, channels == 3 ? Color(p[0], p[1], p[2]) : Color(p[0]));
        }
    }
    return image;
}

Image read_hdr(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<float, void (*)(void*)> pixels(stbi_loadf(path.c_str(), &w, &h, &channels, 3),
                                                    stbi_image_free);
    if (!pixels) {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw InputError("cannot read " + path + ": " + system_reason());
        std::fclose(f);
        throw InputError(path + ": not a readable Radiance HDR image (" + stbi_failure_reason() + ")");
    }
    Image image(w, h);
    std::copy(pixels.get(), pixels.get() + image.data().size(), image.data().begin());
    return image;
}

Image read_image(const std::string& path) {
    std::string ext = file_extension(path);
    if (ext == ".png") return read_png(path);
    if (ext == ".pfm") return read_pfm(path);
    if (ext == ".hdr") return read_hdr(path);
    if (ext == ".exr") return read_exr(path);
    throw InputError(path + ": unknown image type '" + ext + "' (expected .png, .pfm, .hdr or .exr)");
}

}  // namespace pt
