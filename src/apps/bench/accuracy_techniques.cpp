#include "apps/bench/accuracy_techniques.h"

#include <cmath>

#include "core/error.h"

namespace pt::bench {

bool textbook_has_converged(const PixelStatistics& stats, double max_tolerance) {
    if (stats.n < 2) return false;
    const double n = stats.n, mu = stats.s1 / n;
    const double variance = std::max(0.0, (stats.s2 - stats.s1 * stats.s1 / n) / (n - 1));
    return 1.96 * std::sqrt(variance / n) <= max_tolerance * mu;
}

const std::vector<Technique>& all_techniques() {
    // Part 4 (path tracing) will add, each one entry:
    //   {"rr-off", "path tracing without Russian roulette", "light", ...},
    //   {"depth-1" ... "depth-8", "-m 1" ... "-m 8", "light", ...}.
    static const std::vector<Technique> techniques = {
        {"hemisphere", "direct light: uniform hemisphere sampling (-H)", "light",
         [](TechniqueConfig& c) { c.settings.direct = DirectStrategy::hemisphere; }},
        {"light", "direct light: light sampling; uniform spp; BVH (the baseline)", "",
         [](TechniqueConfig&) {}},
        {"mis", "direct light: MIS, light and BSDF samples (--direct mis)", "light",
         [](TechniqueConfig& c) { c.settings.direct = DirectStrategy::mis; }},
        {"adaptive", "adaptive sampling (-a), -s is the maximum", "light",
         [](TechniqueConfig& c) { c.settings.adaptive = true; }},
        {"adaptive-noguard", "adaptive sampling without the rare-event guard (CS184's rule)",
         "adaptive",
         [](TechniqueConfig& c) {
             c.settings.adaptive = true;
             c.stages.adaptive.has_converged = textbook_has_converged;
         }},
        {"linear-scan", "no BVH: every ray tests every primitive (--accel none)", "light",
         [](TechniqueConfig& c) { c.accelerator.use_bvh = false; }},
    };
    return techniques;
}

std::vector<Technique> select_techniques(const std::string& list) {
    const std::vector<Technique>& all = all_techniques();
    if (list == "all") return all;
    std::vector<std::string> names;
    size_t start = 0;
    while (start <= list.size()) {
        size_t comma = list.find(',', start);
        if (comma == std::string::npos) comma = list.size();
        names.push_back(list.substr(start, comma - start));
        start = comma + 1;
    }
    std::string known;
    for (const Technique& t : all)
        known += (known.empty() ? "" : ", ") + t.name;
    for (const std::string& name : names) {
        bool found = false;
        for (const Technique& t : all)
            found = found || t.name == name;
        if (!found)
            throw InputError("accuracy: --techniques: unknown technique '" + name +
                             "' (expected all, or some of: " + known + ")");
    }
    std::vector<Technique> chosen;
    for (const Technique& t : all)
        for (const std::string& name : names)
            if (t.name == name) {
                chosen.push_back(t);
                break;
            }
    return chosen;
}

}  // namespace pt::bench
