#include "stages/uniform_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/counters.h"
#include "scene/scene.h"
#include "stages/spatial_subdivision.h"

namespace pt {
namespace {

constexpr int kMaxCellsPerAxis = 256;

/// Primitives already tested by the current ray (hashed by id; a collision
/// only costs a repeated test).
struct Mailbox {
    std::array<uint32_t, 64> ids;
    Mailbox() { ids.fill(UINT32_MAX); }
    /// Whether `prim` was tested already; records it if not.
    bool seen(uint32_t prim) {
        uint32_t& slot = ids[prim & 63];
        if (slot == prim) return true;
        slot = prim;
        return false;
    }
};

/// Where the ray crosses the plane through which it leaves cell i along axis a.
double next_crossing(const GridCells& g, const Ray& ray, int i, int step, int a) {
    if (step == 0) return kInfinity;
    double plane = g.bounds.min[a] + (step > 0 ? i + 1 : i) * g.cell_size[a];
    return (plane - ray.o[a]) / ray.d[a];
}

/// The 3D-DDA: calls visit(cell, t_exit) for every cell the ray crosses
/// within [t_min, t_max], in order, until visit returns false. t_exit is
/// where the ray leaves the cell (recomputed from the cell's planes at
/// each step rather than accumulated, so no error builds up).
template <class Visit>
void walk(const GridCells& g, const Ray& ray, Visit visit) {
    double t0, t1;
    if (g.empty() || !clip_ray(g.bounds, ray, t0, t1)) return;
    Vec3 p = ray.at(t0);
    int cell[3], step[3], out[3];
    double t_next[3];
    for (int a = 0; a < 3; ++a) {
        cell[a] = g.cell_index(p[a], a);
        if (ray.d[a] > 0) {
            step[a] = 1;
            out[a] = g.res[a];
        } else if (ray.d[a] < 0) {
            step[a] = -1;
            out[a] = -1;
        } else {
            step[a] = 0;
            out[a] = -2;  // never reached
        }
        t_next[a] = next_crossing(g, ray, cell[a], step[a], a);
    }
    uint64_t visited = 0;
    for (;;) {
        int a = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
        double t_exit = std::min(t_next[a], t1);
        ++visited;
        if (!visit(g.offset(cell[0], cell[1], cell[2]), t_exit) || t_next[a] >= t1) break;
        cell[a] += step[a];
        if (cell[a] == out[a]) break;
        t_next[a] = next_crossing(g, ray, cell[a], step[a], a);
    }
    thread_counters().nodes_visited += visited;
}

class UniformGrid final : public Accelerator {
  public:
    UniformGrid(const Scene& scene, const IntersectStage& stage, GridIntersectFn intersect)
        : grid_(scene, stage), intersect_(intersect) {}

    std::optional<Hit> intersect(const Ray& ray) const override { return intersect_(grid_, ray); }

    bool occluded(const Ray& ray) const override {
        Mailbox mailbox;
        uint64_t tests = 0;
        bool hit = false;
        const std::vector<uint32_t>& start = grid_.starts();
        const std::vector<uint32_t>& refs = grid_.refs();
        walk(grid_, ray, [&](size_t c, double) {
            for (uint32_t i = start[c]; i < start[c + 1] && !hit; ++i) {
                uint32_t p = refs[i];
                if (mailbox.seen(p)) continue;
                ++tests;
                hit = grid_.intersect_primitive(p, ray).has_value();
            }
            return !hit;
        });
        thread_counters().primitive_tests += tests;
        return hit;
    }

    AcceleratorInfo info() const override {
        const size_t cells = grid_.starts().size();
        uint64_t bytes = cells * sizeof(uint32_t) + grid_.refs().size() * sizeof(uint32_t);
        return {"grid", uint64_t(cells == 0 ? 0 : cells - 1), 0, bytes, bytes};
    }

