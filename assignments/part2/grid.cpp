// Part 2, task 6 (optional extension): walk a uniform grid with the 3D-DDA.
// Read the section "Optional: a uniform grid" of assignments/part2/README.md
// first; the contract is in src/stages/uniform_grid.h (GridCells,
// GridIntersectFn). The grid is built for you; `--accel grid` uses your walk.
//
// Until you write it, grid_intersect stops the program with "not
// implemented" when called (only `--accel grid` and `grade` call it).
#include "core/error.h"
#include "stages/uniform_grid.h"

namespace pt::student {

std::optional<Hit> grid_intersect(const GridCells& grid, const Ray& ray) {
    // TODO(part2.6): grid_intersect, as src/stages/uniform_grid.h states its contract.
    // [guided]
    // the closest hit, cell by cell (Amanatides and Woo 1987).
    //  1. Clip [ray.t_min, ray.t_max] to grid.bounds (your slab test works);
    //     on a miss there is no hit. The first cell is the one holding
    //     ray.at(t_entry) (grid.cell_index, per axis): the origin may be
    //     inside the grid, so t_entry is not always the box's entry.
    //  2. Per axis a: step = +1, -1 or 0 (d[a] == 0: the ray never leaves
    //     the slab of cells); tMax[a] = the t where the ray crosses the
    //     cell's far plane along a (the lower plane when step is -1,
    //     infinity when 0); tDelta[a] = cell_size[a] / |d[a]|.
    //  3. Loop: test the cell's primitives (grid.cell_primitives), skipping
    //     those this ray has tested already (mailboxing), keeping the
    //     closest hit (BVHTree::closer) and shrinking t_max to it. Stop if
    //     that hit lies within this cell (t <= the smallest tMax): a hit
    //     beyond it may be beaten by a primitive of the next cell. Else step
    //     along the axis of the smallest tMax; stop when the index leaves
    //     [0, res[a] - 1] or the ray's interval ends.
    // [/guided]
    (void)grid, (void)ray;
    throw NotImplemented(2, "6", "grid_intersect");
}

}  // namespace pt::student
