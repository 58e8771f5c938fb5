// weather_sky.cpp — the sun and the sky of a weather file's hour (weather_sky.h).
#include "sky/weather_sky.h"

#include <cmath>
#include <cstdio>

#include "sky/solar_position.h"
#include "util/error.h"

namespace fen {

HourSky hourSky(const WeatherFile& file, const WeatherRecord& r, const std::string& what)
{
    const std::string where = cat(what, " ", printable(file.path), ":", r.line, " (", r.month, "-", r.day, " hour ", r.hour, ")");
    // The middle of the hour ending at r.hour:00, in the file's standard time.
    LocalTime t;
    t.year = r.year, t.month = r.month, t.day = r.day, t.hour = r.hour - 1, t.minute = 30;
    t.utcOffsetMinutes = static_cast<int>(std::lround(file.timeZoneHours * 60.0));
    const SolarPosition p = solarPosition(file.latitudeDeg, file.longitudeDeg, t);
    if (!(p.apparentAltitudeDeg > 0.0))
        throw Error(cat(where, ": the sun is ", -p.apparentAltitudeDeg,
                        " degrees below the horizon at the middle of the hour; fenestra renders daylight"));
    if (!(r.diffuseHorizontal_W_m2 > 0.0))
        throw Error(cat(where, ": no diffuse light (diffuse horizontal irradiance 0): nothing to render"));
    HourSky h;
    h.sunAltitudeDeg = p.apparentAltitudeDeg;
    h.sunAzimuthDeg = p.azimuthDeg;
    const double z = (90.0 - p.apparentAltitudeDeg) * M_PI / 180.0;
    h.condition = perezCondition(z, dayOfYear(r.month, r.day), r.directNormal_W_m2, r.diffuseHorizontal_W_m2, where);
    h.illuminanceFromFile = r.diffuseHorizontal_lux && r.directNormal_lux;
    h.diffuseHorizontal_lux = r.diffuseHorizontal_lux
                                  ? *r.diffuseHorizontal_lux
                                  : r.diffuseHorizontal_W_m2 * perezDiffuseEfficacy(z, h.condition, r.dewPoint_C);
    h.sunNormal_lux = r.directNormal_lux ? *r.directNormal_lux
                                         : r.directNormal_W_m2 * perezDirectEfficacy(z, h.condition, r.dewPoint_C);
    if (!(h.diffuseHorizontal_lux > 0.0))
        throw Error(cat(where, ": no diffuse light (diffuse horizontal illuminance 0): nothing to render"));
    return h;
}

void parseWeatherHour(const std::string& text, const std::string& option, int* month, int* day, int* hour)
{
    int m = 0, d = 0, h = 0, used = 0;
    if (std::sscanf(text.c_str(), "%2d-%2d:%2d%n", &m, &d, &h, &used) != 3 || used != static_cast<int>(text.size()) ||
        m < 1 || m > 12 || d < 1 || d > 31 || h < 1 || h > 24)
        throw Error(cat(option, " '", printable(text, 40), "': expected MM-DD:HH, the hour 1..24 ending then (e.g. "
                        "06-21:13 for 12:00-13:00 on 21 June)"));
    *month = m, *day = d, *hour = h;
}

}  // namespace fen
