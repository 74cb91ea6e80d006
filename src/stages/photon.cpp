// Reference implementation of stage `photon` (stages/photon.h): emission
// by equation 2 and the density estimate of equation 1. The kd-tree's
// reference is in stages/kdtree.cpp.
#include "stages/photon.h"

#include <cmath>

#include "core/math.h"
#include "scene/light_set.h"

namespace pt::reference {

EmittedPhoton emit_photon(const Light& light, double light_probability, uint64_t count, Vec2 u_pos, Vec2 u_dir) {
    LightEmission e = light.sample_Le(u_pos, u_dir);
    EmittedPhoton photon;
    if (!e.valid() || !(light_probability > 0) || count == 0) return photon;
    photon.ray = e.ray();
    // Equation 2: LightEmission::flux is Le |cos| / (pdf_pos pdf_dir).
    photon.flux = e.flux() / (light_probability * double(count));
    photon.valid = true;
    return photon;
}

Color density_estimate(const std::vector<PhotonContribution>& found, double radius2, PhotonKernel kernel) {
    if (found.empty() || !(radius2 > 0)) return Color(0);
    Color sum;
    for (const PhotonContribution& c : found) {
        const double s2 = c.dist2 / radius2;  // (d / r)^2, in [0, 1]
        double w = 1;
        switch (kernel) {
            case PhotonKernel::box: w = 1; break;
            case PhotonKernel::cone: w = 3 * (1 - std::sqrt(s2)); break;        // integral over the disk: pi r^2
            case PhotonKernel::epanechnikov: w = 2 * (1 - s2); break;  // the same
        }
        sum += c.weighted_flux * w;
    }
    return sum / (kPi * radius2);
}

}  // namespace pt::reference
