// DensityGrid: the density of a heterogeneous medium on a regular grid of
// points spanning a box, read from a small text file that anyone can write
// (the generator `make_cloud` writes assets/media/cloud.grid):
//
//     ptgrid 1                     magic word and format version
//     NX NY NZ                     points per axis, each 2 to 512
//     XMIN YMIN ZMIN XMAX YMAX ZMAX the box, scene units (world space)
//     d d d ...                    NX*NY*NZ densities >= 0, x fastest, then y, then z
//
// Lines starting with '#' are comments. Point (i, j, k) sits at
// min + (i / (NX-1), j / (NY-1), k / (NZ-1)) * (max - min); between points
// the density is trilinear, and outside the box it is 0. The medium's
// coefficients are multiplied by it (scene/medium.h), so a density of 1
// gives the material's sigma_a and sigma_s.
//
// Tests: tests/unit/test_media_scene.cpp (values, interpolation, every
// malformed file's message).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/bbox.h"
#include "core/vec3.h"

namespace pt {

class DensityGrid {
  public:
    /// A grid of nx * ny * nz densities (x fastest) over `bounds`.
    DensityGrid(int nx, int ny, int nz, const BBox& bounds, std::vector<float> values);

    /// The trilinear density at world point p; 0 outside the box.
    double density(const Vec3& p) const;
    /// The largest density anywhere (the majorant of delta tracking).
    double max_density() const { return max_density_; }
    const BBox& bounds() const { return bounds_; }
    int nx() const { return nx_; }
    int ny() const { return ny_; }
    int nz() const { return nz_; }

  private:
    double at(int i, int j, int k) const { return values_[(size_t(k) * ny_ + j) * nx_ + i]; }

    int nx_, ny_, nz_;            ///< points per axis, >= 2
    BBox bounds_;                 ///< world-space box the points span
    std::vector<float> values_;   ///< densities, x fastest
    double max_density_ = 0;      ///< max of values_
};

/// Reads a grid file (format above); throws InputError "WHERE: FILE: line N:
/// what was expected" for anything malformed (bad magic, sizes, a negative
/// or non-finite density, too few or too many values).
DensityGrid load_density_grid(const std::string& path, const std::string& where);

/// Writes `grid`-format text for the given values (used by make_cloud and the tests).
std::string density_grid_text(int nx, int ny, int nz, const BBox& bounds, const std::vector<float>& values,
                              const std::string& comment);

}  // namespace pt
