// sensor_set_test.cpp — building sensors (sensor/sensor_set.h, points_file.h) and their device
// tables (device_sensors.h) on the host: lattices over triangles, work planes over floors however
// they are wound, a points file's spacing, every cell found where the kernel's lookup looks
// (lib/sensor.h, emulated here), and the jackknife against the plain standard error of a mean.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "sensor/device_sensors.h"
#include "sensor/points_file.h"
#include "sensor/sensor_set.h"
#include "sensor/sensor_smoothing.h"
#include "sensor/sensor_stats.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

std::vector<Triangle> square(glm::vec3 p, glm::vec3 u, glm::vec3 v)
{
    return {{p, p + u, p + u + v}, {p, p + u + v, p + v}};
}

TEST(SensorSet, ALatticeCoversTheTrianglesWithItsCentres)
{
    SensorSet set;
    // facing up (winding): a 1 x 1 m square at y = 2, cells of 0.25 m
    addMeshSensor(set, "sq", "node", "test", square({0, 2, 1}, {1, 0, 0}, {0, 0, -1}), 0.25);
    ASSERT_EQ(set.cells.size(), 16u);
    for (const SensorCell& c : set.cells) {
        EXPECT_NEAR(c.normal.y, 1.0, 1e-12);
        EXPECT_NEAR(c.position.y, 2.0, 1e-6);
        const double fx = c.position.x / 0.25 - 0.5, fz = c.position.z / 0.25 - 0.5;
        EXPECT_NEAR(fx, std::round(fx), 1e-6);
        EXPECT_NEAR(fz, std::round(fz), 1e-6);
    }
    // half of it: the cells whose centres lie on the triangle (10 of 16: the diagonal's included)
    addMeshSensor(set, "tri", "node", "test", {{{0, 0, 1}, {1, 0, 1}, {1, 0, 0}}}, 0.25);
    EXPECT_EQ(set.cellsOf(1), 10u);
    EXPECT_THROW(addMeshSensor(set, "sq", "node", "again", square({0, 3, 1}, {1, 0, 0}, {0, 0, -1}), 0.25), Error);
}

TEST(SensorSet, AWorkPlaneLiesAboveTheFloorWhicheverWayItIsWound)
{
    for (const bool down : {false, true}) {
        Scene scene;
        scene.source = "test";
        scene.nodeNames = {"room", "floor"};
        scene.nodeParent = {-1, 0};
        auto tris = square({0, 0.5f, 2}, {3, 0, 0}, {0, 0, -2});
        if (down)
            for (Triangle& t : tris)
                std::swap(t.p1, t.p2);
        tris.push_back({{0, 0.5f, 0}, {3, 0.5f, 0}, {3, 2.5f, 0}});  // a wall of the same node: ignored
        for (const Triangle& t : tris) {
            scene.triangles.push_back(t);
            scene.triangleNode.push_back(1);
            scene.triangleMaterial.push_back(0);
        }
        SensorSet set;
        addWorkPlane(set, scene, "room", 0.8, 0.5);  // a parent names its children's floors
        ASSERT_EQ(set.cells.size(), 24u) << down;
        for (const SensorCell& c : set.cells) {
            EXPECT_NEAR(c.position.y, 1.3, 1e-6);
            EXPECT_NEAR(c.normal.y, 1.0, 1e-12);
        }
        SensorSet none;
        EXPECT_THROW(addWorkPlane(none, scene, "nothing", 0.8, 0.5), Error);
    }
}

TEST(SensorSet, PointsTakeTheirOwnSpacing)
{
    const std::string path = test::tempDir("sensor-points") + "/grid.pts";
    {
        std::ofstream f(path);
        for (int i = 0; i < 30; ++i)
            for (int j = 0; j < 20; ++j)
                f << 0.1 + 0.036 * i << " 0.8 " << 0.2 + 0.036 * j << " 0 1 0\n";
    }
    SensorSet set;
    addPointsSensor(set, path, std::nullopt);
    ASSERT_EQ(set.cells.size(), 600u);
    EXPECT_NEAR(set.cells[0].side_m, 0.036, 1e-9);
    EXPECT_EQ(set.sensors[0].name, "grid");
    SensorSet sized;
    addPointsSensor(sized, path, 0.1);
    EXPECT_EQ(sized.cells[0].side_m, 0.1);
}

