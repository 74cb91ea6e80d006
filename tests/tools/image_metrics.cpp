// image_metrics: error of an image against a reference (image/metrics.h),
// for docs/global.md. Not a test.
//
//   image_metrics IMAGE REFERENCE      (PFM, PNG or HDR; compare PFMs)
//
// Prints "rmse R relmse E" and, per image, the mean of each channel.
#include <cstdio>

#include "core/error.h"
#include "image/image_io.h"
#include "image/metrics.h"

using namespace pt;

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s IMAGE REFERENCE\n", argv[0]);
        return 2;
    }
    try {
        Image a = read_image(argv[1]), b = read_image(argv[2]);
        if (a.width() != b.width() || a.height() != b.height()) {
            std::fprintf(stderr, "sizes differ: %dx%d and %dx%d\n", a.width(), a.height(),
                         b.width(), b.height());
            return 2;
        }
        std::printf("rmse %.6g relmse %.6g\n", rmse(a, b), relmse(a, b));
        for (const Image* image : {&a, &b}) {
            double sum[3] = {0, 0, 0};
            for (size_t i = 0; i < image->data().size(); ++i)
                sum[i % 3] += image->data()[i];
            double n = double(image->pixel_count());
            std::printf("mean %.6g %.6g %.6g\n", sum[0] / n, sum[1] / n, sum[2] / n);
        }
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    return 0;
}
