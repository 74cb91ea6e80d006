// The MIS weight of a BDPT strategy by the ratio recursion (stages/bdpt.h).
//
// For a path of n = s + t vertices x0 .. x(n-1) (x0 on the light), let p_i
// be the density of strategy (i, n - i). Moving the connection one vertex
// towards the camera swaps how vertex x_i is made: by the camera subpath
// (pdf_rev as the light path stores it) for the light subpath (pdf_fwd), so
//
//     p_(i+1) / p_i = pdf_fwd(x_i) / pdf_rev(x_i)       (Veach 1997 eq. 10.9)
//
// and, walking outwards from the strategy (s, t) actually used, each ratio
// r_i = p_i / p_s is a running product. The weight is then
//
//     w_s = 1 / sum_i (r_i)^b,   b = 1 (balance) or 2 (power heuristic),
//
// over the strategies that can make the path: none that must join an edge
// at a delta vertex (a mirror, glass, or a point or directional light, which
// no ray can hit), none with t = 0 (no ray hits the lens), and not (1, 1).
// Densities of 0 (delta bounces) count as 1 in the products, so that the
// vertex leaves the ratios unchanged (pbrt-v3's remap0).
#include "stages/bdpt.h"

namespace pt::reference {

double mis_weight(const MisVertex* light, int s, const MisVertex* camera, int t, bool delta_light,
                  MisHeuristic heuristic) {
    if (s + t == 2) return 1.0;
    auto remap0 = [](double pdf) { return pdf != 0 ? pdf : 1.0; };
    auto term = [heuristic](double r) { return heuristic == MisHeuristic::power ? r * r : r; };
    double sum = 0;
    // Towards the camera: camera vertex i joins the light subpath, strategy (s + t - i, i).
    double r = 1;
    for (int i = t - 1; i > 0; --i) {
        r *= remap0(camera[i].pdf_rev) / remap0(camera[i].pdf_fwd);
        if (!camera[i].delta && !camera[i - 1].delta) sum += term(r);
    }
    // Towards the light: light vertex i joins the camera subpath, strategy (i, s + t - i).
    r = 1;
    for (int i = s - 1; i >= 0; --i) {
        r *= remap0(light[i].pdf_rev) / remap0(light[i].pdf_fwd);
        const bool delta_before = i > 0 ? light[i - 1].delta : delta_light;
        const bool one_one = i == 1 && s + t - i == 1;
        if (!light[i].delta && !delta_before && !one_one) sum += term(r);
    }
    return 1.0 / (1.0 + sum);
}

}  // namespace pt::reference
