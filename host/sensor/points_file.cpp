// points_file.cpp — reading a Radiance points file into sensor cells (points_file.h).
#include "sensor/points_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "util/error.h"

namespace fen {

namespace {

// Median over the points of the distance to the nearest other point (0 with one point): a hash
// grid of buckets about the typical spacing, searched outwards ring by ring until a neighbour is
// found and no nearer one can be in the next ring.
double medianSpacing(const std::vector<glm::dvec3>& pts)
{
    if (pts.size() < 2)
        return 0.0;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& p : pts) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::dvec3 e = hi - lo;
    // Points on a plane or a line: the bucket from the extent spread over the points' dimension.
    int dims = 0;
    double volume = 1.0;
    const double span = std::max({e.x, e.y, e.z});
    for (int k = 0; k < 3; ++k)
        if (e[k] > 1e-6 * span) {
            ++dims;
            volume *= e[k];
        }
    if (dims == 0)
        return 0.0;  // all at one point
    const double h = std::max(std::pow(volume / static_cast<double>(pts.size()), 1.0 / dims), 1e-9 * span);
    using Key = std::tuple<long long, long long, long long>;
    std::map<Key, std::vector<std::size_t>> grid;
    const auto key = [&](const glm::dvec3& p) {
        return Key{static_cast<long long>(std::floor((p.x - lo.x) / h)), static_cast<long long>(std::floor((p.y - lo.y) / h)),
                   static_cast<long long>(std::floor((p.z - lo.z) / h))};
    };
    for (std::size_t i = 0; i < pts.size(); ++i)
        grid[key(pts[i])].push_back(i);
    std::vector<double> nearest(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto [kx, ky, kz] = key(pts[i]);
        double best = INFINITY;
        for (long long r = 0;; ++r) {
            // ring r: the buckets at Chebyshev distance r
            for (long long x = kx - r; x <= kx + r; ++x)
                for (long long y = ky - r; y <= ky + r; ++y)
                    for (long long z = kz - r; z <= kz + r; ++z) {
                        if (std::max({std::llabs(x - kx), std::llabs(y - ky), std::llabs(z - kz)}) != r)
                            continue;
                        const auto it = grid.find({x, y, z});
                        if (it == grid.end())
                            continue;
                        for (std::size_t j : it->second)
                            if (j != i) {
                                const double d = glm::length(pts[j] - pts[i]);
                                if (d > 0.0)
                                    best = std::min(best, d);
                            }
                    }
            if (best <= static_cast<double>(r) * h || r > 64)
                break;
        }
        nearest[i] = best;
    }
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
    const double m = nearest[nearest.size() / 2];
    return std::isfinite(m) ? m : 0.0;
}

}  // namespace

void addPointsSensor(SensorSet& set, const std::string& path, std::optional<double> side_m)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error(cat(printable(path), ": --sensor-points: no such file (or not a regular file)"));
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(cat(printable(path), ": --sensor-points: cannot be read"));
    std::vector<glm::dvec3> pos, dir;
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.size() > 4096)
            throw Error(cat(printable(path), ":", number, ": a line of more than 4096 characters"));
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::istringstream s(line);
        s.imbue(std::locale::classic());
        double v[6];
        int k = 0;
        std::string word;
        while (s >> word) {
            if (k == 6)
                throw Error(cat(printable(path), ":", number, ": more than six numbers (expected x y z dx dy dz)"));
            char* end = nullptr;
            v[k] = std::strtod(word.c_str(), &end);
            if (end != word.c_str() + word.size() || !std::isfinite(v[k]))
                throw Error(cat(printable(path), ":", number, ": '", printable(word, 40),
                                "' is not a finite number (expected x y z dx dy dz)"));
            ++k;
        }
        if (k != 6)
            throw Error(cat(printable(path), ":", number, ": ", k, " numbers; expected six, x y z dx dy dz"));
        const glm::dvec3 d(v[3], v[4], v[5]);
        const double l = glm::length(d);
        if (!(l > 0.0) || !std::isfinite(l))
            throw Error(cat(printable(path), ":", number, ": the direction (dx dy dz) is zero; it says which side the "
                                                       "point measures"));
        if (pos.size() >= kMaxSensorCells)
            throw Error(cat(printable(path), ": more than ", kMaxSensorCells, " points"));
        pos.emplace_back(v[0], v[1], v[2]);
        dir.push_back(d / l);
    }
    if (in.bad())
        throw Error(cat(printable(path), ": --sensor-points: a read error"));
    if (pos.empty())
        throw Error(cat(printable(path), ": --sensor-points: no points in the file"));
    double side = 0.0;
    if (side_m) {
        side = *side_m;
        if (!(side > 0.0) || !std::isfinite(side) || side > 1e4)
            throw Error(cat("--sensor-size ", side, ": must be a cell side in metres, more than 0 and at most 10 km"));
    } else {
        side = medianSpacing(pos);
        if (!(side > 0.0))
            throw Error(cat(printable(path), ": one point, or all at one place: give its cell's side with --sensor-size"));
    }
    if (set.cells.size() + pos.size() > kMaxSensorCells)
        throw Error(cat(printable(path), ": more than ", kMaxSensorCells, " sensor cells in all"));
    std::string name = std::filesystem::path(path).stem().string();
    if (name.empty())
        name = "points";
    for (const SensorInfo& s : set.sensors)
        if (s.name == name)
            throw Error(cat(printable(path), ": a second sensor named '", printable(name, 60), "' (the first: ",
                            s.source, ")"));
    const std::uint32_t index = static_cast<std::uint32_t>(set.sensors.size());
    for (std::size_t i = 0; i < pos.size(); ++i)
        set.cells.push_back({pos[i], dir[i], side, index});
    set.sensors.push_back({name, "points", cat("--sensor-points ", printable(path))});
}

}  // namespace fen
