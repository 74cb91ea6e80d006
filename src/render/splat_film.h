// SplatFilm: contributions that land on pixels other than the one being
// rendered (BDPT's light tracing, t = 1; stages/bdpt.h), kept per thread
// and merged so that the image is the same at any thread count.
//
// Floating-point sums depend on their order, and which thread splats what
// depends on scheduling. So each thread adds its splats in fixed point
// (64-bit integers, 2^-28 units of radiance): integer addition is
// associative, and the merged sums are exact whatever the order. A splat
// rounds to within 2^-29 (1.9e-9), far below any pixel's noise; a sum that
// would overflow (beyond 3.4e10) saturates.
//
// Normalisation (Veach 1997 section 10.3.4): the pixel importance is
// W_j = N We on pixel j, with We normalised over the whole film of N
// pixels, so M light paths estimate pixel j as (N / M) sum of the splats
// (the t = 1 contributions carry We). value() applies that factor.
//
// The integrator finds its thread's film through current_splat_film(),
// which render_image sets for every worker of an integrator that splats
// (Integrator::splat_layers); it is null elsewhere, where t = 1 strategies
// cannot be evaluated.
#pragma once

#include <cstdint>
#include <vector>

#include "core/color.h"
#include "core/vec3.h"

namespace pt {

class SplatFilm {
  public:
    /// `layers` images of width x height: layer 0 is the image's own splats,
    /// further layers are an integrator's extra images (BDPT's strategies).
    SplatFilm(int width, int height, int layers);

    /// Adds c to the pixel at normalised film position `film` ((0, 0) the
    /// bottom-left corner, generate_ray's coordinates); nothing off the film.
    void add(int layer, Vec2 film, const Color& c);
    /// One more light path (or camera sample) for the normalisation.
    void count_path() { ++paths_; }
    /// Adds another thread's film (exact: integer sums).
    void merge(const SplatFilm& other);

    int layers() const { return layers_; }
    uint64_t paths() const { return paths_; }
    /// The splats of pixel (x, y) of `layer` times (width height / paths), the
    /// estimate of that pixel (black before any path).
    Color value(int layer, int x, int y) const;

  private:
    int width_ = 0, height_ = 0, layers_ = 0;
    std::vector<int64_t> sums_;  ///< per layer, row-major pixel (y = 0 at the top), 3 channels; 2^-28 units
    uint64_t paths_ = 0;         ///< light paths traced into this film
};

/// The calling thread's film, or null.
SplatFilm* current_splat_film();
/// Sets (or, with null, clears) the calling thread's film.
void set_current_splat_film(SplatFilm* film);

}  // namespace pt
