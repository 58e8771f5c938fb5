// geometry.h — the host's triangle and box types shared by the builder, the flattener and the
// reference traversal. A scene reaches the BVH as a triangle soup; triangle i is primitive i.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

namespace fen {

struct Triangle {
    glm::vec3 p0, p1, p2;
};

struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};

    void grow(const glm::vec3& p)
    {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Aabb& b)
    {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    // Half the surface area; the SAH only ever uses ratios of areas.
    float halfArea() const
    {
        const glm::vec3 e = extent();
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
    bool contains(const Aabb& b) const
    {
        return b.empty() || (lo.x <= b.lo.x && lo.y <= b.lo.y && lo.z <= b.lo.z &&
                             hi.x >= b.hi.x && hi.y >= b.hi.y && hi.z >= b.hi.z);
    }
    int longestAxis() const
    {
        const glm::vec3 e = extent();
        return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    }
};

inline Aabb bounds(const Triangle& t)
{
    Aabb b;
    b.grow(t.p0);
    b.grow(t.p1);
    b.grow(t.p2);
    return b;
}

// Twice the area, in double so that a triangle is "degenerate" only when it truly has none.
inline double doubleArea2(const Triangle& t)
{
    const glm::dvec3 a(t.p0), b(t.p1), c(t.p2);
    return glm::length(glm::cross(b - a, c - a));
}

inline bool isFinite(const glm::vec3& p)
{
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace fen
