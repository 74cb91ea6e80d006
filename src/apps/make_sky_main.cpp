// make_sky: writes the procedural sky environment map (a gradient, a dim
// ground and a small sun; scene/environment_map.h) as .hdr or .pfm, so the
// project ships an environment map without downloading one.
//   make_sky OUT.hdr [WIDTH HEIGHT SUN_ELEVATION SUN_AZIMUTH]
#include <cstdlib>
#include <iostream>

#include "core/error.h"
#include "image/image_io.h"
#include "scene/environment_map.h"

int main(int argc, char** argv) {
    if (argc != 2 && argc != 6) {
        std::cerr << "usage: make_sky OUT.hdr|OUT.pfm [WIDTH HEIGHT SUN_ELEVATION_DEG SUN_AZIMUTH_DEG]\n";
        return pt::kExitBadInput;
    }
    int width = argc == 6 ? std::atoi(argv[2]) : 256, height = argc == 6 ? std::atoi(argv[3]) : 128;
    double elevation = argc == 6 ? std::atof(argv[4]) : 35, azimuth = argc == 6 ? std::atof(argv[5]) : -40;
    if (width < 2 || height < 2 || width > 16384 || height > 16384) {
        std::cerr << "make_sky: error: WIDTH and HEIGHT must be whole numbers in [2, 16384]\n";
        return pt::kExitBadInput;
    }
    try {
        pt::write_image(pt::make_sky_image(width, height, elevation, azimuth), argv[1]);
    } catch (const pt::InputError& e) {
        std::cerr << "make_sky: error: " << e.what() << "\n";
        return pt::kExitBadInput;
    }
    std::cout << "make_sky: wrote " << argv[1] << "\n";
    return 0;
}
