// gltf_load.h — reading a glTF 2.0 file (.gltf or .glb) into a Scene.
//
// Geometry: every triangle primitive of the default scene (scene 0 if none is marked), with node
// transforms (matrix or TRS) applied, in metres, +y up (DESIGN.md §1). Every problem -- a missing
// or malformed file, a missing buffer, an accessor out of its buffer's bounds, a non-triangle
// primitive, a non-finite coordinate -- is a fen::Error that names the file and the node / mesh /
// accessor at fault.
#pragma once

#include <string>

#include "scene/scene.h"

namespace fen {

Scene loadGltf(const std::string& path);

}  // namespace fen
