// sensor_options.h — the sensor and daylight-factor options of `fenestra render` (DESIGN.md §8):
//   --sensor-points FILE        a Radiance points file (x y z dx dy dz per line); repeatable
//   --sensor-size M             the side of a point's cell (default: the points' own spacing)
//   --work-plane NODE           a work plane over the floors of the node NODE
//   --work-plane-height M       ... this high above them (default 0.8 m)
//   --sensor-spacing M          ... cells of this side (default 0.25 m)
//   --sensor-smoothing R        report each cell by a local linear fit over the cells within R m
//                               (sensor/sensor_smoothing.h; off by default)
//   --no-image                  render the sensors alone (no camera, no image files)
//   --daylight-factor           a daylight-factor study: the CIE overcast sky (type 1) of 10,000 lux
//                               and no sun, unless --sky-lux says otherwise; DF = E / E_outside
//   --df-threshold PCT          the DF a cell must reach to count as daylit (default 2 %)
//   --falsecolor                also write the image's luminance in false colour (PATH.falsecolor.png)
// Sensors from the scene's own nodes (extras.sensor) need no option. Ranges are checked before
// anything is loaded; the sensors are built once the scene is (buildSensors()).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "sensor/sensor_set.h"
#include "sky/sky_sun_options.h"

namespace CLI {
class App;
}

namespace fen {

struct SensorOptions {
    std::vector<std::string> pointsFiles;
    std::optional<double> sensorSize_m;
    std::optional<std::string> workPlane;
    std::optional<double> workPlaneHeight_m;
    std::optional<double> spacing_m;
    std::optional<double> smoothing_m;
    bool noImage = false;
    bool daylightFactor = false;
    std::optional<double> dfThreshold_pct;
    bool falseColor = false;

    double workPlaneHeightValue() const { return workPlaneHeight_m.value_or(0.8); }
    double spacingValue() const { return spacing_m.value_or(0.25); }
    double dfThresholdValue() const { return dfThreshold_pct.value_or(2.0); }
};

void addSensorOptions(CLI::App* render, SensorOptions* options);

// Checks the ranges and combinations, and for --daylight-factor sets the sky and sun options it
// implies (refusing a sky or sun that contradicts it). Throws fen::Error naming the option.
void validateSensorOptions(SensorOptions& options, SkySunOptions& skySun);

// The render's sensors: the scene's marked nodes, the work plane, the points files, in that order.
SensorSet buildSensors(const SensorOptions& options, const Scene& scene);

}  // namespace fen
