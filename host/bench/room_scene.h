// room_scene.h — the benchmark's default scene and its rays.
//
// An interior-like scene: a closed 10 x 3 x 8 m box room (x east, y up, z south) whose walls,
// floor and ceiling are tessellated into ~7 cm quads, plus 50 random axis-aligned boxes
// (~110k triangles), the scene of the README's traversal targets. Rays are incoherent: origins
// uniform in free space (inside the room, outside every box), directions uniform on the sphere;
// occlusion queries are segments between two free-space points.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "shared/fen_bvh.h"

namespace fen {

struct BenchScene {
    Scene scene;
    // Returns a random point from which rays start; for the room, outside every box.
    std::function<glm::vec3(std::mt19937_64&)> freePoint;
};

BenchScene makeBenchRoom(std::uint32_t seed = 1);
// The room plus 100 overlapping UV spheres of 9,800 triangles each (~1.09M triangles): the
// large scene of the README's traversal targets. Free points also avoid the spheres.
BenchScene makeBenchSpheres(std::uint32_t seed = 1);
// "room", "spheres", or a glTF file.
BenchScene benchSceneNamed(const std::string& nameOrPath);

// The benchmark room made renderable (for `fenestra bench --render`): a 3 x 1.6 m window in its
// south wall (the wall's quads inside it become a glass pane, node "window", marked as a portal,
// so that every emission method renders it), the sun at altitude 40 deg, azimuth 160 deg,
// 80 klux, a CIE clear sky (type 12), and a camera in the north-west corner looking at the window
// and the floor. Every other surface has albedo 0.6.
void makeRenderable(Scene& room);
// Any scene: free points are uniform in its bounding box (solid objects are not known).
BenchScene benchSceneFrom(Scene scene);

std::vector<dev::Ray> makeClosestRays(const BenchScene& s, std::size_t n, std::uint64_t seed);
std::vector<dev::Ray> makeOcclusionSegments(const BenchScene& s, std::size_t n, std::uint64_t seed);

// Appends the 12 triangles of an axis-aligned box, and a tessellated axis-aligned rectangle.
void addBox(std::vector<Triangle>& out, const Aabb& box);
void addGrid(std::vector<Triangle>& out, const glm::vec3& origin, const glm::vec3& edgeU,
             const glm::vec3& edgeV, int nu, int nv);

}  // namespace fen
