// trace_support.cpp — device / reference / brute-force comparisons (trace_support.h).
#include "trace_support.h"

#include <cmath>
#include <cstring>

namespace fen { namespace test {

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Smallest barycentric coordinate of the ray's crossing of tri's plane (double precision).
double minBarycentric(const Triangle& tri, const RefRay& r)
{
    const glm::dvec3 o(r.org), d(r.dir), p0(tri.p0), p1(tri.p1), p2(tri.p2);
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);
    if (det == 0.0)
        return 0.0;
    const glm::dvec3 tv = o - p0;
    const double u = glm::dot(tv, pv) / det;
    const double v = glm::dot(d, glm::cross(tv, e1)) / det;
    return std::min({u, v, 1.0 - u - v});
}

}  // namespace

std::size_t deviceVsReference(TracedScene& s, const std::vector<RefRay>& rays)
{
    const auto hits = s.queries->closest(toDevice(rays));
    const auto occ = s.queries->any(toDevice(rays));
    std::size_t bad = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const dev::Hit ref = traceClosestRef(s.flat, rays[i]);
        const bool refAny = traceAnyRef(s.flat, rays[i]);
        const dev::Hit& h = hits[i];
        const bool same = h.prim == ref.prim && sameBits(h.t, ref.t) && sameBits(h.u, ref.u) &&
                          sameBits(h.v, ref.v) && (occ[i] != 0) == refAny;
        if (!same && ++bad <= 5)
            ADD_FAILURE() << "ray " << i << ": device prim " << h.prim << " t " << h.t << " u "
                          << h.u << " v " << h.v << " any " << occ[i] << "; reference prim "
                          << ref.prim << " t " << ref.t << " u " << ref.u << " v " << ref.v
                          << " any " << refAny;
    }
    return bad;
}

BruteComparison deviceVsBruteForce(TracedScene& s, const std::vector<RefRay>& rays)
{
    const auto hits = s.queries->closest(toDevice(rays));
    BruteComparison c;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const BruteHit b = bruteForceClosest(s.tris, rays[i]);
        const dev::Hit& h = hits[i];
        const bool hitD = h.prim != FEN_INVALID_ID, hitB = b.prim != FEN_INVALID_ID;
        bool agree = hitD == hitB;
        if (agree && hitD) {
            const double scale = std::max(1.0, std::fabs(b.t) * glm::length(glm::dvec3(rays[i].dir)));
            agree = std::fabs(h.t - b.t) * glm::length(glm::dvec3(rays[i].dir)) <= 1e-5 * scale;
        }
        if (agree)
            continue;
        double m = 1.0;
        if (hitD)
            m = std::min(m, std::fabs(minBarycentric(s.tris[h.prim], rays[i])));
        if (hitB)
            m = std::min(m, std::fabs(minBarycentric(s.tris[b.prim], rays[i])));
        if (m < 1e-5) {
            ++c.borderline;
            continue;
        }
        if (++c.disagreements <= 5)
            ADD_FAILURE() << "ray " << i << ": device prim " << h.prim << " t " << h.t
                          << "; brute force prim " << b.prim << " t " << b.t;
    }
    return c;
}

} }  // namespace fen::test