  private:
    GridCells grid_;
    GridIntersectFn intersect_;
};

}  // namespace

GridCells::GridCells(const Scene& scene, const IntersectStage& stage) : scene_(scene), stage_(stage) {
    const uint32_t n = scene.primitive_count();
    if (n == 0) return;
    for (uint32_t p = 0; p < n; ++p)
        bounds.expand(padded_primitive_bounds(scene, p));
    const double margin = insertion_margin(bounds);
    bounds = BBox(bounds.min - Vec3(2 * margin), bounds.max + Vec3(2 * margin));

    // ~3 cbrt(n) cells along the longest axis, the others in proportion.
    Vec3 extent = bounds.extent();
    double longest = std::max({extent.x, extent.y, extent.z});
    double per_unit = 3.0 * std::cbrt(double(n)) / longest;
    for (int a = 0; a < 3; ++a) {
        res[a] = std::clamp(int(std::lround(extent[a] * per_unit)), 1, kMaxCellsPerAxis);
        cell_size[a] = extent[a] / res[a];
        inv_cell_[a] = 1.0 / cell_size[a];
    }

    // Two passes (count, then fill) into one array of references per
    // cell, cells stored consecutively.
    start_.assign(size_t(res[0]) * res[1] * res[2] + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<uint32_t> fill;
        if (pass == 1) {
            for (size_t c = 1; c < start_.size(); ++c)
                start_[c] += start_[c - 1];
            refs_.resize(start_.back());
            fill.assign(start_.begin(), start_.end() - 1);
        }
        for (uint32_t p = 0; p < n; ++p) {
            BBox b = insertion_bounds(scene, p, margin);
            int lo[3], hi[3];
            for (int a = 0; a < 3; ++a) {
                lo[a] = cell_index(b.min[a], a);
                hi[a] = cell_index(b.max[a], a);
            }
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) {
                        size_t c = offset(x, y, z);
                        if (pass == 0)
                            ++start_[c + 1];
                        else
                            refs_[fill[c]++] = p;
                    }
        }
    }
}

int GridCells::cell_index(double x, int a) const {
    double i = std::floor((x - bounds.min[a]) * inv_cell_[a]);
    return int(std::clamp(i, 0.0, double(std::max(res[a] - 1, 0))));
}

const uint32_t* GridCells::cell_primitives(int x, int y, int z, size_t& count) const {
    count = 0;
    if (empty() || x < 0 || y < 0 || z < 0 || x >= res[0] || y >= res[1] || z >= res[2]) return nullptr;
    size_t c = offset(x, y, z);
    count = start_[c + 1] - start_[c];
    return refs_.data() + start_[c];
}

std::optional<Hit> GridCells::intersect_primitive(uint32_t prim, const Ray& ray) const {
    return pt::intersect_primitive(scene_, stage_, prim, ray);
}

uint32_t GridCells::primitive_count() const { return scene_.primitive_count(); }

namespace reference {

std::optional<Hit> grid_intersect(const GridCells& grid, const Ray& ray) {
    ClosestHit closest(ray);
    Mailbox mailbox;
    uint64_t tests = 0;
    const std::vector<uint32_t>& start = grid.starts();
    const std::vector<uint32_t>& refs = grid.refs();
    walk(grid, ray, [&](size_t c, double t_exit) {
        for (uint32_t i = start[c]; i < start[c + 1]; ++i) {
            uint32_t p = refs[i];
            if (mailbox.seen(p)) continue;
            ++tests;
            closest.offer(grid.intersect_primitive(p, closest.ray));
        }
        // A hit beyond this cell could still be beaten by a primitive
        // of a later cell; one within it cannot.
        return !(closest.best && closest.best->t <= t_exit);
    });
    thread_counters().primitive_tests += tests;
    return closest.best;
}

}  // namespace reference

std::unique_ptr<Accelerator> make_uniform_grid(const Scene& scene, const IntersectStage& stage,
                                               GridIntersectFn intersect) {
    return std::make_unique<UniformGrid>(scene, stage, intersect);
}

}  // namespace pt
