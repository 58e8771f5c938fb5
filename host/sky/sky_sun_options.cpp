// sky_sun_options.cpp — the sky and the sun from the command line (sky_sun_options.h).
#include "sky/sky_sun_options.h"

#include <cmath>

#include <CLI/CLI.hpp>

#include "io/image.h"
#include "io/weather_file.h"
#include "sky/cie_sky.h"
#include "sky/solar_position.h"
#include "sky/weather_sky.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace fen {

namespace {

// The brightest sun on Earth: about 128,000 lux above the atmosphere (the solar constant, 1361
// W/m², times the sun's luminous efficacy, 93 lm/W); anything well above it is a unit mistake.
constexpr double kMaxPlausibleSunLux = 150000.0;

double parseNumber(const std::string& s, const std::string& what)
{
    const std::optional<double> v = parseWholeNumber(s);
    if (!v)
        throw Error(cat(what, ": '", printable(s, 40), "' is not a number"));
    return *v;
}

// "A,B" as two finite numbers.
void parsePair(const std::string& text, const std::string& option, const char* expected, double* a, double* b)
{
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
        throw Error(cat(option, " '", printable(text, 60), "': expected ", expected));
    *a = parseNumber(text.substr(0, comma), option);
    *b = parseNumber(text.substr(comma + 1), option);
}

void requireNonNegativeLight(double v, const std::string& option)
{
    if (!(v >= 0.0) || !std::isfinite(v) || v > 1e12)
        throw Error(cat(option, " ", v, ": must be a finite value from 0 to 1e12"));
}

}  // namespace

void addSkySunOptions(CLI::App* render, SkySunOptions* o)
{
    render->add_option("--sky", o->sky,
                       "The sky, replacing the file's: cie:N (CIE standard general sky, type 1..15: 1 overcast, "
                       "12 clear), uniform, or none");
    render->add_option("--sky-zenith", o->skyZenith_cd_m2, "The sky's zenith luminance (cd/m^2)");
    render->add_option("--sky-lux", o->skyLux,
                       "The sky's diffuse horizontal illuminance (lux), instead of --sky-zenith");
    render->add_option("--sun", o->sun,
                       "The sun's position ALT,AZ in degrees (altitude; azimuth from north towards east), "
                       "or none");
    render->add_option("--sun-lux", o->sunLux, "The sun's normal illuminance (lux)");
    render->add_option("--site", o->site, "Latitude,longitude in degrees (north, east positive), with --sun-at");
    render->add_option("--sun-at", o->sunAt,
                       "Local date and time with its UTC offset, e.g. 2026-06-21T14:00+02:00: the sun's "
                       "position at --site");
    render->add_option("--weather", o->weather,
                       "An EPW weather file: with --weather-hour, the sun and a Perez all-weather sky of that hour "
                       "(replacing the scene's sun and sky)");
    render->add_option("--weather-hour", o->weatherHour,
                       "The weather file's hour MM-DD:HH, the hour 1..24 ending then in the file's standard time "
                       "(06-21:13: 12:00-13:00 on 21 June)");
    render->add_option("--ground-albedo", o->groundAlbedo,
                       "The ground's albedo, 0 to 1: below the horizon the sky glows at albedo x the horizontal "
                       "illuminance of the sky and sun / pi (0: off, the default)");
}

double cieHorizontalIlluminancePerZenith(int type, double sunAltitudeDeg, double sunAzimuthDeg)
{
    return cieSky(type, 1.0, sunAltitudeDeg, sunAzimuthDeg, "--sky").illuminance(glm::dvec3(0.0, 1.0, 0.0));
}

