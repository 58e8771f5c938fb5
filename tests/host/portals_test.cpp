// portals_test.cpp — choosing portal triangles: marking and --portals, convex hulls of frames,
// grouping by plane, and the errors for sets that cannot emit anything.
#include <gtest/gtest.h>

#include "emission/portals.h"
#include "support/render_support.h"
#include "util/error.h"

namespace fen {
namespace {

using test::rect;

double totalArea(const std::vector<Triangle>& t)
{
    double a = 0.0;
    for (const auto& x : t)
        a += 0.5 * doubleArea2(x);
    return a;
}

TEST(Portals, PlanarFrameHullIsTheOpening)
{
    // A 1 x 0.5 m opening in the plane z = 2 framed by four 2 cm strips: the hull is the outer
    // rectangle of the frame, 1.04 x 0.54 m, as a flat polygon.
    std::vector<glm::dvec3> pts;
    for (const auto& r : {rect({-0.02f, -0.02f, 2}, {1.04f, 0, 0}, {0, 0.02f, 0}),
                          rect({-0.02f, 0.5f, 2}, {1.04f, 0, 0}, {0, 0.02f, 0}),
                          rect({-0.02f, 0, 2}, {0.02f, 0, 0}, {0, 0.5f, 0}),
                          rect({1.0f, 0, 2}, {0.02f, 0, 0}, {0, 0.5f, 0})})
        for (const auto& t : r)
            for (const glm::vec3* p : {&t.p0, &t.p1, &t.p2})
                pts.push_back(glm::dvec3(*p));
    const auto hull = convexHull(pts, "frame");
    EXPECT_NEAR(totalArea(hull), 1.04 * 0.54, 1e-6);
    for (const auto& t : hull)
        EXPECT_NEAR(t.p0.z, 2.0f, 1e-6);
}

TEST(Portals, SpatialHullIsClosed)
{
    std::vector<glm::dvec3> cube;
    for (int i = 0; i < 8; ++i)
        cube.push_back(glm::dvec3(i & 1, (i >> 1) & 1, (i >> 2) & 1) * 2.0);
    cube.push_back({1, 1, 1});  // inside: must not appear
    const auto hull = convexHull(cube, "box");
    EXPECT_EQ(hull.size(), 12u);
    EXPECT_NEAR(totalArea(hull), 24.0, 1e-9);
}

TEST(Portals, CollinearFrameIsAnError)
{
    EXPECT_THROW(convexHull({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, "frame"), Error);
    EXPECT_THROW(convexHull({{0, 0, 0}, {1, 0, 0}}, "frame"), Error);
}

Scene twoWindows()
{
    test::SceneBuilder b;
    const int wall = b.material("wall", glm::vec3(0.5f));
    b.add("room", rect({0, 0, 0}, {3, 0, 0}, {0, 0, 3}), wall);
    // two coplanar panes (one group), and one facing the other way (the same plane orientation)
    b.add("south", rect({0.5f, 1, 3}, {1, 0, 0}, {0, 1, 0}), wall, PortalMark::Panes);
    b.add("south_b", rect({2, 1, 3}, {0, 1, 0}, {0.5f, 0, 0}), wall, PortalMark::Panes);
    b.add("east", rect({3, 1, 1}, {0, 0, 1}, {0, 1, 0}), wall, PortalMark::Panes);
    b.add("skylight", rect({1, 2.5f, 1}, {1, 0, 0}, {0, 0, 1}), wall);
    b.add("flat", {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}}, wall);
    return b.build();
}

TEST(Portals, MarkingGroupsByPlane)
{
    const PortalSet s = collectPortals(twoWindows(), "");
    EXPECT_EQ(s.triangles.size(), 6u);
    ASSERT_EQ(s.groups.size(), 2u);  // z-facing (both windows, either winding), x-facing
    EXPECT_NEAR(s.area_m2_total, 1.0 + 0.5 + 1.0, 1e-9);
    EXPECT_NEAR(s.projectedArea({0, 0, 1}), 1.5, 1e-9);
    EXPECT_NEAR(s.projectedArea({1, 0, 0}), 1.0, 1e-9);
    for (const auto& g : s.groups)
        for (std::uint32_t t = g.first; t < g.first + g.count; ++t)
            EXPECT_NEAR(std::fabs(glm::dot(glm::normalize(glm::cross(glm::dvec3(s.triangles[t].p1 - s.triangles[t].p0),
                                                                     glm::dvec3(s.triangles[t].p2 - s.triangles[t].p0))),
                                           g.normal)),
                        1.0, 1e-9);
}

TEST(Portals, SinglePlaneOnlyWhenEveryTriangleIsInIt)
{
    // Portal emission skips counting N(x, v) when no line can cross two portal triangles: two
    // panes in the plane z = 3 qualify; a parallel pane a millimetre behind, or one on another
    // wall, does not.
    const Scene scene = twoWindows();
    EXPECT_TRUE(collectPortals(scene, "south,south_b").singlePlane());
    EXPECT_TRUE(collectPortals(scene, "east").singlePlane());
    EXPECT_FALSE(collectPortals(scene, "south,east").singlePlane());
    test::SceneBuilder b;
    const int glass = b.material("glass", glm::vec3(0.5f));
    b.add("front", rect({0, 0, 3}, {1, 0, 0}, {0, 1, 0}), glass, PortalMark::Panes);
    b.add("back", rect({0, 0, 3.001f}, {1, 0, 0}, {0, 1, 0}), glass, PortalMark::Panes);
    const Scene doubled = b.build();
    EXPECT_EQ(collectPortals(doubled, "").groups.size(), 1u);  // one orientation, two planes
    EXPECT_FALSE(collectPortals(doubled, "").singlePlane());
    EXPECT_TRUE(collectPortals(doubled, "front").singlePlane());
}

TEST(Portals, OverrideAndErrors)
{
    const Scene scene = twoWindows();
    EXPECT_EQ(collectPortals(scene, "skylight").triangles.size(), 2u);
    EXPECT_EQ(collectPortals(scene, " skylight , east ").groups.size(), 2u);
    // a pane forced to a hull: its hull is itself (a rectangle)
    EXPECT_NEAR(collectPortals(scene, "skylight:hull").area_m2_total, 1.0, 1e-9);
    EXPECT_THROW(collectPortals(scene, "skylight:round"), Error);
    auto message = [&](const std::string& o) {
        try {
            collectPortals(scene, o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message("nope").find("no node named 'nope'"), std::string::npos);
    EXPECT_NE(message("flat").find("zero area"), std::string::npos);
    EXPECT_NE(message(",").find("no node names"), std::string::npos);
    Scene unmarked = scene;
    for (auto& m : unmarked.nodePortal)
        m = PortalMark::None;
    EXPECT_NE([&] {
        try {
            collectPortals(unmarked, "");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    }().find("no portals"), std::string::npos);
}

}  // namespace
}  // namespace fen
