// sensor_pictures.cpp — plan pictures of sensor planes (sensor_pictures.h).
#include "io/sensor_pictures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "io/sensor_planes.h"
#include "util/error.h"

namespace fen {

namespace {

std::string uniformityLabel(double mean, double minimum, const std::string& unit)
{
    if (std::isnan(mean))
        return "no data";
    char ratio[32];
    if (mean > 0.0)
        std::snprintf(ratio, sizeof ratio, "%.2f", minimum / mean);
    else
        std::snprintf(ratio, sizeof ratio, "-");
    return cat("mean ", compactNumber(mean), " ", unit, "  min/mean ", ratio);
}

std::string fileNamePart(const std::string& name)
{
    std::string out;
    for (const char c : name.substr(0, 100)) {
        const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                          c == '.' || c == '_' || c == '-';
        out += keep ? c : '_';
    }
    return out;
}

// The file name of each plane (see the header), checked for collisions.
std::vector<std::string> planePaths(const SensorFile& file, const std::vector<SensorPlane>& planes,
                                    const std::string& outPng)
{
    const std::string stem = outPng.substr(0, outPng.size() - 4), extension = outPng.substr(outPng.size() - 4);
    std::vector<std::string> paths;
    std::map<std::string, std::string> sensorOfFile;
    for (const SensorPlane& plane : planes) {
        std::string path = outPng;
        if (!paths.empty())
            path = cat(stem, "-", fileNamePart(plane.sensor), plane.count > 1 ? cat("-", plane.index) : "", extension);
        const auto [it, fresh] = sensorOfFile.emplace(path, plane.sensor);
        if (!fresh)
            throw Error(cat("sensors '", printable(it->second, 60), "' and '", printable(plane.sensor, 60),
                            "' would both be written to ", printable(path), "; rename one in ", printable(file.path)));
        paths.push_back(path);
    }
    return paths;
}

}  // namespace

std::vector<std::string> sensorPicturePaths(const SensorFile& file, const std::string& outPng)
{
    return planePaths(file, sensorPlanes(file), outPng);
}

std::vector<SensorPicture> sensorPictures(const SensorFile& file, bool df, FalseColorScale scale,
                                          const std::string& outPng, const std::optional<std::string>& title)
{
    std::vector<double> values;
    for (const SensorRow& r : file.rows)
        values.push_back(df ? r.daylightFactor : r.illuminance);
    return sensorPictures(file, values, df ? "daylight factor" : "illuminance", df ? "%" : "lux", scale, outPng, title);
}

std::vector<SensorPicture> sensorPictures(const SensorFile& file, const std::vector<double>& values,
                                          const std::string& quantity, const std::string& unit, FalseColorScale scale,
                                          const std::string& outPng, const std::optional<std::string>& title)
{
    if (values.size() != file.rows.size())
        throw Error(cat("internal error: ", values.size(), " values for the ", file.rows.size(), " cells of ",
                        printable(file.path)));
    const std::vector<SensorPlane> planes = sensorPlanes(file);
    const std::vector<std::string> paths = planePaths(file, planes, outPng);
    std::vector<SensorPicture> out;
    for (std::size_t p = 0; p < planes.size(); ++p) {
        const SensorPlane& plane = planes[p];
        std::vector<PlanCell> cells;
        double sum = 0.0, area = 0.0, minimum = INFINITY;
        for (std::size_t k = 0; k < plane.rows.size(); ++k) {
            const SensorRow& r = file.rows[plane.rows[k]];
            const double v = values[plane.rows[k]];
            cells.push_back({plane.u[k], plane.v[k], std::sqrt(r.area), v});
            if (!std::isnan(v)) {
                sum += v * r.area;
                area += r.area;
                minimum = std::min(minimum, v);
            }
        }
        const double mean = area > 0.0 ? sum / area : NAN;
        const std::string where = plane.count > 1 ? cat(plane.sensor, " (facing ", facing(plane), ")") : plane.sensor;
        const std::string label = uniformityLabel(mean, minimum, unit);
        scale.title = title ? *title : cat(quantity, ", ", where);
        SensorPicture pic;
        pic.path = paths[p];
        try {
            pic.png = falseColorPlanPng(cells, scale, label);
        } catch (const Error& e) {
            throw Error(cat(printable(file.path), ": sensor '", printable(plane.sensor, 60), "': ", e.what()));
        }
        pic.summary = cat(pic.path, ": ", quantity, " of ", where, ", ", cells.size(),
                          cells.size() == 1 ? " cell, " : " cells, ", label);
        out.push_back(std::move(pic));
    }
    return out;
}

}  // namespace fen
