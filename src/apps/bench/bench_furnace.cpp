// bench furnace: the white-furnace energy of the glossy BSDFs. For each
// microfacet model (GGX, Beckmann, Blinn-Phong), each roughness and each
// angle, the directional albedo E[f |cos| / pdf] of a perfect conductor
// (F = 1) and of a clear rough dielectric (ior 1.5, reflected plus
// refracted energy, entering and leaving), estimated by the BSDF's own
// sampling. Single scattering loses what would bounce between facets: the
// table reports 1 - albedo, the energy lost (docs/materials.md).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/bench/bench_command.h"
#include "apps/number_flags.h"
#include "core/error.h"
#include "scene/material.h"
#include "scene/microfacet_bsdf.h"

namespace pt::bench {
namespace {

const char* kUsage = "furnace [--samples N]";

int run_furnace(const std::vector<std::string>& args) {
    int samples = 1000000;
    for (const std::string& a : args)
        if (a == "-h" || a == "--help") {
            std::printf("usage: bench %s\n", kUsage);
            return 0;
        }
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--samples" && i + 1 < args.size()) samples = int(parse_whole_number("--samples", args[++i], 1000, 1 << 30));
        else throw InputError("bench furnace: unexpected argument '" + args[i] + "' (usage: bench " + kUsage + ")");
    }
    std::printf("Energy lost, 1 - albedo (in %%), %d samples per cell; standard errors below 0.1%%.\n"
                "Blinn-Phong's exponent is 2 / alpha^2 - 2 (Walter et al. 2007).\n\n", samples);
    const double alphas[] = {0.1, 0.3, 0.5, 0.7, 1.0};
    const double cosines[] = {1.0, 0.5, 0.1};
    uint64_t seed = 0;
    for (MaterialType type : {MaterialType::microfacet, MaterialType::rough_dielectric}) {
        for (double side : {1.0, -1.0}) {
            if (type == MaterialType::microfacet && side < 0) continue;
            std::printf("%s%s\n\n| model | cos_o |", type == MaterialType::microfacet ? "Rough conductor, F = 1" : "Rough dielectric, ior 1.5, ",
                        type == MaterialType::microfacet ? "" : (side > 0 ? "entering (from outside)" : "leaving (from inside)"));
            for (double a : alphas) std::printf(" alpha %.1f |", a);
            std::printf("\n|---|---|");
            for (size_t i = 0; i < std::size(alphas); ++i) std::printf("--:|");
            std::printf("\n");
            for (MicrofacetModel model : {MicrofacetModel::ggx, MicrofacetModel::beckmann, MicrofacetModel::blinn_phong}) {
                for (double c : cosines) {
                    std::printf("| %s | %.1f |", to_string(model), c);
                    for (double a : alphas) {
                        Material m;
                        m.type = type;
                        m.distribution = model;
                        m.roughness = a;
                        m.exponent = 2.0 / (a * a) - 2.0;
                        m.ior = 1.5;
                        m.eta = Color(1);
                        m.k = Color(1e4);  // F = 1 for the conductor
                        Vec3 wo(std::sqrt(1 - c * c), 0, side * c);
                        double mean = rough_albedo(m, wo, samples, ++seed).mean;
                        std::printf(" %.1f |", 100.0 * (1.0 - mean) + 0.0);  // + 0.0: no "-0.0"
                    }
                    std::printf("\n");
                }
            }
            std::printf("\n");
        }
    }
    return 0;
}

const BenchCommandRegistration kRegistration({"furnace", kUsage,
                                              "white-furnace energy lost by each glossy BSDF, by roughness and angle",
                                              run_furnace});

}  // namespace
}  // namespace pt::bench
