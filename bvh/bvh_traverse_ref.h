// bvh_traverse_ref.h — CPU oracles for the traversal kernels.
//
// traceClosestRef / traceAnyRef walk the *flat device layout* (FlatBvh) with the kernels'
// algorithm and the kernels' float arithmetic, operation for operation (kernels/lib/ray_setup.h,
// tri_packet.h, bvh_traverse.h), so on a device with IEEE float and no contraction (PoCL) the
// results match bit for bit. bruteForceClosest is independent of both: every triangle, in double
// precision, Moller-Trumbore; it is the ground truth for the layout-and-algorithm pair.
#pragma once

#include <vector>

#include "bvh_flat.h"

namespace fen {

struct RefRay {
    glm::vec3 org;
    glm::vec3 dir;
    float tmin = 0.0f;
    float tmax = 0.0f;
};

dev::Hit traceClosestRef(const FlatBvh& bvh, const RefRay& ray);
bool traceAnyRef(const FlatBvh& bvh, const RefRay& ray);

struct BruteHit {
    double t = 0.0;
    std::uint32_t prim = FEN_INVALID_ID;
};
// Closest triangle with tmin < t < tmax in double precision; skips zero-area triangles.
BruteHit bruteForceClosest(const std::vector<Triangle>& tris, const RefRay& ray);

}  // namespace fen
