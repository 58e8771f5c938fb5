// sensor_smoothing.cpp — local linear regression over a sensor grid's cells (sensor_smoothing.h).
#include "sensor/sensor_smoothing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "bvh_build.h"
#include "bvh_flat.h"
#include "bvh_traverse_ref.h"
#include "util/error.h"

namespace fen {

SensorSmoother::SensorSmoother(const SensorSet& set, double radius_m, const Scene* scene) : radius_(radius_m)
{
    if (!(radius_m > 0.0) || !std::isfinite(radius_m))
        throw Error(cat("--sensor-smoothing ", radius_m, ": must be a radius in metres, more than 0"));
    // What separates cells: the scene's triangles, in the CPU reference traversal.
    std::optional<FlatBvh> bvh;
    if (scene && !scene->triangles.empty())
        bvh = flattenBvh(buildBinnedSah(scene->triangles), scene->triangles, 2);
    const auto sees = [&](const glm::dvec3& a, const glm::dvec3& b) {
        if (!bvh)
            return true;
        const glm::dvec3 d = b - a;
        const double len = glm::length(d);
        if (!(len > 0.0))
            return true;
        RefRay ray;
        ray.org = glm::vec3(a);
        ray.dir = glm::vec3(d / len);
        ray.tmin = 0.0f;
        ray.tmax = static_cast<float>(len);
        return !traceAnyRef(*bvh, ray);
    };
    const std::size_t n = set.cells.size();
    // Cells by sensor and plane, then by a 2D hash of R-sized buckets in the plane.
    using PlaneKey = std::tuple<std::uint32_t, long long, long long, long long, long long>;
    std::map<PlaneKey, std::vector<std::uint32_t>> planes;
    for (std::uint32_t i = 0; i < n; ++i) {
        const SensorCell& c = set.cells[i];
        planes[{c.sensor, std::llround(c.normal.x * 1e4), std::llround(c.normal.y * 1e4), std::llround(c.normal.z * 1e4),
                std::llround(glm::dot(c.normal, c.position) * 1e4)}]
            .push_back(i);
    }
    std::vector<std::vector<std::pair<std::uint32_t, double>>> rows(n);
    for (const auto& [key, members] : planes) {
        glm::dvec3 u, v;
        sensorPlaneAxes(set.cells[members.front()].normal, &u, &v);
        std::vector<glm::dvec2> at(members.size());
        std::map<std::pair<long long, long long>, std::vector<std::size_t>> grid;
        for (std::size_t k = 0; k < members.size(); ++k) {
            const glm::dvec3& p = set.cells[members[k]].position;
            at[k] = {glm::dot(p, u), glm::dot(p, v)};
            grid[{static_cast<long long>(std::floor(at[k].x / radius_m)), static_cast<long long>(std::floor(at[k].y / radius_m))}]
                .push_back(k);
        }
        for (std::size_t k = 0; k < members.size(); ++k) {
            const long long gx = static_cast<long long>(std::floor(at[k].x / radius_m));
            const long long gy = static_cast<long long>(std::floor(at[k].y / radius_m));
            // The cells within R, with their tricube weights. Where the neighbourhood is lopsided
            // (the grid's edge: a wall), a fit leaning on one side would extrapolate the field's
            // steepest change, across the edge; there the kernel narrows across the edge to the
            // cell's own row (within 0.6 of the nearest cell's distance) and keeps R along it.
            std::vector<std::pair<std::size_t, double>> near;  // (member, tricube weight)
            std::vector<std::pair<std::size_t, glm::dvec2>> within;
            glm::dvec2 centroid(0.0);
            double wsum = 0.0, nearest = INFINITY;
            for (long long x = gx - 1; x <= gx + 1; ++x)
                for (long long y = gy - 1; y <= gy + 1; ++y) {
                    const auto it = grid.find({x, y});
                    if (it == grid.end())
                        continue;
                    for (std::size_t m : it->second) {
                        const glm::dvec2 delta = at[m] - at[k];
                        const double dist = glm::length(delta);
                        if (m != k)
                            nearest = std::min(nearest, dist);
                        if (dist < radius_m && (m == k || sees(set.cells[members[k]].position, set.cells[members[m]].position))) {
                            const double t = 1.0 - std::pow(dist / radius_m, 3.0);
                            within.emplace_back(m, delta);
                            centroid += t * t * t * delta;
                            wsum += t * t * t;
                        }
                    }
                }
            const glm::dvec2 lean = centroid / wsum;
            const bool lopsided = glm::length(lean) > 0.1 * radius_m;
            const glm::dvec2 across = lopsided ? glm::normalize(lean) : glm::dvec2(1.0, 0.0);
            const glm::dvec2 along(-across.y, across.x);
            const double narrow = 0.6 * (std::isfinite(nearest) ? nearest : radius_m);
            for (const auto& [m, delta] : within) {
                const double a = glm::dot(delta, across), b = glm::dot(delta, along);
                const double d = lopsided ? std::sqrt((a / narrow) * (a / narrow) + (b / radius_m) * (b / radius_m))
                                          : glm::length(delta) / radius_m;
                if (d < 1.0) {
                    const double t = 1.0 - d * d * d;
                    near.emplace_back(m, t * t * t);
                }
            }
            // Normal equations of the weighted fit a + b du + c dv; the weight of each neighbour
            // in a is e1' M^-1 (1, du, dv) w.
            double M[3][3] = {};
            for (const auto& [m, w] : near) {
                const double x[3] = {1.0, at[m].x - at[k].x, at[m].y - at[k].y};
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c)
                        M[r][c] += w * x[r] * x[c];
            }
            // The first row of M^-1 by cofactors; scaled determinant to judge conditioning.
            const double c0 = M[1][1] * M[2][2] - M[1][2] * M[2][1];
            const double c1 = -(M[1][0] * M[2][2] - M[1][2] * M[2][0]);
            const double c2 = M[1][0] * M[2][1] - M[1][1] * M[2][0];
            const double det = M[0][0] * c0 + M[0][1] * c1 + M[0][2] * c2;
            const double scale = M[0][0] * M[1][1] * M[2][2];
            auto& row = rows[members[k]];
            if (near.size() >= 3 && scale > 0.0 && det > 1e-6 * scale) {
                for (const auto& [m, w] : near) {
                    const double x[3] = {1.0, at[m].x - at[k].x, at[m].y - at[k].y};
                    row.emplace_back(members[m], w * (c0 * x[0] + c1 * x[1] + c2 * x[2]) / det);
                }
            } else {
                double sum = 0.0;
                for (const auto& nw : near)
                    sum += nw.second;
                for (const auto& [m, w] : near)
                    row.emplace_back(members[m], w / sum);
            }
        }
    }
    first_.push_back(0);
    for (const auto& row : rows) {
        for (const auto& [c, w] : row) {
            cell_.push_back(c);
            weight_.push_back(w);
        }
        first_.push_back(static_cast<std::uint32_t>(cell_.size()));
    }
}

std::vector<double> SensorSmoother::apply(const std::vector<double>& in) const
{
    std::vector<double> out(first_.size() - 1, 0.0);
    for (std::size_t c = 0; c + 1 < first_.size(); ++c)
        for (std::uint32_t i = first_[c]; i < first_[c + 1]; ++i)
            out[c] += weight_[i] * in[cell_[i]];
    return out;
}

double SensorSmoother::meanNeighbours() const
{
    return first_.size() > 1 ? static_cast<double>(cell_.size()) / static_cast<double>(first_.size() - 1) : 0.0;
}

}  // namespace fen
