// gltf_load.h — reading a glTF 2.0 file (.gltf or .glb) into a Scene (DESIGN.md §1, §6).
//
// - Geometry: every triangle primitive of the default scene (scene 0 if none is marked), node
//   transforms (matrix or TRS) applied, metres, +y up.
// - Materials: baseColorFactor RGB times the baseColorTexture (sRGB decoded, by TEXCOORD_n and the
//   sampler's wrap modes) is the albedo (two-sided Lambertian); KHR_materials_transmission
//   makes thin glass with T = transmissionFactor * baseColor and KHR_materials_ior (default 1.5).
//   Emission is ignored with a warning; so is every extension used that is not one of these.
// - Sun: the one KHR_lights_punctual directional light; intensity is normal illuminance (lux),
//   light travels along its node's -z; light.extras.angular_radius_deg (default 0) widens it.
// - Sky: scenes[i].extras.sky, one of
//     {"type":"uniform","luminance":L}
//     {"type":"cie","cie_type":1..15,"zenith_luminance":L,"sun_altitude_deg":h,"sun_azimuth_deg":A}
//     {"type":"table","zenith_deg":[...],"azimuth_deg":[...],"luminance":[[...],...]}
// - Cameras: perspective cameras, in traversal order, with their node's name and their own.
// - node.extras.portal: true (window panes) or "hull" (opening frame), for portal emission.
// Every problem -- a missing or malformed file, a missing buffer, an accessor out of bounds, a
// non-triangle primitive, a non-finite coordinate, an unknown or malformed extras key, a point
// light -- is a fen::Error naming the file and the node / mesh / material / key at fault.
// The file is untrusted (README, "Untrusted scenes"): its bytes are framed and bounded before a
// parser sees them and its URIs stay in its folder (scene_files.h), its JSON is checked as
// written (gltf_check.h), the node graph must be a forest and is walked without recursion, sizes
// use checked arithmetic, and no message quotes another file's bytes or size. A node that blows
// up the scene's bounds is named in Scene::warnings.
#pragma once

#include <cstddef>
#include <string>

#include "scene/scene.h"

namespace fen {

Scene loadGltf(const std::string& path);

// The same from a file's bytes in memory (also the fuzz target's entry): `path` only names the
// file in messages, and external files are read from `folder` only. The bytes are binary glTF when
// `path` ends in .glb or they start with the GLB magic, else JSON.
Scene loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& path,
                         const std::string& folder);

// The camera named `name` (node name first, then the camera's own name); the first camera when
// `name` is empty. Throws fen::Error listing the cameras there are.
const CameraSpec& findCamera(const Scene& scene, const std::string& name);

}  // namespace fen
