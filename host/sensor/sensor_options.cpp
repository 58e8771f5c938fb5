// sensor_options.cpp — registering, checking and applying the sensor options (sensor_options.h).
#include "sensor/sensor_options.h"

#include <cmath>

#include <CLI/CLI.hpp>

#include "sensor/points_file.h"
#include "util/error.h"

namespace fen {

void addSensorOptions(CLI::App* r, SensorOptions* o)
{
    r->add_option("--sensor-points", o->pointsFiles,
                  "Sensor points file (Radiance's x y z dx dy dz per line), repeatable: illuminance per point");
    r->add_option("--sensor-size", o->sensorSize_m, "Side of each point's square cell, m (default: the points' spacing)");
    r->add_option("--work-plane", o->workPlane, "A sensor grid over the floors of this node");
    r->add_option("--work-plane-height", o->workPlaneHeight_m, "Its height above them, m (default 0.8)");
    r->add_option("--sensor-spacing", o->spacing_m, "Its cells' side, m (default 0.25)");
    r->add_option("--sensor-smoothing", o->smoothing_m,
                  "Report each cell by a local linear fit over the cells within this radius, m (default: off)");
    r->add_flag("--no-image", o->noImage, "Render the sensors alone: no image, no camera needed");
    r->add_flag("--daylight-factor", o->daylightFactor,
                "Daylight-factor study: CIE overcast sky, no sun; DF per sensor cell");
    r->add_option("--df-threshold", o->dfThreshold_pct, "The DF a daylit cell reaches, % (default 2)");
    r->add_flag("--falsecolor", o->falseColor, "Also write the image's luminance in false colour");
}

void validateSensorOptions(SensorOptions& o, SkySunOptions& skySun)
{
    const auto side = [](const std::optional<double>& v, const char* option) {
        if (v && (!(*v > 0.0) || !std::isfinite(*v) || *v > 1e4))
            throw Error(cat(option, " ", *v, ": must be a length in metres, more than 0 and at most 10 km"));
    };
    side(o.sensorSize_m, "--sensor-size");
    side(o.spacing_m, "--sensor-spacing");
    side(o.smoothing_m, "--sensor-smoothing");
    if (o.workPlaneHeight_m && (!std::isfinite(*o.workPlaneHeight_m) || std::abs(*o.workPlaneHeight_m) > 1e4))
        throw Error(cat("--work-plane-height ", *o.workPlaneHeight_m, ": must be a finite height in metres, at most 10 km"));
    if (o.workPlane && o.workPlane->empty())
        throw Error("--work-plane: give a node name");
    if (!o.workPlane && (o.workPlaneHeight_m || o.spacing_m))
        throw Error(cat(o.workPlaneHeight_m ? "--work-plane-height" : "--sensor-spacing",
                        " needs --work-plane NODE (the floors it lies over)"));
    if (o.sensorSize_m && o.pointsFiles.empty())
        throw Error("--sensor-size needs --sensor-points FILE (the points it sizes)");
    for (const std::string& f : o.pointsFiles)
        if (f.empty())
            throw Error("--sensor-points: give a file name");
    if (o.dfThreshold_pct && (!(*o.dfThreshold_pct > 0.0) || !(*o.dfThreshold_pct <= 100.0)))
        throw Error(cat("--df-threshold ", *o.dfThreshold_pct, ": must be a percentage, more than 0 and at most 100"));
    if (o.dfThreshold_pct && !o.daylightFactor)
        throw Error("--df-threshold needs --daylight-factor");
    if (o.noImage && o.falseColor)
        throw Error("--falsecolor colours the image, and --no-image renders none (sensors get their false-colour "
                    "plans anyway)");
    if (o.daylightFactor) {
        // DF is defined under the CIE standard overcast sky (ISO 15469 type 1, the old CIE overcast
        // sky) with no sun; its absolute level cancels, 10,000 lux by convention.
        if (skySun.weather || skySun.weatherHour)
            throw Error("--daylight-factor is defined under the CIE overcast sky with no sun; leave out --weather");
        if (skySun.sky && *skySun.sky != "cie:1")
            throw Error(cat("--daylight-factor is defined under the CIE overcast sky (cie:1), not --sky ",
                            printable(*skySun.sky, 40)));
        if (skySun.sun && *skySun.sun != "none")
            throw Error("--daylight-factor is defined with no sun; leave out --sun");
        if (skySun.site || skySun.sunAt || skySun.sunLux)
            throw Error(cat("--daylight-factor is defined with no sun; leave out ",
                            skySun.site ? "--site" : skySun.sunAt ? "--sun-at" : "--sun-lux"));
        skySun.sky = "cie:1";
        skySun.sun = "none";
        if (!skySun.skyZenith_cd_m2 && !skySun.skyLux)
            skySun.skyLux = 10000.0;
    }
}

SensorSet buildSensors(const SensorOptions& o, const Scene& scene)
{
    SensorSet set;
    addSceneSensors(set, scene);
    if (o.workPlane)
        addWorkPlane(set, scene, *o.workPlane, o.workPlaneHeightValue(), o.spacingValue());
    for (const std::string& f : o.pointsFiles)
        addPointsSensor(set, f, o.sensorSize_m);
    return set;
}

}  // namespace fen
