// sensor_set.h — the sensors of a render: named sets of square cells that measure the illuminance
// arriving at one side, and block nothing (DESIGN.md §8). Three ways to give one:
//   - a glTF node marked `"extras": {"sensor": true}` or `{"sensor": {"cell_m": 0.25}}`: its
//     triangles, grouped by plane, are covered by a lattice of cells of that side whose centres
//     lie on them, facing the side the triangles' winding makes their normal point to;
//   - a work plane (`--work-plane NODE`): the upward-facing triangles of a node (its floors),
//     lifted by a height, covered by a lattice of the given spacing, facing up;
//   - a points file (`--sensor-points FILE`, sensor/points_file.h): one cell per point, of a
//     given side or, by default, the points' own spacing.
// Invariants: every cell has a unit normal and a positive, finite side; cells keep their order
// (points: the file's), which is the CSV's row order; at most kMaxSensorCells cells in all.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace fen {

constexpr std::size_t kMaxSensorCells = std::size_t{1} << 22;

struct SensorCell {
    glm::dvec3 position{0.0};  // centre (m)
    glm::dvec3 normal{0.0, 1.0, 0.0};  // unit: the side it faces
    double side_m = 0.0;       // the square's side
    std::uint32_t sensor = 0;  // SensorSet::sensors index
};

struct SensorInfo {
    std::string name;  // node name, "workplane", or the points file's stem
    std::string kind;  // "node", "work plane", "points"
    std::string source;  // what it came from, for messages: "room.gltf: nodes[3] 'desk'", "--work-plane floor"
};

struct SensorSet {
    std::vector<SensorInfo> sensors;
    std::vector<SensorCell> cells;
    bool empty() const { return cells.empty(); }
    std::size_t cellsOf(std::uint32_t sensor) const;
};

// Two unit axes in the plane of unit normal n, (u, v, n) right-handed up to v's sign: for a floor
// or a ceiling u = +x and v = +z, so a plan's rows run from north (-z) to south; otherwise u is
// horizontal and v = n x u points up the wall.
void sensorPlaneAxes(const glm::dvec3& n, glm::dvec3* u, glm::dvec3* v);

// Cells of side `cell_m` covering the triangles (grouped by plane) with their centres on them.
// Throws, naming `source`, when no cell centre lands on any triangle (the mesh is smaller than a
// cell) or when the cells would exceed the limit.
void addMeshSensor(SensorSet& set, const std::string& name, const std::string& kind, const std::string& source,
                   const std::vector<Triangle>& triangles, double cell_m);

// The work plane over the upward-facing triangles of node `node` (and its children) of the scene,
// `height_m` above them, cells of side `spacing_m`. Throws naming the node when there is no such
// node, or it has no upward-facing triangle.
void addWorkPlane(SensorSet& set, const Scene& scene, const std::string& node, double height_m, double spacing_m);

// The box around every cell's square. Emission (the uniform box, the emission sphere) covers the
// scene's bounds, and light must be emitted where a sensor can see it: the render grows the scene's
// bounds by this.
Aabb sensorBounds(const SensorSet& set);

// The sensors the scene's nodes carry (Scene::sensorMeshes).
void addSceneSensors(SensorSet& set, const Scene& scene);

}  // namespace fen
