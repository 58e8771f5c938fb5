// test_scenes.cpp — procedural test geometry (test_scenes.h).
#include "support/test_scenes.h"

#include <cmath>

namespace fen { namespace test {

std::vector<Triangle> randomSoup(std::size_t n, std::uint64_t seed, glm::vec3 center, float size,
                                 float maxEdge)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    std::vector<Triangle> t(n);
    for (auto& tri : t) {
        const glm::vec3 c = center + size * glm::vec3(u(rng), u(rng), u(rng));
        tri.p0 = c + maxEdge * glm::vec3(u(rng), u(rng), u(rng));
        tri.p1 = c + maxEdge * glm::vec3(u(rng), u(rng), u(rng));
        tri.p2 = c + maxEdge * glm::vec3(u(rng), u(rng), u(rng));
    }
    return t;
}

std::vector<Triangle> uvSphere(glm::vec3 center, float radius, int rings, int segments)
{
    std::vector<glm::vec3> v;
    auto at = [&](int r, int s) -> glm::vec3 {
        if (r == 0)
            return center + glm::vec3(0, radius, 0);
        if (r == rings)
            return center + glm::vec3(0, -radius, 0);
        const double th = M_PI * r / rings, ph = 2.0 * M_PI * (s % segments) / segments;
        return center + glm::vec3(glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th),
                                             std::sin(th) * std::sin(ph)) *
                                  double(radius));
    };
    std::vector<Triangle> out;
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const glm::vec3 a = at(r, s), b = at(r, s + 1), c = at(r + 1, s + 1), d = at(r + 1, s);
            if (r != 0)
                out.push_back({a, b, d});
            if (r != rings - 1)
                out.push_back({b, c, d});
        }
    return out;
}

std::vector<Triangle> grid(glm::vec3 origin, glm::vec3 u, glm::vec3 v, int n)
{
    std::vector<Triangle> out;
    auto at = [&](int i, int j) { return origin + u * (float(i) / n) + v * (float(j) / n); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            out.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            out.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return out;
}

RefRay refRay(glm::vec3 o, glm::vec3 d, float tmin, float tmax)
{
    RefRay r;
    r.org = o;
    r.dir = d;
    r.tmin = tmin;
    r.tmax = tmax;
    return r;
}

dev::Ray toDevice(const RefRay& r)
{
    dev::Ray d;
    d.org_tmin = {r.org.x, r.org.y, r.org.z, r.tmin};
    d.dir_tmax = {r.dir.x, r.dir.y, r.dir.z, r.tmax};
    return d;
}

std::vector<dev::Ray> toDevice(const std::vector<RefRay>& rays)
{
    std::vector<dev::Ray> out;
    out.reserve(rays.size());
    for (const auto& r : rays)
        out.push_back(toDevice(r));
    return out;
}

glm::vec3 uniformSphere(std::mt19937_64& rng)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double z = 1.0 - 2.0 * u(rng), phi = 2.0 * M_PI * u(rng);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

} }  // namespace fen::test