// The kernel's lookup (lib/sensor.h), in double: the cells whose squares hold the point.
std::vector<std::uint32_t> lookup(const SensorTables& t, glm::dvec3 x)
{
    std::vector<std::uint32_t> found;
    for (const auto& pl : t.planes) {
        const glm::dvec3 n(pl.normal.x, pl.normal.y, pl.normal.z), o(pl.origin.x, pl.origin.y, pl.origin.z);
        if (std::abs(glm::dot(n, x) - pl.origin.w) > 1e-4)
            continue;
        const glm::dvec3 d = x - o;
        const double u = glm::dot(d, glm::dvec3(pl.u_axis.x, pl.u_axis.y, pl.u_axis.z));
        const double v = glm::dot(d, glm::dvec3(pl.v_axis.x, pl.v_axis.y, pl.v_axis.z));
        const double fu = u * pl.normal.w, fv = v * pl.normal.w;
        if (!(fu >= 0 && fv >= 0 && fu < pl.cols && fv < pl.rows))
            continue;
        const std::uint32_t b = pl.bucket_first + static_cast<std::uint32_t>(fv) * pl.cols + static_cast<std::uint32_t>(fu);
        for (std::uint32_t i = t.bucketStart[b]; i < t.bucketStart[b + 1]; ++i) {
            const auto& c = t.cells[t.bucketCells[i]];
            if (u - c.u >= -c.half_side && u - c.u < c.half_side && v - c.v >= -c.half_side && v - c.v < c.half_side)
                found.push_back(t.bucketCells[i]);
        }
    }
    return found;
}

TEST(SensorTables, EveryCellIsFoundWhereItIsAndNowhereElse)
{
    SensorSet set;
    addMeshSensor(set, "floor", "node", "test", square({0, 0.8f, 3}, {4, 0, 0}, {0, 0, -3}), 0.25);
    addMeshSensor(set, "wall", "node", "test", square({0, 0, 0}, {2, 0, 0}, {0, 2, 0}), 0.5);
    // scattered points, far apart: buckets larger than the cells
    const std::string path = test::tempDir("sensor-tables") + "/few.pts";
    std::ofstream(path) << "10 1 10 0 1 0\n20 1 13 0 1 0\n-5 1 40 0 1 0\n";
    addPointsSensor(set, path, 0.2);
    const SensorTables t = makeSensorTables(set, 1.0f);
    EXPECT_EQ(t.info.cells, set.cells.size());
    EXPECT_EQ(t.planes.size(), 3u);  // floor, wall, the points' plane y = 1
    for (std::uint32_t c = 0; c < set.cells.size(); ++c) {
        const SensorCell& cell = set.cells[c];
        glm::dvec3 u, v;
        sensorPlaneAxes(cell.normal, &u, &v);
        for (const double su : {-0.49, 0.0, 0.49})
            for (const double sv : {-0.49, 0.0, 0.49}) {
                const auto f = lookup(t, cell.position + cell.side_m * (su * u + sv * v));
                ASSERT_EQ(f.size(), 1u) << "cell " << c;
                EXPECT_EQ(f[0], c);
            }
        EXPECT_TRUE(lookup(t, cell.position + cell.side_m * 0.51 * u + cell.normal * 0.01).empty());
    }
    // between the points: nothing
    EXPECT_TRUE(lookup(t, {15, 1, 11}).empty());
}

TEST(SensorStatistics, TheJackknifeOfAMeanIsItsStandardError)
{
    // For the mean over cells (linear), the jackknife equals the spread of the batch means.
    SensorStatistics s(3);
    const std::vector<std::vector<double>> batches = {{1, 2, 3}, {2, 2, 5}, {0, 4, 3}, {3, 1, 2}};
    std::vector<double> means;
    for (const auto& b : batches) {
        s.add(b);
        means.push_back((b[0] + b[1] + b[2]) / 3.0);
    }
    double m = 0.0, ss = 0.0;
    for (double x : means)
        m += x / 4.0;
    for (double x : means)
        ss += (x - m) * (x - m);
    const double se = std::sqrt(ss / 3.0 / 4.0);
    const auto e = s.jackknife([](const std::vector<double>& v) { return (v[0] + v[1] + v[2]) / 3.0; });
    EXPECT_NEAR(e.value, m, 1e-12);
    EXPECT_NEAR(e.stdErr, se, 1e-6);
    EXPECT_NEAR(s.stdErr()[0], std::sqrt(5.0 / 3.0 / 4.0), 1e-6);  // cell 0: 1, 2, 0, 3 about 1.5
}

}  // namespace
}  // namespace fen

