// portals.h — the triangles light is emitted through in the `portal` strategy (DESIGN.md §3.2).
//
// Marking: node.extras.portal = true (the node's triangles are panes / glazed doors / opening
// surfaces) or "hull" (the node is a frame: emit through the convex hull of its vertices, a flat
// polygon when they are coplanar, else the hull's surface). `--portals NAME,...` replaces the
// scene's marking with the named nodes (each keeps its own kind, panes when it has none;
// NAME:panes or NAME:hull forces one).
// Triangles are grouped by plane orientation (n and -n together, within 1e-9 in cosine) so a path
// chooses among groups, not triangles: per-path work grows with the number of distinct planes.
// Invariants: every portal triangle has positive area; groups are contiguous in `triangles`.
#pragma once

#include <string>
#include <vector>

#include "geometry.h"
#include "scene/scene.h"

namespace fen {

struct PortalGroup {
    glm::dvec3 normal{0.0};      // unit; the sign is irrelevant (|v . n| everywhere)
    double area_m2 = 0.0;        // total area of the group's triangles
    std::uint32_t first = 0;     // triangles[first, first + count)
    std::uint32_t count = 0;
};

struct PortalSet {
    std::vector<Triangle> triangles;  // world space, grouped
    std::vector<double> area_m2;      // per triangle
    std::vector<PortalGroup> groups;
    std::vector<std::string> nodes;   // the nodes they came from, for reports
    double area_m2_total = 0.0;
    // Sum over portal triangles of area * |v . n| for unit v (m^2): eq. (1)'s normaliser.
    double projectedArea(const glm::dvec3& v) const;
    // Whether every triangle lies in one plane (one group, every vertex within 1e-6 of the set's
    // extent of it): then a line off the plane crosses at most one of them, so every emitted line
    // has N(x, v) = 1 and portal emission need not count (lib/emit_portal.h).
    bool singlePlane() const;
};

// The portal set of `scene`: its marking, or `override` (comma-separated node names) when not
// empty. Errors name the file and the node: an unknown name, a set that is empty or has no area,
// a hull of fewer than three non-collinear points.
PortalSet collectPortals(const Scene& scene, const std::string& override);

// Convex hull of points as triangles: the flat polygon when they are coplanar (within 1e-6 of
// their extent), else the closed hull surface. Throws fen::Error (naming `what`) when the points
// span no area.
std::vector<Triangle> convexHull(const std::vector<glm::dvec3>& points, const std::string& what);

}  // namespace fen
