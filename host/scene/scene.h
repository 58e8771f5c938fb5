// scene.h — a scene as the renderer sees it: a triangle soup with, per triangle, the glTF node it
// came from. Loaded from glTF by gltf_load.h or built procedurally (host/bench/room_scene.h).
#pragma once

#include <string>
#include <vector>

#include "geometry.h"

namespace fen {

struct Scene {
    std::string source;                     // file path, or a name for procedural scenes
    std::vector<Triangle> triangles;        // world space, metres
    std::vector<std::uint32_t> triangleNode;  // glTF node index of each triangle
    std::vector<std::string> nodeNames;     // per glTF node ("" when unnamed)
    Aabb bounds;
};

}  // namespace fen
