// Part 2, task 6 (optional), written from the handout's steps: the 3D-DDA
// of Amanatides and Woo with tMax accumulated by tDelta and a mailbox of
// the primitives tested.
#include <cmath>
#include <unordered_set>

#include "stages/bvh.h"
#include "stages/uniform_grid.h"

namespace pt::student {

std::optional<Hit> grid_intersect(const GridCells& grid, const Ray& ray) {
    double t0 = ray.t_min, t1 = ray.t_max;
    if (grid.empty() || !bbox_intersect(grid.bounds, ray, t0, t1)) return std::nullopt;
    const Vec3 p = ray.at(t0);
    int cell[3], step[3];
    double t_max[3], t_delta[3];
    for (int a = 0; a < 3; ++a) {
        cell[a] = grid.cell_index(p[a], a);
        if (ray.d[a] == 0) {
            step[a] = 0, t_max[a] = t_delta[a] = INFINITY;
            continue;
        }
        step[a] = ray.d[a] > 0 ? 1 : -1;
        double plane = grid.bounds.min[a] + (cell[a] + (step[a] > 0 ? 1 : 0)) * grid.cell_size[a];
        t_max[a] = (plane - ray.o[a]) / ray.d[a];
        t_delta[a] = grid.cell_size[a] / std::fabs(ray.d[a]);
    }
    std::unordered_set<uint32_t> tested;
    std::optional<Hit> best;
    Ray r = ray;
    for (;;) {
        size_t n = 0;
        const uint32_t* prims = grid.cell_primitives(cell[0], cell[1], cell[2], n);
        for (size_t i = 0; i < n; ++i) {
            if (!tested.insert(prims[i]).second) continue;
            std::optional<Hit> h = grid.intersect_primitive(prims[i], r);
            if (h && BVHTree::closer(*h, best)) best = h, r.t_max = h->t;
        }
        int a = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
        if (best && best->t <= std::min(t_max[a], t1)) return best;
        if (t_max[a] > t1) return best;
        cell[a] += step[a];
        if (cell[a] < 0 || cell[a] >= grid.res[a]) return best;
        t_max[a] += t_delta[a];
    }
}

}  // namespace pt::student
