// sky_spec.h — the goniogram described by a scene's extras.sky (DESIGN.md §1, §6).
#pragma once

#include <optional>

#include "scene/scene.h"
#include "sky/goniogram.h"

namespace fen {

// None when the scene has no sky. Errors name spec.where and the key.
std::optional<Goniogram> buildSky(const SkySpec& spec);

}  // namespace fen
