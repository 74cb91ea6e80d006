// The converged reference of `bench accuracy`: rendered once per scene and
// settings, and cached on disk.
//
// The reference is the baseline's settings with MIS for direct light (the
// most robust strategy; every strategy converges to the same image) at
// --reference-spp samples per pixel, rendered with the BVH in P passes of
// spp / P samples (P = 16 when spp allows, each pass at least 2 spp so that
// no pass shoots through pixel centres only). The spread of the P pass
// images estimates the reference's own error: its relMSE against the true
// image is about mean over pixels and channels of var(pass) / P / (b^2 +
// 0.01), which the table header reports. Every error in the table is
// inflated by about that much.
//
// Cache (under build/accuracy_cache/ unless --cache DIR): the file name is
// <scene>-<fingerprint>.pfm with a JSON sidecar (spp, seconds, settings)
// and a witness, a 2 spp render with a fixed seed. The fingerprint hashes
// kAccuracyCacheVersion, the scene path, the scene file's bytes, the loaded
// vertex positions, the resolution, the integrator and the settings, and
// the spp. The witness catches what the fingerprint cannot see (a changed
// material file, changed renderer code): it is rendered again on every run
// and must match the cached one bit for bit (renders are deterministic).
#pragma once

#include <ostream>
#include <string>

#include "image/image.h"
#include "stages/settings.h"

namespace pt {
struct Scene;
}

namespace pt::bench {

/// Bump to invalidate every cached accuracy reference at once.
constexpr const char* kAccuracyCacheVersion = "pt-accuracy-reference-1";

struct Reference {
    Image image;             ///< linear radiance, the film's size
    int spp = 0;             ///< samples per pixel; 0 when unknown (a given file without sidecar)
    double seconds = 0;      ///< time its render took; 0 when unknown
    double own_relmse = -1;  ///< estimated relMSE of the reference itself; < 0 when unknown
    std::string source;      ///< "cache", "rendered" or "file"
    std::string path;        ///< the PFM it was read from or cached as ("" uncached)
    std::string settings;    ///< the settings it was rendered with, in words
};

/// The reference of `scene` (film size already set) for the baseline
/// `settings`: from the cache in `cache_dir` when the fingerprint and the
/// witness match, else rendered (progress lines on `log`) and cached.
/// `cache_dir` empty: no cache.
Reference converged_reference(const Scene& scene, const RenderSettings& settings, int spp,
                              int threads, const std::string& cache_dir, std::ostream& log);

/// A reference given as a PFM file (--reference); its spp, seconds and own
/// error come from FILE.json beside it when there is one (the sidecar
/// that the cache writes). Throws InputError when the file cannot be read or
/// its size is not width x height.
Reference read_reference(const std::string& path, int width, int height);

}  // namespace pt::bench
