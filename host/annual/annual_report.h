// annual_report.h — what an annual study writes (DESIGN.md §8 "Annual daylight"; docs/annual.md):
//   PATH.annual.csv       one row per sensor cell: where it is, its mean illuminance over the
//                         occupied hours with its standard error, DA, the three UDI shares, ASE hours
//   PATH.annual.png       daylight autonomy in false colour, one plan per sensor plane
//                         (PATH.annual-NAME.png for the others), 0..100 %
//   PATH.dc.mtx           the daylight coefficients (cells x patches, lux per cd/m^2 = sr), in
//   PATH.dc-direct.mtx    Radiance's ASCII matrix format, 3 equal components: what dctimestep reads
//                         with a gendaymtx sky of the same subdivision; then the direct light's alone
//                         (straight from the sky through nothing but glass)
// and the JSON's "annual" block.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "annual/annual_options.h"
#include "annual/annual_study.h"
#include "annual/direct_sun.h"
#include "io/output_files.h"
#include "io/weather_file.h"
#include "sensor/sensor_set.h"
#include "sensor/sensor_stats.h"

namespace fen {

struct AnnualPaths {
    std::string csv, png, matrix, directMatrix;
    std::vector<std::string> pngs;  // one per sensor plane (io/sensor_pictures.h)
};
// The paths from the render's base PATH, the plans named from the cells alone.
AnnualPaths annualPaths(const std::string& base, const SensorSet& sensors);

// The study over the render's coefficients; adds its files to `out` and returns the JSON block.
// `directSun`: the sun's own direct light, with s.exactSun (else null). `lines`: what to print,
// one line each.
nlohmann::json writeAnnual(const SensorSet& sensors, const SensorStatistics& coefficients, const WeatherFile& weather,
                           const AnnualSkies& skies, const AnnualSettings& s, DirectSun* directSun,
                           const AnnualPaths& paths, OutputFiles& out, std::vector<std::string>* lines);

// Radiance's ASCII matrix: rows x cols, each entry written `components` times.
std::string radianceMatrix(const double* values, std::size_t rows, std::size_t cols, int components);

}  // namespace fen
