// float4.h — a host vector as the devices' padded 4-float type (shared/fen_types.h fen_float4),
// its fourth component given: how every shared layout that holds a point or a direction is filled.
#pragma once

#include <glm/vec3.hpp>

#include "shared/fen_types.h"

namespace fen {

inline dev::fen_float4 toFloat4(const glm::dvec3& v, double w)
{
    return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z), static_cast<float>(w)};
}

}  // namespace fen
