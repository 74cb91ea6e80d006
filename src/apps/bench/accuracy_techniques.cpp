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

/// --sampler K.
template <SamplerKind K>
void use_sampler(TechniqueConfig& c) {
    c.settings.sampler = K;
}

/// --adaptive cs184: Part 5's rule, which decides from the samples it averages.
void adaptive_cs184(TechniqueConfig& c) {
    c.settings.adaptive = true;
    c.settings.adaptive_rule = AdaptiveRule::cs184;
}

/// -m D: a hard cap of D bounces.
template <int D>
void cap_depth(TechniqueConfig& c) {
    c.settings.max_depth = D;
}

const std::vector<Technique>& all_techniques() {
    static const std::vector<Technique> techniques = {
        {"hemisphere", "light at each vertex by uniform hemisphere sampling (-H)", "light",
         [](TechniqueConfig& c) { c.settings.direct = DirectStrategy::hemisphere; }},
        {"light", "light sampling at each vertex; uniform spp; BVH (the baseline)", "",
         [](TechniqueConfig&) {}},
        {"mis", "MIS of light and BSDF samples at each vertex (--direct mis)", "light",
         [](TechniqueConfig& c) { c.settings.direct = DirectStrategy::mis; }},
        {"mis-balance", "MIS weighted by the balance heuristic (--direct mis --mis-heuristic balance)", "mis",
         [](TechniqueConfig& c) {
             c.settings.direct = DirectStrategy::mis;
             c.settings.mis_heuristic = MisHeuristic::balance;
         }},
        {"adaptive", "adaptive sampling (-a, --adaptive split: unbiased), -s is the maximum", "light",
         [](TechniqueConfig& c) {
             c.settings.adaptive = true;
             c.settings.adaptive_rule = AdaptiveRule::split;
         }},
        {"adaptive-cs184", "adaptive sampling with Part 5's rule (--adaptive cs184): biased", "adaptive",
         adaptive_cs184},
        {"adaptive-noguard", "--adaptive cs184 without the rare-event guard (CS184's textbook rule)",
         "adaptive-cs184",
         [](TechniqueConfig& c) {
             adaptive_cs184(c);
             c.stages.adaptive.has_converged = textbook_has_converged;
         }},
        {"tracking-delta", "shadow rays through density grids by delta tracking (--transmittance delta)", "light",
         [](TechniqueConfig& c) { c.settings.delta_tracking_shadows = true; }},
        {"rr-off", "no Russian roulette (--rr-depth off): paths end only at -m or a miss", "light",
         [](TechniqueConfig& c) { c.settings.russian_roulette = false; }, true},
        {"linear-scan", "no BVH: every ray tests every primitive (--accel none)", "light",
         [](TechniqueConfig& c) { c.accelerator.kind = AccelKind::none; }},
        {"depth-1", "-m 1: at most 1 bounce (biased against the baseline's -m)", "light",
         cap_depth<1>, true},
        {"depth-2", "-m 2: at most 2 bounces", "light", cap_depth<2>, true},
        {"depth-3", "-m 3: at most 3 bounces", "light", cap_depth<3>, true},
        {"depth-4", "-m 4: at most 4 bounces", "light", cap_depth<4>, true},
        {"depth-5", "-m 5: at most 5 bounces", "light", cap_depth<5>, true},
        {"depth-6", "-m 6: at most 6 bounces", "light", cap_depth<6>, true},
        {"depth-7", "-m 7: at most 7 bounces", "light", cap_depth<7>, true},
        {"depth-8", "-m 8: at most 8 bounces", "light", cap_depth<8>, true},
        {"path", "the path tracer (--integrator path), also where auto picks photon mapping", "light",
         [](TechniqueConfig& c) { c.settings.integrator = IntegratorKind::path; }},
        {"bdpt", "bidirectional path tracing (--integrator bdpt): every strategy (s, t), MIS", "path",
         [](TechniqueConfig& c) { c.settings.integrator = IntegratorKind::bdpt; }},
        {"pm", "photon mapping (--integrator pm, 200000 + 200000 photons): biased, error floor", "path",
         [](TechniqueConfig& c) { c.settings.integrator = IntegratorKind::pm; }},
        {"sppm", "progressive photon mapping (--integrator sppm), one pass per spp, one photon per pixel per pass", "path",
         [](TechniqueConfig& c) { c.settings.integrator = IntegratorKind::sppm; }},
        {"sampler-independent", "--sampler independent: PCG32 per (seed, pixel, sample)", "light",
         use_sampler<SamplerKind::independent>, false, -1, -1},
        {"sampler-stratified", "--sampler stratified: jittered strata per pixel and dimension", "light",
         use_sampler<SamplerKind::stratified>, false, -2, -1.5},
        {"sampler-halton", "--sampler halton: Halton over the image, random digit permutations", "light",
         use_sampler<SamplerKind::halton>, false, -2, -1.5},
        {"sampler-sobol", "--sampler sobol: Sobol over the image, Owen-scrambled, padded", "light",
         use_sampler<SamplerKind::sobol>, false, -3, -1.5},
        {"sampler-zsobol", "--sampler zsobol: Morton-ordered Owen-scrambled Sobol (blue-noise error)", "light",
         use_sampler<SamplerKind::zsobol>, false, -3, -1.5},
    };
    return techniques;
}

std::vector<std::string> sampler_technique_names() {
    std::vector<std::string> names;
    for (SamplerKind kind : all_sampler_kinds()) names.push_back(std::string("sampler-") + to_string(kind));
    return names;
}

std::vector<Technique> select_techniques(const std::string& list) {
    const std::vector<Technique>& all = all_techniques();
    if (list == "all") return all;
    std::vector<std::string> names;
    size_t start = 0;
    while (start <= list.size()) {
        size_t comma = list.find(',', start);
        if (comma == std::string::npos) comma = list.size();
        std::string name = list.substr(start, comma - start);
        if (name == "samplers") {
            for (const std::string& s : sampler_technique_names()) names.push_back(s);
        } else {
            names.push_back(name);
        }
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
                             "' (expected all, samplers, or some of: " + known + ")");
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
