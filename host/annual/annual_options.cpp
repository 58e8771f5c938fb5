// annual_options.cpp — registering and checking the annual-study options (annual_options.h).
#include "annual/annual_options.h"

#include <cmath>

#include <CLI/CLI.hpp>

#include "annual/sky_patches.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace fen {

void addAnnualOptions(CLI::App* r, AnnualOptions* o)
{
    r->add_option("--annual", o->weather,
                  "Annual study from daylight coefficients: this weather file's occupied hours (DA, sDA, ASE, UDI)");
    r->add_option("--sky-patches", o->mf, "Reinhart subdivision MF of the daylight coefficients (default 1: 145 + ground)");
    r->add_option("--occupied", o->occupied, "Occupied hours FROM-TO, the weather file's standard time (default 8-18)");
    r->add_option("--da-lux", o->daLux, "Daylight autonomy threshold, lux (default 300)");
    r->add_option("--sda-share", o->sdaShare, "The DA a cell needs for sDA, % of occupied hours (default 50)");
    r->add_option("--ase-lux", o->aseLux, "Annual sunlight exposure threshold, direct sun lux (default 1000)");
    r->add_option("--ase-hours", o->aseHours, "ASE: occupied hours above --ase-lux a cell may have (default 250)");
    r->add_option("--udi", o->udi, "Useful daylight illuminance band LOW,HIGH, lux (default 100,2000)");
    r->add_option("--annual-learning", o->learning,
                  "What adaptive emission learns the coefficients for: year (the year's mean sky, default) | unit");
    r->add_option("--annual-sun", o->sun,
                  "The sun's direct light: exact (at its own position, hour by hour: five-phase, default) | patch "
                  "(in its sky patch: two-phase)");
    r->add_option("--annual-sun-points", o->sunPoints,
                  "With --annual-sun exact: N x N jittered points a cell and hour (default 4)");
}

namespace {

// "A-B" or "A,B" of two numbers (with `sep`); false if the text is not that.
bool parsePair(const std::string& text, char sep, double* a, double* b)
{
    const std::size_t k = text.find(sep);
    if (k == std::string::npos || k == 0 || k + 1 >= text.size())
        return false;
    const std::optional<double> x = parseWholeNumber(text.substr(0, k)), y = parseWholeNumber(text.substr(k + 1));
    if (!x || !y)
        return false;
    *a = *x;
    *b = *y;
    return true;
}

}  // namespace

void validateAnnualOptions(AnnualOptions& o, const SkySunOptions& skySun, SensorOptions& sensors)
{
    const bool tuned = o.mf || o.occupied || o.daLux || o.sdaShare || o.aseLux || o.aseHours || o.udi || o.learning ||
                       o.sun || o.sunPoints;
    if (!o.weather) {
        if (tuned)
            throw Error("--sky-patches, --occupied, --da-lux, --sda-share, --ase-lux, --ase-hours, --udi, "
                        "--annual-learning, --annual-sun and --annual-sun-points need --annual FILE.epw");
        return;
    }
    if (o.weather->empty())
        throw Error("--annual: give a weather file (.epw)");
    if (skySun.weather || skySun.weatherHour || skySun.sky || skySun.sun || skySun.site || skySun.sunAt ||
        skySun.sunLux || skySun.skyLux || skySun.skyZenith_cd_m2)
        throw Error("--annual takes its skies from the weather file: leave out --sky, --sun, --site, --sun-at, "
                    "--sun-lux, --sky-lux, --sky-zenith and --weather");
    if (sensors.daylightFactor)
        throw Error("--annual and --daylight-factor are two studies: run them one at a time");
    AnnualSettings& s = o.settings;
    s.mf = o.mf.value_or(1);
    if (s.mf < 1 || s.mf > kMaxSkyPatchMF)
        throw Error(cat("--sky-patches ", s.mf, ": must be 1..", kMaxSkyPatchMF,
                        " (1: Tregenza's 145 patches, 2: 577, 4: 2305)"));
    if (o.occupied) {
        double a = 0.0, b = 0.0;
        if (!parsePair(*o.occupied, '-', &a, &b) || a != std::floor(a) || b != std::floor(b) || a < 0 || b > 24 || !(a < b))
            throw Error(cat("--occupied '", printable(*o.occupied, 40),
                            "': expected FROM-TO, whole hours 0..24 with FROM < TO (e.g. 8-18)"));
        s.occupiedFrom = static_cast<int>(a);
        s.occupiedTo = static_cast<int>(b);
    }
    const auto lux = [](const std::optional<double>& v, const char* option, double* out) {
        if (!v)
            return;
        if (!(*v > 0.0) || !std::isfinite(*v) || *v > 1e6)
            throw Error(cat(option, " ", *v, ": must be an illuminance in lux, more than 0 and at most 10^6"));
        *out = *v;
    };
    lux(o.daLux, "--da-lux", &s.daLux);
    lux(o.aseLux, "--ase-lux", &s.aseLux);
    if (o.sdaShare) {
        if (!(*o.sdaShare > 0.0) || !(*o.sdaShare <= 100.0))
            throw Error(cat("--sda-share ", *o.sdaShare, ": must be a percentage, more than 0 and at most 100"));
        s.sdaSharePct = *o.sdaShare;
    }
    if (o.aseHours) {
        if (!(*o.aseHours >= 0.0) || !(*o.aseHours <= 8784.0))
            throw Error(cat("--ase-hours ", *o.aseHours, ": must be 0..8784 hours"));
        s.aseHours = *o.aseHours;
    }
    if (o.udi) {
        double a = 0.0, b = 0.0;
        if (!parsePair(*o.udi, ',', &a, &b) || !(a >= 0.0) || !(a < b) || b > 1e6)
            throw Error(cat("--udi '", printable(*o.udi, 40), "': expected LOW,HIGH in lux with 0 <= LOW < HIGH (e.g. 100,2000)"));
        s.udiLow_lux = a;
        s.udiHigh_lux = b;
    }
    if (o.learning) {
        if (*o.learning != "year" && *o.learning != "unit")
            throw Error(cat("--annual-learning '", printable(*o.learning, 40), "': expected year or unit"));
        s.learnForYear = *o.learning == "year";
    }
    if (o.sun) {
        if (*o.sun != "exact" && *o.sun != "patch")
            throw Error(cat("--annual-sun '", printable(*o.sun, 40), "': expected exact or patch"));
        s.exactSun = *o.sun == "exact";
    }
    if (o.sunPoints) {
        if (!s.exactSun)
            throw Error("--annual-sun-points: only with --annual-sun exact (the patch sun traces no rays of its own)");
        if (*o.sunPoints < 1 || *o.sunPoints > 16)
            throw Error(cat("--annual-sun-points ", *o.sunPoints, ": must be 1..16 (points a side of each cell)"));
        s.sunPoints = *o.sunPoints;
    }
    s.groundAlbedo = skySun.groundAlbedo.value_or(0.2);
    sensors.noImage = true;
}

}  // namespace fen
