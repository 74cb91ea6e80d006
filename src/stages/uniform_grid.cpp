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

class UniformGrid final : public Accelerator {
  public:
    UniformGrid(const Scene& scene, const IntersectStage& stage) : scene_(scene), stage_(stage) {
        const uint32_t n = scene.primitive_count();
        if (n == 0) return;
        for (uint32_t p = 0; p < n; ++p)
            bounds_.expand(padded_primitive_bounds(scene, p));
        const double margin = insertion_margin(bounds_);
        bounds_ = BBox(bounds_.min - Vec3(2 * margin), bounds_.max + Vec3(2 * margin));

        // ~3 cbrt(n) cells along the longest axis, the others in proportion.
        Vec3 extent = bounds_.extent();
        double longest = std::max({extent.x, extent.y, extent.z});
        double per_unit = 3.0 * std::cbrt(double(n)) / longest;
        for (int a = 0; a < 3; ++a) {
            res_[a] = std::clamp(int(std::lround(extent[a] * per_unit)), 1, kMaxCellsPerAxis);
            cell_[a] = extent[a] / res_[a];
            inv_cell_[a] = 1.0 / cell_[a];
        }

        // Two passes (count, then fill) into one array of references per
        // cell, cells stored consecutively: cell c's primitives are
        // refs_[start_[c], start_[c + 1]).
        start_.assign(size_t(res_[0]) * res_[1] * res_[2] + 1, 0);
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

    std::optional<Hit> intersect(const Ray& ray) const override {
        ClosestHit closest(ray);
        Mailbox mailbox;
        uint64_t tests = 0;
        walk(ray, [&](size_t c, double t_exit) {
            for (uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
                uint32_t p = refs_[i];
                if (mailbox.seen(p)) continue;
                ++tests;
                closest.offer(intersect_primitive(scene_, stage_, p, closest.ray));
            }
            // A hit beyond this cell could still be beaten by a primitive
            // of a later cell; one within it cannot.
            return !(closest.best && closest.best->t <= t_exit);
        });
        thread_counters().primitive_tests += tests;
        return closest.best;
    }

    bool occluded(const Ray& ray) const override {
        Mailbox mailbox;
        uint64_t tests = 0;
        bool hit = false;
        walk(ray, [&](size_t c, double) {
            for (uint32_t i = start_[c]; i < start_[c + 1] && !hit; ++i) {
                uint32_t p = refs_[i];
                if (mailbox.seen(p)) continue;
                ++tests;
                hit = intersect_primitive(scene_, stage_, p, ray).has_value();
            }
            return !hit;
        });
        thread_counters().primitive_tests += tests;
        return hit;
    }

    AcceleratorInfo info() const override {
        uint64_t bytes = start_.size() * sizeof(uint32_t) + refs_.size() * sizeof(uint32_t);
        return {"grid", uint64_t(start_.empty() ? 0 : start_.size() - 1), 0, bytes, bytes};
    }

  private:
    int cell_index(double x, int a) const {
        double i = std::floor((x - bounds_.min[a]) * inv_cell_[a]);
        return int(std::clamp(i, 0.0, double(res_[a] - 1)));
    }
    size_t offset(int x, int y, int z) const { return (size_t(z) * res_[1] + y) * res_[0] + x; }

    /// The 3D-DDA: calls visit(cell, t_exit) for every cell the ray crosses
    /// within [t_min, t_max], in order, until visit returns false. t_exit is
    /// where the ray leaves the cell (recomputed from the cell's planes at
    /// each step rather than accumulated, so no error builds up).
    template <class Visit>
    void walk(const Ray& ray, Visit visit) const {
        double t0, t1;
        if (start_.empty() || !clip_ray(bounds_, ray, t0, t1)) return;
        Vec3 p = ray.at(t0);
        int cell[3], step[3], out[3];
        double t_next[3];
        for (int a = 0; a < 3; ++a) {
            cell[a] = cell_index(p[a], a);
            if (ray.d[a] > 0) {
                step[a] = 1;
                out[a] = res_[a];
            } else if (ray.d[a] < 0) {
                step[a] = -1;
                out[a] = -1;
            } else {
                step[a] = 0;
                out[a] = -2;  // never reached
            }
            t_next[a] = next_crossing(ray, cell[a], step[a], a);
        }
        uint64_t visited = 0;
        for (;;) {
            int a = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
            double t_exit = std::min(t_next[a], t1);
            ++visited;
            if (!visit(offset(cell[0], cell[1], cell[2]), t_exit) || t_next[a] >= t1) break;
            cell[a] += step[a];
            if (cell[a] == out[a]) break;
            t_next[a] = next_crossing(ray, cell[a], step[a], a);
        }
        thread_counters().nodes_visited += visited;
    }

    /// Where the ray crosses the plane through which it leaves cell i along axis a.
    double next_crossing(const Ray& ray, int i, int step, int a) const {
        if (step == 0) return kInfinity;
        double plane = bounds_.min[a] + (step > 0 ? i + 1 : i) * cell_[a];
        return (plane - ray.o[a]) / ray.d[a];
    }

    const Scene& scene_;
    IntersectStage stage_;
    BBox bounds_;                ///< the grid's box: all primitives, plus a margin
    int res_[3] = {0, 0, 0};     ///< cells per axis
    double cell_[3] = {0, 0, 0};      ///< cell size per axis
    double inv_cell_[3] = {0, 0, 0};  ///< 1 / cell size
    std::vector<uint32_t> start_;  ///< per cell, its first reference; one more at the end
    std::vector<uint32_t> refs_;   ///< primitive ids, cell by cell
};

}  // namespace

std::unique_ptr<Accelerator> make_uniform_grid(const Scene& scene, const IntersectStage& stage) {
    return std::make_unique<UniformGrid>(scene, stage);
}

}  // namespace pt
