// room_scene.cpp — the benchmark room and incoherent rays (room_scene.h).
#include "bench/room_scene.h"

#include "scene/gltf_load.h"

#include <cmath>
#include <limits>
#include <memory>

namespace fen {

void addGrid(std::vector<Triangle>& out, const glm::vec3& origin, const glm::vec3& edgeU,
             const glm::vec3& edgeV, int nu, int nv)
{
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const glm::vec3 a = origin + edgeU * (float(i) / nu) + edgeV * (float(j) / nv);
            const glm::vec3 b = origin + edgeU * (float(i + 1) / nu) + edgeV * (float(j) / nv);
            const glm::vec3 c = origin + edgeU * (float(i + 1) / nu) + edgeV * (float(j + 1) / nv);
            const glm::vec3 d = origin + edgeU * (float(i) / nu) + edgeV * (float(j + 1) / nv);
            out.push_back({a, b, c});
            out.push_back({a, c, d});
        }
}

void addBox(std::vector<Triangle>& out, const Aabb& b)
{
    const glm::vec3 e = b.hi - b.lo;
    const glm::vec3 ex(e.x, 0, 0), ey(0, e.y, 0), ez(0, 0, e.z);
    addGrid(out, b.lo, ex, ey, 1, 1);
    addGrid(out, b.lo + ez, ex, ey, 1, 1);
    addGrid(out, b.lo, ey, ez, 1, 1);
    addGrid(out, b.lo + ex, ey, ez, 1, 1);
    addGrid(out, b.lo, ez, ex, 1, 1);
    addGrid(out, b.lo + ey, ez, ex, 1, 1);
}

BenchScene makeBenchRoom(std::uint32_t seed)
{
    const glm::vec3 size(10.0f, 3.0f, 8.0f);
    const float quad = 0.07f;
    const int nx = static_cast<int>(std::round(size.x / quad));
    const int ny = static_cast<int>(std::round(size.y / quad));
    const int nz = static_cast<int>(std::round(size.z / quad));
    std::vector<Triangle> t;
    const glm::vec3 o(0.0f), X(size.x, 0, 0), Y(0, size.y, 0), Z(0, 0, size.z);
    addGrid(t, o, X, Z, nx, nz);      // floor
    addGrid(t, o + Y, X, Z, nx, nz);  // ceiling
    addGrid(t, o, X, Y, nx, ny);      // north wall
    addGrid(t, o + Z, X, Y, nx, ny);  // south wall
    addGrid(t, o, Z, Y, nz, ny);      // west wall
    addGrid(t, o + X, Z, Y, nz, ny);  // east wall

    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    auto boxes = std::make_shared<std::vector<Aabb>>();
    for (int i = 0; i < 50; ++i) {
        const glm::vec3 ext(0.2f + 1.3f * u01(rng), 0.2f + 1.3f * u01(rng), 0.2f + 1.3f * u01(rng));
        const glm::vec3 lo((size.x - ext.x) * u01(rng), (size.y - ext.y) * u01(rng),
                           (size.z - ext.z) * u01(rng));
        Aabb b;
        b.grow(lo);
        b.grow(lo + ext);
        boxes->push_back(b);
        addBox(t, b);
    }

    BenchScene s;
    s.scene.source = "room (procedural)";
    s.scene.triangles = std::move(t);
    s.scene.triangleNode.assign(s.scene.triangles.size(), 0);
    s.scene.triangleMaterial.assign(s.scene.triangles.size(), 0);
    s.scene.nodeNames = {"room"};
    s.scene.nodePortal = {PortalMark::None};
    s.scene.materials = {Material{"white", glm::vec3(0.8f)}};
    for (const auto& tri : s.scene.triangles) {
        s.scene.bounds.grow(tri.p0);
        s.scene.bounds.grow(tri.p1);
        s.scene.bounds.grow(tri.p2);
    }
    s.freePoint = [size, boxes](std::mt19937_64& r) {
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (;;) {
            const glm::vec3 p(0.01f + (size.x - 0.02f) * u(r), 0.01f + (size.y - 0.02f) * u(r),
                              0.01f + (size.z - 0.02f) * u(r));
            bool inside = false;
            for (const auto& b : *boxes)
                if (p.x > b.lo.x && p.x < b.hi.x && p.y > b.lo.y && p.y < b.hi.y && p.z > b.lo.z &&
                    p.z < b.hi.z) {
                    inside = true;
                    break;
                }
            if (!inside)
                return p;
        }
    };
    return s;
}

BenchScene makeBenchSpheres(std::uint32_t seed)
{
    BenchScene s = makeBenchRoom(seed);
    std::mt19937_64 rng(seed + 1000);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    struct Ball {
        glm::vec3 c;
        float r;
    };
    auto balls = std::make_shared<std::vector<Ball>>();
    const int rings = 50, segments = 100;
    for (int i = 0; i < 100; ++i) {
        const float r = 0.1f + 0.5f * u(rng);
        const glm::vec3 c(r + (10.0f - 2 * r) * u(rng), r + (3.0f - 2 * r) * u(rng),
                          r + (8.0f - 2 * r) * u(rng));
        balls->push_back({c, r});
        auto at = [&](int ring, int seg) -> glm::vec3 {
            const double th = M_PI * ring / rings, ph = 2.0 * M_PI * (seg % segments) / segments;
            return c + r * glm::vec3(glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th),
                                                std::sin(th) * std::sin(ph)));
        };
        for (int ring = 0; ring < rings; ++ring)
            for (int seg = 0; seg < segments; ++seg) {
                const glm::vec3 a = at(ring, seg), b = at(ring, seg + 1), cc = at(ring + 1, seg + 1),
                                d = at(ring + 1, seg);
                if (ring != 0)
                    s.scene.triangles.push_back({a, b, d});
                if (ring != rings - 1)
                    s.scene.triangles.push_back({b, cc, d});
            }
    }
    s.scene.source = "spheres (procedural)";
    s.scene.triangleNode.assign(s.scene.triangles.size(), 0);
    s.scene.triangleMaterial.assign(s.scene.triangles.size(), 0);
    auto roomPoint = s.freePoint;
    s.freePoint = [roomPoint, balls](std::mt19937_64& r) {
        for (;;) {
            const glm::vec3 p = roomPoint(r);
            bool inside = false;
            for (const auto& b : *balls)
                inside = inside || glm::dot(p - b.c, p - b.c) < b.r * b.r;
            if (!inside)
                return p;
        }
    };
    return s;
}

