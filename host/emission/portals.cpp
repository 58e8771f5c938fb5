// portals.cpp — portal selection, convex hulls of frames, grouping by plane (portals.h).
#include "emission/portals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "util/error.h"

namespace fen {

namespace {

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

double area(const Triangle& t) { return 0.5 * doubleArea2(t); }

// Canonical orientation: the largest component positive, so n and -n compare equal.
glm::dvec3 canonicalNormal(const Triangle& t)
{
    glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(t.p1) - glm::dvec3(t.p0),
                                             glm::dvec3(t.p2) - glm::dvec3(t.p0)));
    const glm::dvec3 a = glm::abs(n);
    const int k = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    return n[k] < 0.0 ? -n : n;
}

std::vector<Triangle> planarHull(const std::vector<glm::dvec3>& pts, const glm::dvec3& origin,
                                 const glm::dvec3& u, const glm::dvec3& w)
{
    std::vector<glm::dvec2> p;
    for (const auto& q : pts)
        p.push_back({glm::dot(q - origin, u), glm::dot(q - origin, w)});
    std::sort(p.begin(), p.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    auto cross2 = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    // Andrew's monotone chain.
    std::vector<glm::dvec2> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0.0)
            --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross2(h[k - 2], h[k - 1], p[i - 1]) <= 0.0)
            --k;
        h[k++] = p[i - 1];
    }
    h.resize(k > 0 ? k - 1 : 0);
    std::vector<Triangle> out;
    auto to3 = [&](const glm::dvec2& q) { return glm::vec3(origin + q.x * u + q.y * w); };
    for (std::size_t i = 1; i + 1 < h.size(); ++i)
        out.push_back({to3(h[0]), to3(h[i]), to3(h[i + 1])});
    return out;
}

// Incremental 3D hull (O(n h)); faces oriented outwards.
std::vector<Triangle> spatialHull(const std::vector<glm::dvec3>& pts, const std::array<int, 4>& seed,
                                  double eps)
{
    struct Face {
        int a, b, c;
        glm::dvec3 n;
        double d;
        bool alive = true;
    };
    std::vector<Face> faces;
    glm::dvec3 inside(0.0);
    for (int i : seed)
        inside += pts[static_cast<std::size_t>(i)] * 0.25;
    auto makeFace = [&](int a, int b, int c) {
        Face f{a, b, c, glm::dvec3(0.0), 0.0};
        const glm::dvec3 &A = pts[static_cast<std::size_t>(a)], &B = pts[static_cast<std::size_t>(b)],
                         &C = pts[static_cast<std::size_t>(c)];
        f.n = glm::normalize(glm::cross(B - A, C - A));
        f.d = glm::dot(f.n, A);
        if (glm::dot(f.n, inside) - f.d > 0.0) {  // point it away from the interior
            std::swap(f.b, f.c);
            f.n = -f.n;
            f.d = -f.d;
        }
        faces.push_back(f);
    };
    makeFace(seed[0], seed[1], seed[2]);
    makeFace(seed[0], seed[1], seed[3]);
    makeFace(seed[0], seed[2], seed[3]);
    makeFace(seed[1], seed[2], seed[3]);
    for (int i = 0; i < static_cast<int>(pts.size()); ++i) {
        if (std::find(seed.begin(), seed.end(), i) != seed.end())
            continue;
        const glm::dvec3& p = pts[static_cast<std::size_t>(i)];
        std::vector<std::size_t> visible;
        for (std::size_t f = 0; f < faces.size(); ++f)
            if (faces[f].alive && glm::dot(faces[f].n, p) - faces[f].d > eps)
                visible.push_back(f);
        if (visible.empty())
            continue;
        std::set<std::pair<int, int>> edges;
        for (std::size_t f : visible) {
            const Face& F = faces[f];
            for (auto e : {std::make_pair(F.a, F.b), std::make_pair(F.b, F.c), std::make_pair(F.c, F.a)}) {
                // an edge shared by two visible faces appears in both directions: it is interior
                if (!edges.erase({e.second, e.first}))
                    edges.insert(e);
            }
            faces[f].alive = false;
        }
        for (const auto& e : edges)
            makeFace(e.first, e.second, i);
    }
    std::vector<Triangle> out;
    for (const Face& f : faces)
        if (f.alive)
            out.push_back({glm::vec3(pts[static_cast<std::size_t>(f.a)]),
                           glm::vec3(pts[static_cast<std::size_t>(f.b)]),
                           glm::vec3(pts[static_cast<std::size_t>(f.c)])});
    return out;
}

}  // namespace

