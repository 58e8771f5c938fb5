// weather_sky.cpp — the sun and the sky of a weather file's hour (weather_sky.h).
#include "sky/weather_sky.h"

#include <cmath>

#include "sky/solar_position.h"
#include "util/error.h"

namespace fen {

namespace {

// The sun at the middle of the hour ending at r.hour:00, in the file's standard time.
SolarPosition midHourSun(const WeatherFile& file, const WeatherRecord& r)
{
    LocalTime t;
    // A typical year's months come from different years; outside the solar algorithm's 1800-2200 a
    // year is taken as 2001 (the sun's path moves by a few thousandths of a degree a decade).
    t.year = r.year >= 1800 && r.year <= 2200 ? r.year : 2001;
    t.month = r.month, t.day = r.day, t.hour = r.hour - 1, t.minute = 30;
    t.utcOffsetMinutes = static_cast<int>(std::lround(file.timeZoneHours * 60.0));
    return solarPosition(file.latitudeDeg, file.longitudeDeg, t);
}

}  // namespace

bool hourIsDark(const WeatherFile& file, const WeatherRecord& r)
{
    return !(midHourSun(file, r).apparentAltitudeDeg > 0.0) ||
           (r.diffuseHorizontal_W_m2 && !(*r.diffuseHorizontal_W_m2 > 0.0)) ||
           (r.diffuseHorizontal_lux && !(*r.diffuseHorizontal_lux > 0.0));
}

HourSky hourSky(const WeatherFile& file, const WeatherRecord& r, const std::string& what)
{
    const std::string where = cat(what, " ", printable(file.path), ":", r.line, " (", r.month, "-", r.day, " hour ", r.hour, ")");
    const SolarPosition p = midHourSun(file, r);
    if (!(p.apparentAltitudeDeg > 0.0))
        throw Error(cat(where, ": the sun is ", -p.apparentAltitudeDeg,
                        " degrees below the horizon at the middle of the hour; fenestra renders daylight"));
    if (!r.directNormal_W_m2 || !r.diffuseHorizontal_W_m2)
        throw Error(cat(where, ": the ", r.directNormal_W_m2 ? "diffuse horizontal" : "direct normal",
                        " irradiance is missing (9999): the hour's sky cannot be made"));
    if (!(*r.diffuseHorizontal_W_m2 > 0.0))
        throw Error(cat(where, ": no diffuse light (diffuse horizontal irradiance 0): nothing to render"));
    const double dni = *r.directNormal_W_m2, dhi = *r.diffuseHorizontal_W_m2;
    // The efficacy models' precipitable water from the dew point; 2 cm where it is missing
    // (Radiance's gendaylit assumes 2 cm always).
    const double dewPoint = r.dewPoint_C ? *r.dewPoint_C : (std::log(2.0) + 0.075) / 0.07;
    HourSky h;
    h.sunAltitudeDeg = p.apparentAltitudeDeg;
    h.sunAzimuthDeg = p.azimuthDeg;
    const double z = (90.0 - p.apparentAltitudeDeg) * M_PI / 180.0;
    h.condition = perezCondition(z, dayOfYear(r.month, r.day), dni, dhi, where);
    // The file's lux where it gives them (and gives light where its irradiance does), else the
    // irradiance times Perez's efficacy.
    const bool diffuseLux = r.diffuseHorizontal_lux && (*r.diffuseHorizontal_lux > 0.0 || dhi == 0.0);
    const bool directLux = r.directNormal_lux && (*r.directNormal_lux > 0.0 || dni == 0.0);
    h.illuminanceFromFile = diffuseLux && directLux;
    h.diffuseHorizontal_lux = diffuseLux ? *r.diffuseHorizontal_lux : dhi * perezDiffuseEfficacy(z, h.condition, dewPoint);
    h.sunNormal_lux = directLux ? *r.directNormal_lux : dni * perezDirectEfficacy(z, h.condition, dewPoint);
    if (!(h.diffuseHorizontal_lux > 0.0))
        throw Error(cat(where, ": no diffuse light (diffuse horizontal illuminance 0): nothing to render"));
    return h;
}

void parseWeatherHour(const std::string& text, const std::string& option, int* month, int* day, int* hour)
{
    const auto digit = [&](std::size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
    const auto two = [&](std::size_t i) { return (text[i] - '0') * 10 + (text[i + 1] - '0'); };
    const bool shape = text.size() == 8 && digit(0) && digit(1) && text[2] == '-' && digit(3) && digit(4) &&
                       text[5] == ':' && digit(6) && digit(7);
    const int m = shape ? two(0) : 0, d = shape ? two(3) : 0, h = shape ? two(6) : 0;
    if (!shape || m < 1 || m > 12 || d < 1 || d > 31 || h < 1 || h > 24)
        throw Error(cat(option, " '", printable(text, 40), "': expected MM-DD:HH, the hour 01..24 ending then (e.g. "
                        "06-21:13 for 12:00-13:00 on 21 June)"));
    *month = m, *day = d, *hour = h;
}

}  // namespace fen
