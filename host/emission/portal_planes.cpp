// portal_planes.cpp — portal triangles by plane, with frames (portal_planes.h).
#include "emission/portal_planes.h"

#include <algorithm>

#include "bvh_build.h"

namespace fen {

PortalPlanes makePortalPlanes(const Scene& scene, const std::string& override, int bvhWidth)
{
    PortalPlanes pp;
    pp.set = collectPortals(scene, override);
    const PortalSet& P = pp.set;
    const double tol = std::max(1e-4, 1e-6 * glm::length(glm::dvec3(scene.bounds.extent())));
    for (const PortalGroup& g : P.groups) {
        // Offsets along the group's normal, sorted, split where they jump.
        std::vector<std::pair<double, std::uint32_t>> by;
        for (std::uint32_t t = g.first; t < g.first + g.count; ++t) {
            const Triangle& tr = P.triangles[t];
            const glm::dvec3 c = (glm::dvec3(tr.p0) + glm::dvec3(tr.p1) + glm::dvec3(tr.p2)) / 3.0;
            by.push_back({glm::dot(c, g.normal), t});
        }
        std::sort(by.begin(), by.end());
        for (std::size_t a = 0; a < by.size();) {
            std::size_t b = a + 1;
            while (b < by.size() && by[b].first - by[b - 1].first <= tol)
                ++b;
            const std::uint32_t first = static_cast<std::uint32_t>(pp.triangles.size());
            double area = 0.0, longest = -1.0;
            glm::dvec3 axis(0.0);
            for (std::size_t k = a; k < b; ++k) {
                const Triangle& tr = P.triangles[by[k].second];
                pp.triangles.push_back(tr);
                area += P.area_m2[by[k].second];
                const glm::dvec3 v[3] = {tr.p0, tr.p1, tr.p2};
                for (int e = 0; e < 3; ++e) {
                    const glm::dvec3 d = v[(e + 1) % 3] - v[e];
                    if (glm::length(d) > longest) {
                        longest = glm::length(d);
                        axis = d / longest;
                    }
                }
            }
            const glm::dvec3 n = g.normal;
            axis = glm::normalize(axis - glm::dot(axis, n) * n);
            const glm::dvec3 side = glm::cross(n, axis);
            const glm::dvec3 o = pp.triangles[first].p0;
            double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
            for (std::size_t k = first; k < pp.triangles.size(); ++k)
                for (const glm::vec3* p : {&pp.triangles[k].p0, &pp.triangles[k].p1, &pp.triangles[k].p2}) {
                    const glm::dvec3 q = glm::dvec3(*p) - o;
                    s0 = std::min(s0, glm::dot(q, axis));
                    s1 = std::max(s1, glm::dot(q, axis));
                    t0 = std::min(t0, glm::dot(q, side));
                    t1 = std::max(t1, glm::dot(q, side));
                }
            const glm::dvec3 origin = o + s0 * axis + t0 * side, S = (s1 - s0) * axis, T = (t1 - t0) * side;
            dev::PortalFrame f{};
            f.origin = {float(origin.x), float(origin.y), float(origin.z), float((s1 - s0) * (t1 - t0))};
            f.axis_s = {float(S.x), float(S.y), float(S.z), 0.0f};
            f.axis_t = {float(T.x), float(T.y), float(T.z), 0.0f};
            f.normal = {float(n.x), float(n.y), float(n.z), dev::fen_as_float(first)};
            f.triangles = static_cast<std::uint32_t>(pp.triangles.size() - first);
            pp.frames.push_back(f);
            pp.normal.push_back(n);
            pp.area_m2.push_back(area);
            a = b;
        }
    }
    pp.bvh = flattenBvh(buildBinnedSah(pp.triangles), pp.triangles, bvhWidth);
    return pp;
}

}  // namespace fen