SkySunReport applySkySunOptions(const SkySunOptions& o, Scene* scene)
{
    SkySunReport report;
    const bool sunBrightnessFromFile = scene->sun.present && !o.sunLux && !o.weather;

    // A weather file's hour: the sun and the sky both (weather_sky.h).
    if (o.weather.has_value() != o.weatherHour.has_value())
        throw Error(o.weather ? "--weather needs --weather-hour MM-DD:HH (which hour of the file)"
                              : "--weather-hour needs --weather FILE.epw");
    if (o.weather) {
        const std::pair<bool, const char*> others[] = {
            {o.sky.has_value(), "--sky"},       {o.skyZenith_cd_m2.has_value(), "--sky-zenith"},
            {o.skyLux.has_value(), "--sky-lux"}, {o.sun.has_value(), "--sun"},
            {o.sunLux.has_value(), "--sun-lux"}, {o.site.has_value(), "--site"},
            {o.sunAt.has_value(), "--sun-at"}};
        for (const auto& [given, name] : others)
            if (given)
                throw Error(cat("--weather sets the sun and the sky of its hour; ", name, " cannot be given with it"));
        int month = 0, day = 0, hour = 0;
        parseWeatherHour(*o.weatherHour, "--weather-hour", &month, &day, &hour);
        const WeatherFile file = readWeatherFile(*o.weather);
        const HourSky h = hourSky(file, file.at(month, day, hour, "--weather-hour"), "--weather");
        const double radius = scene->sun.present ? scene->sun.angularRadiusRad : 0.0;
        scene->sun = Sun{};
        if (h.sunNormal_lux > 0.0) {
            scene->sun.present = true;
            scene->sun.nodeName = "--weather";
            scene->sun.travelDirection = -directionFromAltitudeAzimuth(h.sunAltitudeDeg, h.sunAzimuthDeg);
            scene->sun.illuminanceRgb_lux = glm::dvec3(h.sunNormal_lux);
            scene->sun.angularRadiusRad = radius;
        }
        SkySpec spec;
        spec.type = SkySpec::Type::Perez;
        spec.where = cat("--weather ", printable(*o.weather, 120), " ", printable(*o.weatherHour, 20));
        spec.perezEpsilon = h.condition.epsilon;
        spec.perezDelta = h.condition.delta;
        spec.diffuseHorizontal_lux = h.diffuseHorizontal_lux;
        spec.sunAltitudeDeg = h.sunAltitudeDeg;
        spec.sunAzimuthDeg = h.sunAzimuthDeg;
        spec.illuminanceFromFile = h.illuminanceFromFile;
        spec.groundAlbedo = scene->sky.groundAlbedo;  // the file's ground stays unless --ground-albedo says
        scene->sky = spec;
    }

    // The sun's position: --sun ALT,AZ, or --site and --sun-at, or the file's.
    if (o.site.has_value() != o.sunAt.has_value())
        throw Error(o.site ? "--site needs --sun-at (the moment)" : "--sun-at needs --site (the place)");
    std::optional<glm::dvec3> towardsSun;
    std::string sunLabel;
    if (o.sun && o.sunAt)
        throw Error("give the sun's position with --sun or with --site and --sun-at, not both");
    const bool sunNone = o.sun && *o.sun == "none";
    if (sunNone && o.sunLux)
        throw Error("--sun none removes the sun; --sun-lux has nothing to set");
    if (o.sun && !sunNone) {
        double alt = 0.0, az = 0.0;
        parsePair(*o.sun, "--sun", "ALT,AZ in degrees (e.g. 45,180), or none", &alt, &az);
        if (!(alt > 0.0 && alt <= 90.0))
            throw Error(cat("--sun ", printable(*o.sun, 60), ": the altitude ", alt, " must be in (0, 90] degrees"));
        towardsSun = directionFromAltitudeAzimuth(alt, az);
        sunLabel = "--sun";
    } else if (o.sunAt) {
        double lat = 0.0, lon = 0.0;
        parsePair(*o.site, "--site", "LAT,LON in degrees (e.g. 45.0,8.0)", &lat, &lon);
        if (!(lat >= -90.0 && lat <= 90.0) || !(lon >= -180.0 && lon <= 180.0))
            throw Error(cat("--site ", printable(*o.site, 60), ": latitude must be in [-90, 90], longitude in [-180, 180]"));
        const LocalTime t = parseLocalTime(*o.sunAt, "--sun-at");
        const SolarPosition p = solarPosition(lat, lon, t);
        if (!(p.apparentAltitudeDeg > 0.0))
            throw Error(cat("--sun-at ", printable(*o.sunAt, 60), ": the sun is ", -p.apparentAltitudeDeg,
                            " degrees below the horizon at ", printable(*o.site, 60), "; fenestra renders daylight"));
        towardsSun = directionFromAltitudeAzimuth(p.apparentAltitudeDeg, p.azimuthDeg);
        sunLabel = "--sun-at";
    }
    if (towardsSun) {
        if (!scene->sun.present && !o.sunLux)
            throw Error(cat(sunLabel, ": the scene has no sun to move; give its normal illuminance with --sun-lux"));
        scene->sun.travelDirection = -*towardsSun;
        if (!scene->sun.present) {
            scene->sun.present = true;
            scene->sun.nodeName = sunLabel;
            scene->sun.illuminanceRgb_lux = glm::dvec3(1.0);
            scene->sun.angularRadiusRad = 0.0;
        }
    }
    if (o.sunLux) {
        requireNonNegativeLight(*o.sunLux, "--sun-lux");
        if (!scene->sun.present)
            throw Error("--sun-lux: the scene has no sun; give its position with --sun ALT,AZ or --site and --sun-at");
        // Keep the sun's colour, with the luminance asked for.
        const glm::dvec3 c = scene->sun.illuminanceRgb_lux;
        const double y = luminance(c.r, c.g, c.b);
        scene->sun.illuminanceRgb_lux = y > 0.0 ? c * (*o.sunLux / y) : glm::dvec3(*o.sunLux);
    }
    // Where the sky's sun is: the sun's position (before --sun-lux 0 may remove it).
    std::optional<glm::dvec3> skySun;
    if (scene->sun.present)
        skySun = -scene->sun.travelDirection;
    if (sunNone || (o.sunLux && *o.sunLux == 0.0))
        scene->sun = Sun{};

    // The sky.
    if (o.skyZenith_cd_m2 && o.skyLux)
        throw Error("give the sky's brightness with --sky-zenith or --sky-lux, not both");
    if (o.skyZenith_cd_m2)
        requireNonNegativeLight(*o.skyZenith_cd_m2, "--sky-zenith");
    if (o.skyLux)
        requireNonNegativeLight(*o.skyLux, "--sky-lux");
    const bool brightness = o.skyZenith_cd_m2 || o.skyLux;
    if (o.sky) {
        const std::string& s = *o.sky;
        SkySpec spec;
        spec.where = "--sky";
        if (s == "none") {
            if (brightness)
                throw Error("--sky none: --sky-zenith and --sky-lux have no sky to set");
        } else if (s == "uniform") {
            spec.type = SkySpec::Type::Uniform;
        } else if (s.rfind("cie:", 0) == 0) {
            const double t = parseNumber(s.substr(4), "--sky " + printable(s, 40));
            if (t != std::floor(t) || t < 1 || t > 15)
                throw Error(cat("--sky ", printable(s, 40), ": the CIE sky type must be 1 to 15"));
            spec.type = SkySpec::Type::Cie;
            spec.cieType = static_cast<int>(t);
        } else {
            throw Error(cat("--sky '", printable(s, 40), "': expected cie:N (N = 1..15), uniform or none"));
        }
        if (spec.type != SkySpec::Type::None && !brightness)
            throw Error(cat("--sky ", printable(s, 40), " needs its brightness: --sky-zenith L (cd/m^2) or --sky-lux E "
                            "(diffuse horizontal illuminance, lux)"));
        if (spec.type != SkySpec::Type::None)
            spec.groundAlbedo = scene->sky.groundAlbedo;  // the file's ground stays unless --ground-albedo says
        scene->sky = spec;
    } else if (brightness && scene->sky.type == SkySpec::Type::None) {
        throw Error(cat(o.skyLux ? "--sky-lux" : "--sky-zenith", ": the scene has no sky; give one with --sky"));
    } else if (brightness && scene->sky.type == SkySpec::Type::Table) {
        throw Error(cat(o.skyLux ? "--sky-lux" : "--sky-zenith", ": the scene's sky is a table; scale it in the file"));
    }
    SkySpec& sky = scene->sky;
    if (sky.type == SkySpec::Type::Cie && (skySun && (o.sky || towardsSun))) {
        altitudeAzimuthOf(*skySun, &sky.sunAltitudeDeg, &sky.sunAzimuthDeg);
    } else if (sky.type == SkySpec::Type::Cie && o.sky && !skySun) {
        const CieSkyType& p = cieSkyType(sky.cieType);
        if (p.c != 0.0 || p.e != 0.0)  // the sky's indicatrix depends on where the sun is
            throw Error(cat("--sky ", printable(*o.sky, 40), ": the sky depends on the sun's position; give it with "
                            "--sun ALT,AZ or --site and --sun-at (and --sun-lux 0 for the sky alone)"));
        sky.sunAltitudeDeg = 90.0;
        sky.sunAzimuthDeg = 0.0;
    }
    if (o.groundAlbedo) {
        if (!(*o.groundAlbedo >= 0.0 && *o.groundAlbedo <= 1.0))
            throw Error(cat("--ground-albedo ", *o.groundAlbedo, ": must be in 0..1 (0: no ground glow)"));
        if (sky.type == SkySpec::Type::None && *o.groundAlbedo > 0.0)
            throw Error("--ground-albedo: the scene has no sky; give one with --sky (the ground reflects the sky's "
                        "and the sun's light: --sky uniform --sky-zenith 0 for the sun's alone)");
        sky.groundAlbedo = *o.groundAlbedo;
    }
    if (o.skyZenith_cd_m2 || o.skyLux) {
        if (sky.type == SkySpec::Type::Uniform)
            sky.luminance_cd_m2 = o.skyZenith_cd_m2 ? *o.skyZenith_cd_m2 : *o.skyLux / M_PI;
        else if (sky.type == SkySpec::Type::Cie)
            sky.zenithLuminance_cd_m2 =
                o.skyZenith_cd_m2 ? *o.skyZenith_cd_m2
                                  : *o.skyLux / cieHorizontalIlluminancePerZenith(sky.cieType, sky.sunAltitudeDeg,
                                                                                   sky.sunAzimuthDeg);
    }

    if (sky.type == SkySpec::Type::None && scene->sun.present)
        report.warnings.push_back(cat(scene->source, " has no sky: no skylight enters, and the sky seen through a "
                                      "window is black; give one with --sky (e.g. --sky cie:12 --sky-lux 20000 "
                                      "for a clear day, --sky cie:1 --sky-lux 10000 for an overcast one)"));
    if (sunBrightnessFromFile && scene->sun.present) {
        const glm::dvec3 c = scene->sun.illuminanceRgb_lux;
        const double y = luminance(c.r, c.g, c.b);
        if (y > kMaxPlausibleSunLux)
            report.warnings.push_back(cat(scene->source, ": the sun's normal illuminance, ", y,
                                          " lux, exceeds any sun's on Earth (about 128,000 lux above the "
                                          "atmosphere); Blender's exporter writes a sun's Strength (W/m^2) x 683 "
                                          "as lux: give the illuminance with --sun-lux (e.g. --sun-lux 100000)"));
    }
    return report;
}

}  // namespace fen
