// Uniform grid (`--accel grid`): spatial subdivision into equal cells,
// traversed cell by cell along the ray with the 3D-DDA of Amanatides and
// Woo, "A Fast Voxel Traversal Algorithm for Ray Tracing" (Eurographics
// 1987). The course's counterpart to the BVH's object subdivision: cheap
// to build, fast on evenly spread triangles, slow on "a teapot in a
// stadium" (most cells empty, the teapot in a few of them).
//
// Resolution: about 3 cbrt(n) cells along the longest axis, the other axes
// in proportion (pbrt-v1's GridAccel; Cleary and Wyvill 1988), at most 256
// per axis. Each primitive is listed in every cell its box overlaps
// (grown by the margin of stages/spatial_subdivision.h), so a primitive
// can be met in several cells; mailboxing (Amanatides and Woo) remembers
// the primitives already tested by this ray in a small per-ray hash table
// (64 slots) and skips them. The closest hit stops at the first cell that
// ends beyond the closest hit found so far.
//
// Answers are exactly the linear scan's (same primitive, same t, ties to the
// larger id): the primitives are tested through the intersect stage.
//
// The closest-hit walk is also Part 2's optional task 6 (grid_intersect,
// assignments/part2/grid.cpp): the grader builds the GridCells below and
// compares the student's walk with brute force.
// Tests: tests/bvh/test_accel_agreement.cpp.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "core/bbox.h"
#include "stages/accelerator.h"

namespace pt {

/// A built uniform grid: the cells and the primitives listed in each.
/// Cell (x, y, z), 0 <= x < res[0] and so on, covers
/// [bounds.min + (x, y, z) * cell_size, bounds.min + (x + 1, y + 1, z + 1) * cell_size].
class GridCells {
  public:
    /// The grid over every primitive of `scene`, which are tested with `stage`.
    GridCells(const Scene& scene, const IntersectStage& stage);

    BBox bounds;                 ///< the grid's box: all primitives, plus a margin
    int res[3] = {0, 0, 0};      ///< cells per axis (all 0 for an empty scene)
    double cell_size[3] = {0, 0, 0};  ///< the size of a cell along each axis

    bool empty() const { return start_.empty(); }
    /// The cell index along axis `a` of coordinate x, clamped to [0, res[a] - 1].
    int cell_index(double x, int a) const;
    /// The ids of the primitives listed in cell (x, y, z) (each in range):
    /// cell_primitives(x, y, z)[0, count).
    const uint32_t* cell_primitives(int x, int y, int z, size_t& count) const;
    /// The closest hit of `ray` with primitive `prim` within [ray.t_min,
    /// ray.t_max], through the intersect stage; sets Hit::primitive.
    std::optional<Hit> intersect_primitive(uint32_t prim, const Ray& ray) const;
    /// Number of primitives in the scene (ids are 0 .. count - 1).
    uint32_t primitive_count() const;

    /// Internal layout (for the accelerator): cell c = (z * res[1] + y) *
    /// res[0] + x holds refs[start[c], start[c + 1]).
    size_t offset(int x, int y, int z) const { return (size_t(z) * res[1] + y) * res[0] + x; }
    const std::vector<uint32_t>& starts() const { return start_; }
    const std::vector<uint32_t>& refs() const { return refs_; }

  private:
    const Scene& scene_;
    IntersectStage stage_;
    double inv_cell_[3] = {0, 0, 0};
    std::vector<uint32_t> start_;  ///< per cell, its first reference; one more at the end
    std::vector<uint32_t> refs_;   ///< primitive ids, cell by cell
};

/// Part 2, task 6 (optional): the closest hit of `ray` within [ray.t_min,
/// ray.t_max] with the grid's primitives, found by walking the cells the
/// ray crosses in order (3D-DDA), with Hit::primitive set; nothing on a
/// miss. Ties at equal t go to the larger id (BVHTree::closer).
using GridIntersectFn = std::optional<Hit> (*)(const GridCells& grid, const Ray& ray);

namespace reference {
std::optional<Hit> grid_intersect(const GridCells& grid, const Ray& ray);
}  // namespace reference
namespace student {
std::optional<Hit> grid_intersect(const GridCells& grid, const Ray& ray);
}  // namespace student

/// The `--accel grid` accelerator; its closest hits come from `intersect`
/// (the bvh stage's grid_intersect: the reference's, or the student's).
std::unique_ptr<Accelerator> make_uniform_grid(const Scene& scene, const IntersectStage& stage,
                                               GridIntersectFn intersect = reference::grid_intersect);

}  // namespace pt
