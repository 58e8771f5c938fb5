// sensor_set.cpp — building sensors from meshes, work planes and the scene's marked nodes
// (sensor_set.h).
#include "sensor/sensor_set.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "util/error.h"

namespace fen {

namespace {

bool insideTriangle2(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c)
{
    const auto edge = [](const glm::dvec2& o, const glm::dvec2& e, const glm::dvec2& q) {
        return (e.x - o.x) * (q.y - o.y) - (e.y - o.y) * (q.x - o.x);
    };
    const double d0 = edge(a, b, p), d1 = edge(b, c, p), d2 = edge(c, a, p);
    const double scale = 1e-9 * (std::abs(edge(a, b, c)) + 1e-30);
    const bool neg = d0 < -scale || d1 < -scale || d2 < -scale;
    const bool pos = d0 > scale || d1 > scale || d2 > scale;
    return !(neg && pos);
}

struct PlaneKey {
    long long nx, ny, nz, d;
    bool operator<(const PlaneKey& o) const { return std::tie(nx, ny, nz, d) < std::tie(o.nx, o.ny, o.nz, o.d); }
};

// Lattice cells of side c over the triangles of one plane (normal n), centres on a triangle.
std::vector<glm::dvec3> latticeOver(const std::vector<Triangle>& tris, const glm::dvec3& n, double c)
{
    glm::dvec3 u, v;
    sensorPlaneAxes(n, &u, &v);
    const glm::dvec3 o = glm::dvec3(tris.front().p0);
    const double d = glm::dot(n, o);
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    std::vector<std::array<glm::dvec2, 3>> flat;
    for (const Triangle& t : tris) {
        std::array<glm::dvec2, 3> f;
        int k = 0;
        for (const glm::vec3* p : {&t.p0, &t.p1, &t.p2}) {
            const glm::dvec3 q = glm::dvec3(*p) - o;
            f[k] = {glm::dot(q, u), glm::dot(q, v)};
            lo = glm::min(lo, f[k]);
            hi = glm::max(hi, f[k]);
            ++k;
        }
        flat.push_back(f);
    }
    const double cols = std::ceil((hi.x - lo.x) / c - 1e-9), rows = std::ceil((hi.y - lo.y) / c - 1e-9);
    if (cols * rows > static_cast<double>(kMaxSensorCells) * 4.0)
        throw Error(cat("a lattice of ", cols, " x ", rows, " cells"));
    std::set<std::pair<long long, long long>> kept;
    for (const auto& f : flat) {
        glm::dvec2 tlo = glm::min(f[0], glm::min(f[1], f[2])), thi = glm::max(f[0], glm::max(f[1], f[2]));
        const long long i0 = std::max(0LL, static_cast<long long>(std::floor((tlo.x - lo.x) / c - 0.5)));
        const long long i1 = std::min(static_cast<long long>(cols) - 1, static_cast<long long>(std::ceil((thi.x - lo.x) / c)));
        const long long j0 = std::max(0LL, static_cast<long long>(std::floor((tlo.y - lo.y) / c - 0.5)));
        const long long j1 = std::min(static_cast<long long>(rows) - 1, static_cast<long long>(std::ceil((thi.y - lo.y) / c)));
        for (long long j = j0; j <= j1; ++j)
            for (long long i = i0; i <= i1; ++i) {
                const glm::dvec2 p(lo.x + (static_cast<double>(i) + 0.5) * c, lo.y + (static_cast<double>(j) + 0.5) * c);
                if (insideTriangle2(p, f[0], f[1], f[2]))
                    kept.insert({j, i});
            }
    }
    std::vector<glm::dvec3> centres;
    centres.reserve(kept.size());
    for (const auto& [j, i] : kept) {  // row by row: the order a plan is read in
        const double pu = lo.x + (static_cast<double>(i) + 0.5) * c, pv = lo.y + (static_cast<double>(j) + 0.5) * c;
        glm::dvec3 x = o + pu * u + pv * v;
        x += n * (d - glm::dot(n, x));  // exactly on the plane
        centres.push_back(x);
    }
    return centres;
}

glm::dvec3 unitNormal(const Triangle& t, double* area)
{
    const glm::dvec3 c = glm::cross(glm::dvec3(t.p1) - glm::dvec3(t.p0), glm::dvec3(t.p2) - glm::dvec3(t.p0));
    const double l = glm::length(c);
    *area = 0.5 * l;
    return l > 0.0 ? c / l : glm::dvec3(0.0);
}

void checkSide(double side_m, const std::string& what)
{
    if (!(side_m > 0.0) || !std::isfinite(side_m) || side_m > 1e4)
        throw Error(cat(what, ": a cell side of ", side_m, " m; it must be positive and at most 10 km"));
}

}  // namespace

void sensorPlaneAxes(const glm::dvec3& n, glm::dvec3* u, glm::dvec3* v)
{
    if (std::abs(n.y) > 0.9) {
        *u = glm::normalize(glm::dvec3(1.0, 0.0, 0.0) - n * n.x);
        *v = glm::normalize(glm::cross(*u, n) * (n.y > 0.0 ? 1.0 : -1.0));
    } else {
        *u = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), n));
        *v = glm::cross(n, *u);
    }
}

std::size_t SensorSet::cellsOf(std::uint32_t sensor) const
{
    return static_cast<std::size_t>(
        std::count_if(cells.begin(), cells.end(), [&](const SensorCell& c) { return c.sensor == sensor; }));
}

