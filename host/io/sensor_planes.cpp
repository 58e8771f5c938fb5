// sensor_planes.cpp — grouping sensor cells into planes and their plane coordinates (sensor_planes.h).
#include "io/sensor_planes.h"

#include <cmath>
#include <cstdio>

namespace fen {

namespace {

const double kSameDirection = std::cos(5.0 * std::acos(-1.0) / 180.0);  // 5°

struct Vec {
    double x, y, z;
};
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec normalised(Vec a)
{
    const double n = std::sqrt(dot(a, a));
    return {a.x / n, a.y / n, a.z / n};
}

}  // namespace

std::vector<SensorPlane> sensorPlanes(const SensorFile& file)
{
    std::vector<SensorPlane> planes;
    for (std::size_t i = 0; i < file.rows.size(); ++i) {
        const SensorRow& r = file.rows[i];
        const Vec n{r.nx, r.ny, r.nz};
        SensorPlane* plane = nullptr;
        int ofSensor = 0;
        for (SensorPlane& p : planes) {
            if (p.sensor != r.sensor)
                continue;
            ++ofSensor;
            if (dot(n, {p.nx, p.ny, p.nz}) >= kSameDirection) {
                plane = &p;
                break;
            }
        }
        if (plane == nullptr) {
            planes.emplace_back();
            plane = &planes.back();
            plane->sensor = r.sensor;
            plane->nx = r.nx;
            plane->ny = r.ny;
            plane->nz = r.nz;
            plane->horizontal = std::fabs(r.ny) >= kSameDirection;
            plane->index = ofSensor + 1;
        }
        plane->rows.push_back(i);
    }
    for (SensorPlane& p : planes) {
        for (const SensorPlane& q : planes)
            if (q.sensor == p.sensor)
                p.count = std::max(p.count, q.index);
        const Vec n{p.nx, p.ny, p.nz};
        const Vec right = p.horizontal ? Vec{1, 0, 0} : normalised(cross({0, 1, 0}, n));
        const Vec down = p.horizontal ? Vec{0, 0, 1} : cross(right, n);
        for (const std::size_t i : p.rows) {
            const SensorRow& r = file.rows[i];
            p.u.push_back(dot({r.x, r.y, r.z}, right));
            p.v.push_back(dot({r.x, r.y, r.z}, down));
        }
    }
    return planes;
}

std::string facing(const SensorPlane& p)
{
    if (p.horizontal)
        return p.ny > 0 ? "up" : "down";
    static const struct {
        Vec direction;
        const char* name;
    } compass[] = {{{0, 0, -1}, "north"}, {{1, 0, 0}, "east"}, {{0, 0, 1}, "south"}, {{-1, 0, 0}, "west"}};
    for (const auto& c : compass)
        if (dot({p.nx, p.ny, p.nz}, c.direction) >= kSameDirection)
            return c.name;
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.2g, %.2g, %.2g)", p.nx, p.ny, p.nz);
    return buf;
}

}  // namespace fen
