#include "image/exr_io.h"

#include <tinyexr.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace pt {
namespace {

/// The largest image read: the film's limit (64 Mpixels), so that a header
/// claiming 2^31 x 2^31 pixels is refused before anything is allocated.
constexpr double kMaxPixels = double(1 << 26);

/// tinyexr's message, freed, as a std::string.
std::string take_message(const char* message) {
    std::string s = message ? message : "unknown error";
    if (message) FreeEXRErrorMessage(message);
    return s;
}

}  // namespace

void write_exr(const Image& image, const std::string& path) {
    if (image.empty()) throw InputError(path + ": cannot write an empty image");
    // OpenEXR stores channels by name; viewers expect them sorted: B, G, R.
    const int width = image.width(), height = image.height();
    const size_t n = image.pixel_count();
    std::vector<float> planes[3];
    for (std::vector<float>& p : planes) p.resize(n);
    const std::vector<float>& rgb = image.data();
    for (size_t i = 0; i < n; ++i) {
        planes[0][i] = rgb[3 * i + 2];
        planes[1][i] = rgb[3 * i + 1];
        planes[2][i] = rgb[3 * i + 0];
    }
    float* pointers[3] = {planes[0].data(), planes[1].data(), planes[2].data()};

    EXRImage exr_image;
    InitEXRImage(&exr_image);
    exr_image.num_channels = 3;
    exr_image.images = reinterpret_cast<unsigned char**>(pointers);
    exr_image.width = width;
    exr_image.height = height;

    EXRHeader header;
    InitEXRHeader(&header);
    EXRChannelInfo channels[3];
    std::memset(channels, 0, sizeof channels);
    const char* names[3] = {"B", "G", "R"};
    int pixel_types[3], requested_types[3];
    for (int c = 0; c < 3; ++c) {
        std::snprintf(channels[c].name, sizeof channels[c].name, "%s", names[c]);
        pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;      // what the arrays hold
        requested_types[c] = TINYEXR_PIXELTYPE_FLOAT;  // what the file stores: no rounding to half
    }
    header.num_channels = 3;
    header.channels = channels;
    header.pixel_types = pixel_types;
    header.requested_pixel_types = requested_types;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

    unsigned char* memory = nullptr;
    const char* message = nullptr;
    size_t size = SaveEXRImageToMemory(&exr_image, &header, &memory, &message);
    if (size == 0 || !memory) throw InputError("cannot write " + path + ": OpenEXR encoder: " + take_message(message));
    std::unique_ptr<unsigned char, void (*)(void*)> guard(memory, std::free);
    write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(memory), size));
}

Image read_exr(const std::string& path) {
    // The header first: refuse multi-part, deep and huge images before
    // decoding anything.
    EXRVersion version;
    int status = ParseEXRVersionFromFile(&version, path.c_str());
    if (status != TINYEXR_SUCCESS) {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw InputError("cannot read " + path + ": " + std::strerror(errno));
        std::fclose(f);
        throw InputError(path + ": not an OpenEXR image (bad magic number or version)");
    }
    if (version.multipart || version.non_image)
        throw InputError(path + ": multi-part and deep OpenEXR files are not supported (expected one RGB image)");
    EXRHeader header;
    InitEXRHeader(&header);
    const char* message = nullptr;
    if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &message) != TINYEXR_SUCCESS)
        throw InputError(path + ": unreadable OpenEXR header: " + take_message(message));
    const EXRBox2i& window = header.data_window;
    double width = double(window.max_x) - window.min_x + 1, height = double(window.max_y) - window.min_y + 1;
    FreeEXRHeader(&header);
    if (!(width >= 1 && height >= 1 && width * height <= kMaxPixels))
        throw InputError(path + ": OpenEXR data window of " + std::to_string(long(width)) + " x " +
                         std::to_string(long(height)) + " pixels (expected 1 to 67108864 pixels)");

    float* rgba = nullptr;
    int w = 0, h = 0;
    if (LoadEXR(&rgba, &w, &h, path.c_str(), &message) != TINYEXR_SUCCESS)
        throw InputError(path + ": cannot decode OpenEXR image: " + take_message(message));
    std::unique_ptr<float, void (*)(void*)> guard(rgba, std::free);
    Image image(w, h);
    std::vector<float>& data = image.data();
    for (size_t i = 0; i < image.pixel_count(); ++i) {
        for (int c = 0; c < 3; ++c) {
            float v = rgba[4 * i + size_t(c)];
            if (!std::isfinite(v))
                throw InputError(path + ": pixel (" + std::to_string(i % size_t(w)) + ", " +
                                 std::to_string(i / size_t(w)) + ") is not finite");
            data[3 * i + size_t(c)] = v;
        }
    }
    return image;
}

}  // namespace pt