bool PortalSet::singlePlane() const
{
    if (groups.size() != 1 || triangles.empty())
        return false;
    const glm::dvec3 n = groups[0].normal;
    const double d0 = glm::dot(n, glm::dvec3(triangles[0].p0));
    glm::dvec3 lo(triangles[0].p0), hi(triangles[0].p0);
    double dmin = d0, dmax = d0;
    for (const auto& t : triangles)
        for (const glm::vec3* p : {&t.p0, &t.p1, &t.p2}) {
            const glm::dvec3 q(*p);
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
            const double d = glm::dot(n, q);
            dmin = std::min(dmin, d);
            dmax = std::max(dmax, d);
        }
    const glm::dvec3 e = hi - lo;
    return dmax - dmin <= 1e-6 * std::max({e.x, e.y, e.z});
}

double PortalSet::projectedArea(const glm::dvec3& v) const
{
    double s = 0.0;
    for (const auto& g : groups)
        s += g.area_m2 * std::fabs(glm::dot(v, g.normal));
    return s;
}

std::vector<Triangle> convexHull(const std::vector<glm::dvec3>& points, const std::string& what)
{
    if (points.size() < 3)
        throw Error(cat(what, ": a hull needs at least three points, the node has ", points.size()));
    glm::dvec3 lo = points[0], hi = points[0];
    for (const auto& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const double extent = glm::length(hi - lo);
    const glm::dvec3 p0 = points[0];
    std::size_t i1 = 0, i2 = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (glm::length(points[i] - p0) > glm::length(points[i1] - p0))
            i1 = i;
    const glm::dvec3 axis = points[i1] - p0;
    double best = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double a = glm::length(glm::cross(axis, points[i] - p0));
        if (a > best) {
            best = a;
            i2 = i;
        }
    }
    if (!(best > 1e-12 * extent * extent))
        throw Error(cat(what, ": the frame's vertices are collinear: no opening to emit through"));
    const glm::dvec3 n = glm::normalize(glm::cross(axis, points[i2] - p0));
    std::size_t i3 = 0;
    double off = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double d = std::fabs(glm::dot(points[i] - p0, n));
        if (d > off) {
            off = d;
            i3 = i;
        }
    }
    if (off <= 1e-6 * extent) {
        const glm::dvec3 u = glm::normalize(axis);
        return planarHull(points, p0, u, glm::cross(n, u));
    }
    return spatialHull(points, {0, static_cast<int>(i1), static_cast<int>(i2), static_cast<int>(i3)},
                       1e-9 * extent);
}

