// sensor_pictures.h — a sensor file's planes as false-colour plan pictures (io/false_color.h,
// io/sensor_planes.h), for `fenestra falsecolor` over a CSV and for a render's own sensors.
//
// One PNG per plane, on one shared scale (colours compare across planes): the first plane is
// written to OUT.png itself, each other to OUT-<sensor>.png, or OUT-<sensor>-<k>.png when a sensor
// has several planes (bytes outside A-Za-z0-9._- in the name become '_'). Each picture is labelled
// with the plane's area-weighted mean and min/mean uniformity; its title names the quantity and
// the sensor. Two planes that would share a file name are an error naming both sensors.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/false_color.h"
#include "io/sensor_csv.h"

namespace fen {

struct SensorPicture {
    std::string path;     // where it goes
    std::string png;      // the encoded file (empty from sensorPicturePaths)
    std::string summary;  // one line: the path, the quantity, the plane, its cells and its label
};

// The pictures of `file`'s planes: daylight factor (% DF) when `df`, else illuminance (lux), on
// `scale`; `title` replaces each picture's own.
std::vector<SensorPicture> sensorPictures(const SensorFile& file, bool df, FalseColorScale scale,
                                          const std::string& outPng, const std::optional<std::string>& title = {});
// The same for any per-cell quantity: `values` in the file's row order, named `quantity` in `unit`.
std::vector<SensorPicture> sensorPictures(const SensorFile& file, const std::vector<double>& values,
                                          const std::string& quantity, const std::string& unit, FalseColorScale scale,
                                          const std::string& outPng, const std::optional<std::string>& title = {});
// Their paths alone, for a render to claim its outputs before it has values to draw.
std::vector<std::string> sensorPicturePaths(const SensorFile& file, const std::string& outPng);

}  // namespace fen
