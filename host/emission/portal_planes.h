// portal_planes.h — the portal triangles regrouped by plane, each plane with a frame: the regions
// the `adaptive` strategy's portal cells parametrise (DESIGN.md §3.3, §3.4; device:
// kernels/lib/emit_adaptive.h, shared/fen_emission.h PortalFrame).
//
// portals.h groups triangles by orientation (n and -n together) so that `portal` chooses among
// orientations; here each orientation is split further by offset along n, so that a group is one
// plane: a line crosses it once, at one point, which is what the "first portal crossed" rule needs.
// A plane's frame is the bounding rectangle of its triangles in the plane, its first side along the
// longest triangle edge (a rectangular window fills its frame exactly).
// Invariants: triangles are grouped by plane, contiguous; frame g covers plane g's triangles;
// normal[g] is unit; the BVH's primitive indices are indices into `triangles`.
#pragma once

#include <string>
#include <vector>

#include "bvh_flat.h"
#include "emission/portals.h"
#include "scene/scene.h"
#include "shared/fen_emission.h"

namespace fen {

struct PortalPlanes {
    PortalSet set;                        // the scene's portals, as portals.h collects them
    std::vector<Triangle> triangles;      // grouped by plane
    std::vector<dev::PortalFrame> frames; // per plane
    std::vector<glm::dvec3> normal;       // per plane, unit
    std::vector<double> area_m2;          // per plane: its triangles' area
    FlatBvh bvh;                          // over `triangles`, layout bvhWidth
};

// The portals of `scene` (its marking, or the `override` node names) by plane. Errors as
// collectPortals.
PortalPlanes makePortalPlanes(const Scene& scene, const std::string& override, int bvhWidth);

}  // namespace fen
