// weather_file.h — an EnergyPlus weather file (EPW) read for its daylight (DESIGN.md §1 "Weather
// files"): the place (LOCATION line) and each hour's irradiance and illuminance.
//
// The format (EnergyPlus "Auxiliary Programs", Weather Converter): eight header lines, the first
//   LOCATION,city,state,country,source,WMO,latitude,longitude,time zone (hours from UTC),elevation
// then one line an hour, comma-separated, of which fenestra reads (0-based fields)
//   1 month, 2 day, 3 hour 1..24 (the hour ending then, local standard time), 7 dew point (deg C),
//   13 global horizontal, 14 direct normal, 15 diffuse horizontal irradiance (W/m^2),
//   16 global horizontal, 17 direct normal, 18 diffuse horizontal illuminance (lux; 999999 missing).
// Invariants: every record read has month 1..12, a day of that month, hour 1..24; its irradiances
// are >= 0 and finite or missing (9999), its illuminances >= 0 or missing (999999), its dew point
// in -90..70 deg C or missing (99.9): a missing value is std::nullopt, never a number, and only the
// hour that needs it refuses it (weather_sky.h). Anything else is a one-line fen::Error
// "<path>:<line>: <field> '<text>': <why>". Files are regular files of at most 256 MiB.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace fen {

struct WeatherRecord {
    int line = 0;  // in the file, for messages
    int year = 2001, month = 1, day = 1, hour = 1;  // the hour ending at `hour`:00, standard time
    std::optional<double> dewPoint_C;
    std::optional<double> globalHorizontal_W_m2, directNormal_W_m2, diffuseHorizontal_W_m2;
    std::optional<double> globalHorizontal_lux, directNormal_lux, diffuseHorizontal_lux;
};

struct WeatherFile {
    std::string path;
    std::string place;  // city, country as the file says
    double latitudeDeg = 0.0, longitudeDeg = 0.0;  // north, east positive
    double timeZoneHours = 0.0;                    // the records' clock, hours from UTC
    std::vector<WeatherRecord> records;

    // The record of `month`-`day` hour `hour` (1..24); throws fen::Error naming `what` when the
    // file has none.
    const WeatherRecord& at(int month, int day, int hour, const std::string& what) const;
};

WeatherFile readWeatherFile(const std::string& path);
// The same from the file's bytes (`path` names it in messages; the fuzz target's entry).
WeatherFile readWeatherText(const std::string& text, const std::string& path);

// Day of the year 1..365 of a month and day in a year of 365 days, as typical-year files are (29
// February counts as 1 March).
int dayOfYear(int month, int day);

}  // namespace fen
