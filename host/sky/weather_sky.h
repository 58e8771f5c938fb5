// weather_sky.h — the sun and the sky of one hour of a weather file (DESIGN.md §1 "Weather
// files"): the sun where it stands at the middle of the hour (an EPW record covers the hour ending
// at its time, in the file's standard time), with the record's direct normal illuminance; the sky a
// Perez all-weather sky (perez_sky.h) of the record's clearness and brightness, scaled to its
// diffuse horizontal illuminance. Where the file gives no illuminance (999999), the Perez 1990
// luminous efficacy models turn its irradiance into illuminance (reported: `fromFile` false).
#pragma once

#include <string>

#include "io/weather_file.h"
#include "sky/perez_sky.h"

namespace fen {

struct HourSky {
    double sunAltitudeDeg = 0.0, sunAzimuthDeg = 0.0;  // apparent, at the middle of the hour
    double sunNormal_lux = 0.0;                         // 0: no direct sun this hour
    double diffuseHorizontal_lux = 0.0;
    PerezCondition condition;
    bool illuminanceFromFile = true;  // false: from irradiance by the efficacy models
};

// Throws a one-line fen::Error naming `what` and the record when the hour has no daylight to
// render (the sun below the horizon at its middle, or no diffuse light).
HourSky hourSky(const WeatherFile& file, const WeatherRecord& record, const std::string& what);
// Whether the hour has no daylight: the sun below the horizon at its middle, or a diffuse
// horizontal irradiance or illuminance of 0 (an hour hourSky() refuses for having nothing to render,
// not for what its record lacks).
bool hourIsDark(const WeatherFile& file, const WeatherRecord& record);

// "MM-DD:HH" (HH 1..24, the hour ending then) -> month, day, hour; fen::Error naming `option`.
void parseWeatherHour(const std::string& text, const std::string& option, int* month, int* day, int* hour);

}  // namespace fen
