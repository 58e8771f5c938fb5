// test_scenes.h — small procedural scenes and rays the tests share.
#pragma once

#include <random>
#include <vector>

#include "bvh_traverse_ref.h"
#include "geometry.h"
#include "shared/fen_bvh.h"

namespace fen { namespace test {

// n triangles with vertices uniform in a cube of side `size` at `center`, edges up to `maxEdge`.
std::vector<Triangle> randomSoup(std::size_t n, std::uint64_t seed, glm::vec3 center = glm::vec3(0),
                                 float size = 10.0f, float maxEdge = 1.0f);
// A UV sphere (closed, consistently wound, shared vertices written identically).
std::vector<Triangle> uvSphere(glm::vec3 center, float radius, int rings, int segments);
// An n x n grid of quads (2 triangles each) spanning [0,1]^2 mapped by origin + s*u + t*v.
std::vector<Triangle> grid(glm::vec3 origin, glm::vec3 u, glm::vec3 v, int n);

RefRay refRay(glm::vec3 o, glm::vec3 d, float tmin = 0.0f,
              float tmax = std::numeric_limits<float>::infinity());
dev::Ray toDevice(const RefRay& r);
std::vector<dev::Ray> toDevice(const std::vector<RefRay>& rays);
glm::vec3 uniformSphere(std::mt19937_64& rng);

} }  // namespace fen::test
