// make_cloud: writes the density grid of one cumulus-like cloud
// (scene/density_grid.h's text format), so the project ships a
// heterogeneous medium without downloading one.
//   make_cloud OUT.grid [NX NY NZ SEED]
//
// The cloud is a union of soft spheres (a flat-bottomed heap of "puffs",
// the larger ones in the middle) whose edge is roughened by three octaves of
// value noise; densities are in [0, 1], 0 outside the heap, and the grid
// spans the box [-1.5, 0, -1] .. [1.5, 1.5, 1] (scene units).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "apps/number_flags.h"
#include "apps/tool_main.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/rng.h"
#include "scene/density_grid.h"

namespace {

const char* kUsage =
    "usage: make_cloud OUT.grid [NX NY NZ SEED]\n"
    "Writes the density grid of one cloud (a heap of soft puffs with a noisy edge) over the box\n"
    "[-1.5, 0, -1] .. [1.5, 1.5, 1], in the text format of src/scene/density_grid.h.\n"
    "Defaults: 48 24 32 7. assets/media/cloud.grid is `make_cloud assets/media/cloud.grid`.\n"
    "exit codes: 0 ok, 2 bad input\n";

/// Value noise in [0, 1]: trilinear between hashed lattice values, smoothstepped.
double value_noise(double x, double y, double z, uint64_t seed) {
    auto lattice = [&](int i, int j, int k) {
        uint64_t h = pt::mix_bits(seed ^ (uint64_t(uint32_t(i)) * 73856093u) ^ (uint64_t(uint32_t(j)) * 19349663u) ^
                                  (uint64_t(uint32_t(k)) * 83492791u));
        return double(h >> 11) * 0x1p-53;
    };
    int i = int(std::floor(x)), j = int(std::floor(y)), k = int(std::floor(z));
    auto smooth = [](double t) { return t * t * (3 - 2 * t); };
    double fx = smooth(x - i), fy = smooth(y - j), fz = smooth(z - k);
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    double c00 = lerp(lattice(i, j, k), lattice(i + 1, j, k), fx);
    double c10 = lerp(lattice(i, j + 1, k), lattice(i + 1, j + 1, k), fx);
    double c01 = lerp(lattice(i, j, k + 1), lattice(i + 1, j, k + 1), fx);
    double c11 = lerp(lattice(i, j + 1, k + 1), lattice(i + 1, j + 1, k + 1), fx);
    return lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
}

struct Puff {
    double x, y, z, r;
};

std::vector<float> cloud_densities(int nx, int ny, int nz, const pt::BBox& box, uint64_t seed) {
    // Puffs on a flat base, the larger ones near the middle.
    pt::Rng rng(seed);
    std::vector<Puff> puffs;
    for (int i = 0; i < 14; ++i) {
        double x = (rng.next_1d() - 0.5) * 1.9, z = (rng.next_1d() - 0.5) * 1.0;
        double r = 0.55 - 0.18 * std::fabs(x) + 0.1 * rng.next_1d();
        puffs.push_back({x, 0.25 + r * 0.8, z, r});
    }
    std::vector<float> values(size_t(nx) * ny * nz);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                pt::Vec3 p = box.min + pt::Vec3(double(i) / (nx - 1), double(j) / (ny - 1), double(k) / (nz - 1)) *
                                           box.extent();
                // Distance inside the nearest puff surface, in units of its radius.
                double inside = -1e9;
                for (const Puff& f : puffs) {
                    double d = std::sqrt((p.x - f.x) * (p.x - f.x) + (p.y - f.y) * (p.y - f.y) +
                                         (p.z - f.z) * (p.z - f.z));
                    inside = std::max(inside, 1.0 - d / f.r);
                }
                double noise = 0, amplitude = 0.5, frequency = 3.0;
                for (int octave = 0; octave < 3; ++octave, amplitude *= 0.5, frequency *= 2.0)
                    noise += amplitude * value_noise(p.x * frequency, p.y * frequency, p.z * frequency, seed + octave);
                // A flat base: the density fades over the bottom 0.15 units.
                double base = std::clamp((p.y - 0.1) / 0.15, 0.0, 1.0);
                double d = std::clamp((inside + 0.35 * (noise - 0.45)) * 4.0, 0.0, 1.0) * base;
                values[(size_t(k) * ny + j) * nx + i] = float(d);
            }
    return values;
}

int run(const std::vector<std::string>& args) {
    for (const std::string& a : args)
        if (a == "-h" || a == "--help") {
            std::cout << kUsage;
            return pt::kExitOk;
        }
    if (args.size() != 1 && args.size() != 5)
        throw pt::InputError("expected OUT.grid and optionally NX NY NZ SEED, got " + std::to_string(args.size()) +
                             " arguments (make_cloud --help)");
    if (args[0].size() > 1 && args[0][0] == '-') throw pt::InputError(args[0] + ": unknown option (make_cloud --help)");
    const bool sized = args.size() == 5;
    int nx = sized ? int(pt::parse_whole_number("NX", args[1], 2, 512)) : 48;
    int ny = sized ? int(pt::parse_whole_number("NY", args[2], 2, 512)) : 24;
    int nz = sized ? int(pt::parse_whole_number("NZ", args[3], 2, 512)) : 32;
    uint64_t seed = sized ? pt::parse_whole_number("SEED", args[4], 0, 1u << 30) : 7;
    pt::BBox box(pt::Vec3(-1.5, 0, -1), pt::Vec3(1.5, 1.5, 1));
    pt::check_output_path(args[0], "the grid");
    pt::write_file_atomically(args[0], pt::density_grid_text(nx, ny, nz, box, cloud_densities(nx, ny, nz, box, seed),
                                                             "written by make_cloud (src/apps/make_cloud_main.cpp)"));
    std::cout << "make_cloud: wrote " << args[0] << " (" << nx << "x" << ny << "x" << nz << " densities)\n";
    return pt::kExitOk;
}

}  // namespace

int main(int argc, char** argv) { return pt::run_tool("make_cloud", argc, argv, run); }
