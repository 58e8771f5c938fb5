// sensor_planes.h — a sensor file's cells grouped into the planes they lie on, and laid out flat
// for a plan picture (io/false_color.h's falseColorPlanPng).
//
// A plane is the cells of one sensor name whose normals lie within 5° of its first cell's: each
// cell, in file order, joins the first such plane of its sensor or starts a new one. Planes come
// in the order of their first cell. A horizontal plane (normal within 5° of +y or −y) is seen
// from above, north (−z) up: u = x, v = z. Any other plane is seen from the side its normal
// points to, upright: u runs horizontally to the viewer's right (along y × n), v down the plane
// (along u × n, so that +y is up in the picture). Parallel planes of one sensor at different
// offsets are one plane, drawn together.
#pragma once

#include <string>
#include <vector>

#include "io/sensor_csv.h"

namespace fen {

struct SensorPlane {
    std::string sensor;
    double nx = 0, ny = 1, nz = 0;   // the plane's normal: its first cell's
    bool horizontal = true;
    int index = 1, count = 1;        // the sensor's index-th plane (from 1, in file order) of count
    std::vector<std::size_t> rows;   // its cells: indices into SensorFile::rows, in file order
    std::vector<double> u, v;        // each cell's centre in plane coordinates (m)
};

std::vector<SensorPlane> sensorPlanes(const SensorFile& file);

// Which way a plane faces, in words: "up", "down", "north", "east", "south", "west" (within 5°),
// else its normal, "(0.71, 0.71, 0)".
std::string facing(const SensorPlane& plane);

}  // namespace fen
