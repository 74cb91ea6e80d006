// make_sky: writes the procedural sky environment map (a gradient, a dim
// ground and a small sun; scene/environment_map.h) as .hdr or .pfm, so the
// project ships an environment map without downloading one.
//   make_sky OUT.hdr [WIDTH HEIGHT SUN_ELEVATION SUN_AZIMUTH]
#include <iostream>
#include <string>
#include <vector>

#include "apps/number_flags.h"
#include "apps/tool_main.h"
#include "core/error.h"
#include "image/image_io.h"
#include "scene/environment_map.h"

namespace {

const char* kUsage =
    "usage: make_sky OUT.hdr|OUT.pfm [WIDTH HEIGHT SUN_ELEVATION_DEG SUN_AZIMUTH_DEG]\n"
    "Writes the procedural sky (a gradient, a dim ground and a small sun) as a lat-long\n"
    "environment map. Defaults: 256 128 35 -40. assets/env/sky.hdr is `make_sky assets/env/sky.hdr`.\n"
    "exit codes: 0 ok, 2 bad input\n";

int run(const std::vector<std::string>& args) {
    for (const std::string& a : args)
        if (a == "-h" || a == "--help") {
            std::cout << kUsage;
            return pt::kExitOk;
        }
    if (args.size() != 1 && args.size() != 5)
        throw pt::InputError("expected OUT.hdr and optionally WIDTH HEIGHT SUN_ELEVATION SUN_AZIMUTH, got " +
                             std::to_string(args.size()) + " arguments (make_sky --help)");
    if (args[0].size() > 1 && args[0][0] == '-') throw pt::InputError(args[0] + ": unknown option (make_sky --help)");
    const bool sized = args.size() == 5;
    int width = sized ? int(pt::parse_whole_number("WIDTH", args[1], 2, 16384)) : 256;
    int height = sized ? int(pt::parse_whole_number("HEIGHT", args[2], 2, 16384)) : 128;
    double elevation = sized ? pt::parse_real_number("SUN_ELEVATION", args[3], -90, 90) : 35;
    double azimuth = sized ? pt::parse_real_number("SUN_AZIMUTH", args[4], -360, 360) : -40;
    pt::write_image(pt::make_sky_image(width, height, elevation, azimuth), args[0]);
    std::cout << "make_sky: wrote " << args[0] << "\n";
    return pt::kExitOk;
}

}  // namespace

int main(int argc, char** argv) { return pt::run_tool("make_sky", argc, argv, run); }
