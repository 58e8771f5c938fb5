// light_levels.h — how bright the scene's light is (DESIGN.md §3): the sun's normal illuminance,
// the factor that restores it for a disk sun, and the reference luminance that fixed-point
// scales are set against (the film's pixels, the adaptive strategy's statistics).
#pragma once

#include "scene/scene.h"
#include "sky/sky_tables.h"

namespace fen {

// The brightest plausible diffuse luminance of the scene (cd/m^2): what fixed-point scales are
// set against (max of E_sun / pi and the sky's brightest node).
double referenceLuminance(const Scene& scene, const SkyTables& sky);

// The normal illuminance of the sun as luminance-weighted lux (Y of its RGB; 0 without a sun).
double sunIlluminanceY_lux(const Scene& scene);

// A disk sun's directions are uniform in its cone, so a plane facing it receives E (1 + cos a) / 2
// per unit weight: this restores its normal illuminance E.
double sunConeFactor(const Sun& sun);

}  // namespace fen
