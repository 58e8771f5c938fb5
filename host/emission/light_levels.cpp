// light_levels.cpp — the sun's illuminance and the reference luminance (light_levels.h).
#include "emission/light_levels.h"

#include <algorithm>
#include <cmath>

namespace fen {

double sunIlluminanceY_lux(const Scene& scene)
{
    const glm::dvec3 E = scene.sun.present ? scene.sun.illuminanceRgb_lux : glm::dvec3(0.0);
    return 0.2126 * E.r + 0.7152 * E.g + 0.0722 * E.b;
}

double sunConeFactor(const Sun& sun) { return 2.0 / (1.0 + std::cos(sun.angularRadiusRad)); }

double referenceLuminance(const Scene& scene, const SkyTables& sky)
{
    return std::max({sunIlluminanceY_lux(scene) / M_PI, sky.maxLuminance_cd_m2, 1e-6});
}

}  // namespace fen