BenchScene benchSceneNamed(const std::string& nameOrPath)
{
    if (nameOrPath.empty() || nameOrPath == "room")
        return makeBenchRoom();
    if (nameOrPath == "spheres")
        return makeBenchSpheres();
    return benchSceneFrom(loadGltf(nameOrPath));
}

void makeRenderable(Scene& room)
{
    const float x0 = 3.5f, x1 = 6.5f, y0 = 0.8f, y1 = 2.4f, zWall = 8.0f;
    Scene out = room;
    out.triangles.clear();
    out.triangleNode.clear();
    out.triangleMaterial.clear();
    Material glass{"glass", glm::vec3(1.0f)};
    glass.glass = true;
    glass.transmission = glm::vec3(0.9f);
    out.materials = {Material{"white", glm::vec3(0.6f)}, glass};
    // The pane is the wall's own quads inside the window, so it closes the hole exactly (the
    // quads do not line up with the window's edges); one node, one plane: one portal.
    out.nodeNames = {"room", "window"};
    out.nodePortal = {PortalMark::None, PortalMark::Panes};
    out.nodeParent = {-1, -1};
    for (std::size_t i = 0; i < room.triangles.size(); ++i) {
        const Triangle& t = room.triangles[i];
        const glm::vec3 c = (t.p0 + t.p1 + t.p2) / 3.0f;
        const bool southWall = t.p0.z == zWall && t.p1.z == zWall && t.p2.z == zWall;
        const std::uint32_t pane = southWall && c.x > x0 && c.x < x1 && c.y > y0 && c.y < y1;
        out.triangles.push_back(t);
        out.triangleNode.push_back(pane);
        out.triangleMaterial.push_back(pane);
    }
    out.sun.present = true;
    out.sun.nodeName = "sun";
    const double alt = 40.0 * M_PI / 180.0, az = 160.0 * M_PI / 180.0;
    out.sun.travelDirection = -glm::dvec3(std::cos(alt) * std::sin(az), std::sin(alt), -std::cos(alt) * std::cos(az));
    out.sun.illuminanceRgb_lux = glm::dvec3(80000.0);
    out.sky.type = SkySpec::Type::Cie;
    out.sky.where = "bench room sky";
    out.sky.cieType = 12;
    out.sky.zenithLuminance_cd_m2 = 4000.0;
    out.sky.sunAltitudeDeg = 40.0;
    out.sky.sunAzimuthDeg = 160.0;
    CameraSpec cam;
    cam.nodeName = "camera";
    cam.position = glm::dvec3(0.5, 1.6, 0.5);
    cam.forward = glm::normalize(glm::dvec3(5.0, 0.6, 6.0) - cam.position);
    cam.right = glm::normalize(glm::cross(cam.forward, glm::dvec3(0, 1, 0)));
    cam.up = glm::cross(cam.right, cam.forward);
    cam.yfovRad = 60.0 * M_PI / 180.0;
    cam.aspectRatio = 4.0 / 3.0;
    out.cameras = {cam};
    out.source = room.source + " with a window";
    room = std::move(out);
}

BenchScene benchSceneFrom(Scene scene)
{
    BenchScene s;
    s.scene = std::move(scene);
    const Aabb b = s.scene.bounds;
    s.freePoint = [b](std::mt19937_64& r) {
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        const glm::vec3 e = b.extent();
        return b.lo + glm::vec3(e.x * u(r), e.y * u(r), e.z * u(r));
    };
    return s;
}

namespace {

glm::vec3 uniformDirection(std::mt19937_64& r)
{
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float z = 1.0f - 2.0f * u(r);
    const float rad = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 6.2831853071795864f * u(r);
    return glm::vec3(rad * std::cos(phi), rad * std::sin(phi), z);
}

dev::Ray makeRay(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax)
{
    dev::Ray r;
    r.org_tmin = {o.x, o.y, o.z, tmin};
    r.dir_tmax = {d.x, d.y, d.z, tmax};
    return r;
}

}  // namespace

std::vector<dev::Ray> makeClosestRays(const BenchScene& s, std::size_t n, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::vector<dev::Ray> rays(n);
    for (auto& r : rays) {
        const glm::vec3 o = s.freePoint(rng);
        r = makeRay(o, uniformDirection(rng), 0.0f, std::numeric_limits<float>::infinity());
    }
    return rays;
}

std::vector<dev::Ray> makeOcclusionSegments(const BenchScene& s, std::size_t n, std::uint64_t seed)
{
    std::mt19937_64 rng(seed ^ 0x5bd1e995ull);
    std::vector<dev::Ray> rays(n);
    for (auto& r : rays) {
        const glm::vec3 p = s.freePoint(rng);
        const glm::vec3 q = s.freePoint(rng);
        r = makeRay(p, q - p, 0.0f, 1.0f);
    }
    return rays;
}

}  // namespace fen
