// sky_spec.h — the goniogram described by a scene's extras.sky (DESIGN.md §1, §6), and the
// ground's glow below the horizon.
#pragma once

#include <optional>

#include "scene/scene.h"
#include "sky/goniogram.h"

namespace fen {

// The scene's sky: its extras.sky (after the command line's changes) as a goniogram; none when the
// scene has no sky. With sky.groundAlbedo rho_g > 0 the table covers the whole sphere, the lower
// hemisphere glowing uniformly at L_g = rho_g E_h / pi (Radiance gensky's ground), E_h the
// unobstructed horizontal illuminance of the tabulated sky and of scene.sun (its normal
// illuminance's luminance times the sine of its altitude, 0 below the horizon); with rho_g = 0
// the table is the sky alone, exactly as without a ground. Errors name spec.where and the key.
std::optional<Goniogram> buildSky(const Scene& scene);

// The sky alone, for a spec without a ground (the ground needs the scene's sun: a spec with
// groundAlbedo > 0 is an error here; use buildSky(scene)).
std::optional<Goniogram> buildSky(const SkySpec& spec);

// The horizontal illuminance (lux) the ground reflects: the sky's (over its table) and the sun's.
double groundHorizontalIlluminance(const Goniogram& sky, const Sun& sun);

// Checks a ground albedo: a number in [0, 1]; else a one-line fen::Error "<what>: <value> is outside ...".
void checkGroundAlbedo(double albedo, const std::string& what);

}  // namespace fen