PortalSet collectPortals(const Scene& scene, const std::string& override)
{
    std::vector<std::uint32_t> chosen;
    std::vector<PortalMark> kind(scene.nodePortal);
    kind.resize(scene.nodeNames.size(), PortalMark::None);
    if (!override.empty()) {
        std::stringstream in(override);
        std::string name;
        while (std::getline(in, name, ',')) {
            name = trim(name);
            if (name.empty())
                continue;
            // NAME, NAME:panes or NAME:hull
            PortalMark forced = PortalMark::None;
            const auto colon = name.rfind(':');
            if (colon != std::string::npos) {
                const std::string k = name.substr(colon + 1);
                if (k == "hull")
                    forced = PortalMark::Hull;
                else if (k == "panes")
                    forced = PortalMark::Panes;
                else
                    throw Error(cat("--portals: '", printable(name, 60), "': the kind after ':' must be panes or hull"));
                name = trim(name.substr(0, colon));
            }
            bool found = false;
            for (std::uint32_t n = 0; n < scene.nodeNames.size(); ++n)
                if (scene.nodeNames[n] == name) {
                    chosen.push_back(n);
                    if (forced != PortalMark::None)
                        kind[n] = forced;
                    found = true;
                }
            if (!found) {
                const std::string names = nodesWithGeometry(scene);
                throw Error(cat("--portals: no node named '", printable(name, 60), "' in ", printable(scene.source),
                                " (nodes with geometry: ", names, ")"));
            }
        }
        if (chosen.empty())
            throw Error("--portals: no node names given");
    } else {
        for (std::uint32_t n = 0; n < scene.nodePortal.size(); ++n)
            if (scene.nodePortal[n] != PortalMark::None)
                chosen.push_back(n);
        if (chosen.empty())
            throw Error(cat(scene.source, ": no portals: mark window nodes with extras.portal = "
                                          "true (panes) or \"hull\" (frames), or name them with --portals"));
    }

    // Each triangle belongs to its nearest chosen ancestor-or-self: a node marked as a whole
    // (a Blender object's parent, say) brings its descendants' geometry, and a triangle counts once
    // however many of its ancestors are chosen or named.
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    std::vector<char> isChosen(scene.nodeNames.size(), 0);
    for (std::uint32_t n : chosen)
        isChosen[n] = 1;
    std::map<std::uint32_t, std::vector<Triangle>> byNode;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        int n = static_cast<int>(scene.triangleNode[t]);
        while (n >= 0 && !isChosen[static_cast<std::size_t>(n)])
            n = static_cast<std::size_t>(n) < scene.nodeParent.size() ? scene.nodeParent[static_cast<std::size_t>(n)] : -1;
        if (n >= 0)
            byNode[static_cast<std::uint32_t>(n)].push_back(scene.triangles[t]);
    }

    PortalSet set;
    std::vector<Triangle> all;
    for (std::uint32_t node : chosen) {
        const std::string label = scene.nodeNames[node].empty() ? cat("node ", node)
                                                                : cat("node '", scene.nodeNames[node], "'");
        const std::string where = cat(scene.source, ": portal ", label);
        std::vector<Triangle> own = byNode[node];
        if (own.empty())
            throw Error(cat(where, " has no triangles (nor have its descendants)"));
        if (kind[node] == PortalMark::Hull) {
            std::vector<glm::dvec3> pts;
            for (const auto& t : own)
                for (const glm::vec3* p : {&t.p0, &t.p1, &t.p2})
                    pts.push_back(glm::dvec3(*p));
            own = convexHull(pts, where);
        }
        double nodeArea = 0.0;
        for (const auto& t : own)
            if (area(t) > 0.0) {
                all.push_back(t);
                nodeArea += area(t);
            }
        if (!(nodeArea > 0.0))
            throw Error(cat(where, " has zero area"));
        set.nodes.push_back(scene.nodeNames[node]);
    }

    // Group by plane orientation; keep each group's triangles together.
    std::vector<std::vector<std::size_t>> members;
    std::vector<glm::dvec3> normals;
    for (std::size_t t = 0; t < all.size(); ++t) {
        const glm::dvec3 n = canonicalNormal(all[t]);
        std::size_t g = 0;
        while (g < normals.size() && glm::dot(normals[g], n) < 1.0 - 1e-9)
            ++g;
        if (g == normals.size()) {
            normals.push_back(n);
            members.emplace_back();
        }
        members[g].push_back(t);
    }
    for (std::size_t g = 0; g < members.size(); ++g) {
        PortalGroup grp;
        grp.normal = normals[g];
        grp.first = static_cast<std::uint32_t>(set.triangles.size());
        grp.count = static_cast<std::uint32_t>(members[g].size());
        for (std::size_t t : members[g]) {
            set.triangles.push_back(all[t]);
            set.area_m2.push_back(area(all[t]));
            grp.area_m2 += set.area_m2.back();
        }
        set.area_m2_total += grp.area_m2;
        set.groups.push_back(grp);
    }
    return set;
}

}  // namespace fen