namespace fen {
namespace {

TEST(SensorSmoothing, KeepsLinearFieldsAndCutsNoise)
{
    // A 2 x 1.5 m grid of 5 cm cells: a constant field stays constant everywhere, a linear one
    // stays linear wherever the cell's neighbourhood is balanced (the interior), and independent
    // noise of variance s^2 leaves about s^2 / (cells in the fit) in the interior.
    SensorSet set;
    addMeshSensor(set, "g", "node", "test", square({0, 1, 1.5f}, {2, 0, 0}, {0, 0, -1.5f}), 0.05);
    ASSERT_EQ(set.cells.size(), 1200u);
    const SensorSmoother s(set, 0.2, nullptr);
    EXPECT_GT(s.meanNeighbours(), 20.0);
    std::vector<double> flat(set.cells.size(), 7.0), lin(set.cells.size());
    for (std::size_t c = 0; c < lin.size(); ++c)
        lin[c] = 100.0 + 30.0 * set.cells[c].position.x - 50.0 * set.cells[c].position.z;
    const auto f = s.apply(flat), l = s.apply(lin);
    std::size_t interior = 0;
    for (std::size_t c = 0; c < lin.size(); ++c) {
        EXPECT_NEAR(f[c], 7.0, 1e-9);
        const glm::dvec3 p = set.cells[c].position;
        if (p.x > 0.25 && p.x < 1.75 && p.z > 0.25 && p.z < 1.25) {
            ++interior;
            EXPECT_NEAR(l[c], lin[c], 1e-9) << c;
        }
    }
    EXPECT_GT(interior, 400u);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 1.0);
    double var = 0.0;
    std::size_t n = 0;
    for (int rep = 0; rep < 20; ++rep) {
        std::vector<double> x(set.cells.size());
        for (double& v : x)
            v = noise(rng);
        const auto y = s.apply(x);
        for (std::size_t c = 0; c < y.size(); ++c) {
            const glm::dvec3 p = set.cells[c].position;
            if (p.x > 0.25 && p.x < 1.75 && p.z > 0.25 && p.z < 1.25) {
                var += y[c] * y[c];
                ++n;
            }
        }
    }
    EXPECT_LT(var / static_cast<double>(n), 0.15);  // from 1: at least 6.7x less variance
}

}  // namespace
}  // namespace fen

namespace fen {
namespace {

TEST(SensorSmoothing, NeverReachesAcrossAWall)
{
    // One grid over two rooms, a wall at x = 1 between them: dark on one side, bright on the
    // other, and no cell's fit may take a cell it cannot see.
    SensorSet set;
    addMeshSensor(set, "g", "node", "test", square({0, 1, 1}, {2, 0, 0}, {0, 0, -1}), 0.05);
    Scene scene;
    scene.triangles = square({1, 0, 2}, {0, 0, -3}, {0, 3, 0});  // the plane x = 1
    std::vector<double> lux(set.cells.size());
    for (std::size_t c = 0; c < lux.size(); ++c)
        lux[c] = set.cells[c].position.x < 1.0 ? 0.0 : 1000.0;
    const auto walled = SensorSmoother(set, 0.2, &scene).apply(lux);
    const auto open = SensorSmoother(set, 0.2, nullptr).apply(lux);
    double leakWalled = 0.0, leakOpen = 0.0;
    for (std::size_t c = 0; c < lux.size(); ++c)
        if (set.cells[c].position.x < 1.0) {
            leakWalled = std::max(leakWalled, std::abs(walled[c]));
            leakOpen = std::max(leakOpen, std::abs(open[c]));
        }
    EXPECT_EQ(leakWalled, 0.0);
    EXPECT_GT(leakOpen, 10.0) << "without the wall the fit does reach across: the test can fail";
}

}  // namespace
}  // namespace fen