void addMeshSensor(SensorSet& set, const std::string& name, const std::string& kind, const std::string& source,
                   const std::vector<Triangle>& triangles, double cell_m)
{
    checkSide(cell_m, source);
    for (const SensorInfo& s : set.sensors)
        if (s.name == name)
            throw Error(cat(source, ": a second sensor named '", printable(name, 60), "' (the first: ",
                            s.source, "); sensors are told apart by name"));
    std::map<PlaneKey, std::pair<glm::dvec3, std::vector<Triangle>>> planes;
    for (const Triangle& t : triangles) {
        double a = 0.0;
        const glm::dvec3 n = unitNormal(t, &a);
        if (!(a > 0.0))
            continue;
        const double d = glm::dot(n, glm::dvec3(t.p0));
        const PlaneKey k{std::llround(n.x * 1e4), std::llround(n.y * 1e4), std::llround(n.z * 1e4),
                         std::llround(d * 1e4)};
        auto& p = planes[k];
        if (p.second.empty())
            p.first = n;
        p.second.push_back(t);
    }
    if (planes.empty())
        throw Error(cat(source, ": the sensor has no area (no triangle of positive area)"));
    const std::uint32_t index = static_cast<std::uint32_t>(set.sensors.size());
    std::size_t added = 0;
    for (const auto& [key, plane] : planes) {
        std::vector<glm::dvec3> centres;
        try {
            centres = latticeOver(plane.second, plane.first, cell_m);
        } catch (const Error& e) {
            throw Error(cat(source, ": cells of ", cell_m, " m make ", e.what(), "; give a larger cell"));
        }
        if (set.cells.size() + centres.size() > kMaxSensorCells)
            throw Error(cat(source, ": more than ", kMaxSensorCells, " sensor cells in all; give a larger cell"));
        for (const glm::dvec3& x : centres)
            set.cells.push_back({x, plane.first, cell_m, index});
        added += centres.size();
    }
    if (added == 0)
        throw Error(cat(source, ": no cell of ", cell_m, " m has its centre on the sensor's triangles; "
                                "give a smaller cell"));
    set.sensors.push_back({name, kind, source});
}

void addWorkPlane(SensorSet& set, const Scene& scene, const std::string& node, double height_m, double spacing_m)
{
    const std::string source = cat("--work-plane ", printable(node, 60));
    if (!std::isfinite(height_m) || std::abs(height_m) > 1e4)
        throw Error(cat("--work-plane-height ", height_m, ": must be a finite height in metres"));
    std::vector<char> chosen(scene.nodeNames.size(), 0);
    bool found = false;
    for (std::size_t n = 0; n < scene.nodeNames.size(); ++n)
        if (scene.nodeNames[n] == node)
            chosen[n] = found = true;
    if (!found) {
        const std::string names = nodesWithGeometry(scene);
        throw Error(cat(source, ": no node of that name in ", printable(scene.source), " (nodes with geometry: ",
                        names, ")"));
    }
    // The node's triangles and its descendants'; those facing up (their winding), else, for a
    // floor wound the other way, those facing down.
    std::vector<Triangle> up, down;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        int n = static_cast<int>(scene.triangleNode[t]);
        while (n >= 0 && !chosen[static_cast<std::size_t>(n)])
            n = static_cast<std::size_t>(n) < scene.nodeParent.size() ? scene.nodeParent[static_cast<std::size_t>(n)] : -1;
        if (n < 0)
            continue;
        double a = 0.0;
        const glm::dvec3 nrm = unitNormal(scene.triangles[t], &a);
        if (!(a > 0.0))
            continue;
        if (nrm.y >= std::cos(5.0 * M_PI / 180.0))
            up.push_back(scene.triangles[t]);
        else if (nrm.y <= -std::cos(5.0 * M_PI / 180.0))
            down.push_back(scene.triangles[t]);
    }
    std::vector<Triangle> floors = up.empty() ? down : up;
    if (floors.empty())
        throw Error(cat(source, ": the work plane meets no floor: node '", printable(node, 60),
                        "' has no horizontal triangle (within 5 degrees) to lie above"));
    for (Triangle& t : floors)
        for (glm::vec3* p : {&t.p0, &t.p1, &t.p2})
            p->y += static_cast<float>(height_m);
    // Lifted, every floor faces up: wind them so, and the lattice lies in their planes.
    for (Triangle& t : floors) {
        double a = 0.0;
        if (unitNormal(t, &a).y < 0.0)
            std::swap(t.p1, t.p2);
    }
    addMeshSensor(set, "workplane", "work plane", source, floors, spacing_m);
}

Aabb sensorBounds(const SensorSet& set)
{
    Aabb b;
    for (const SensorCell& c : set.cells) {
        glm::dvec3 u, v;
        sensorPlaneAxes(c.normal, &u, &v);
        const double h = 0.5 * c.side_m;
        for (const double su : {-h, h})
            for (const double sv : {-h, h})
                b.grow(glm::vec3(c.position + su * u + sv * v));
    }
    return b;
}

void addSceneSensors(SensorSet& set, const Scene& scene)
{
    for (const SensorMesh& m : scene.sensorMeshes)
        addMeshSensor(set, m.name, "node", m.source, m.triangles, m.cell_m);
}

}  // namespace fen
