// annual_report.cpp — an annual study's files and JSON (annual_report.h).
#include "annual/annual_report.h"

#include <chrono>
#include <cstdio>

#include "annual/sky_patches.h"
#include "io/false_color.h"
#include "io/sensor_pictures.h"
#include "sensor/sensor_report.h"
#include "util/error.h"

namespace fen {

namespace {

// The sensor file of the cells (positions, normals, areas), for the plans; values set by the caller.
SensorFile cellRows(const SensorSet& sensors, const std::string& path)
{
    const SensorStatistics zero(sensors.cells.size());
    return sensorRows(sensors, zero, std::nullopt, path);
}

std::string num(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

// The place the weather file names, or the file's own name where it names none.
std::string weatherName(const WeatherFile& w)
{
    if (!w.place.empty() && w.place.find("unknown") == std::string::npos)
        return w.place;
    const std::size_t slash = w.path.find_last_of('/');
    return slash == std::string::npos ? w.path : w.path.substr(slash + 1);
}

}  // namespace

AnnualPaths annualPaths(const std::string& base, const SensorSet& sensors)
{
    AnnualPaths p;
    p.csv = base + ".annual.csv";
    p.png = base + ".annual.png";
    p.matrix = base + ".dc.mtx";
    p.directMatrix = base + ".dc-direct.mtx";
    if (!sensors.empty())
        p.pngs = sensorPicturePaths(cellRows(sensors, p.csv), p.png);
    return p;
}

std::string radianceMatrix(const double* values, std::size_t rows, std::size_t cols, int components)
{
    std::string s = cat("#?RADIANCE\nfenestra daylight coefficients\nNROWS=", rows, "\nNCOLS=", cols,
                        "\nNCOMP=", components, "\nFORMAT=ascii\n\n");
    s.reserve(s.size() + rows * cols * components * 12);
    for (std::size_t r = 0; r < rows; ++r) {
        for (std::size_t c = 0; c < cols; ++c) {
            const std::string v = num(values[r * cols + c]);
            for (int k = 0; k < components; ++k) {
                s += v;
                s += c + 1 == cols && k + 1 == components ? '\n' : '\t';
            }
        }
    }
    return s;
}

nlohmann::json writeAnnual(const SensorSet& sensors, const SensorStatistics& coefficients, const WeatherFile& weather,
                           const AnnualSkies& skies, const AnnualSettings& s, DirectSun* directSun,
                           const AnnualPaths& paths, OutputFiles& out, std::vector<std::string>* lines)
{
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t cells = sensors.cells.size(), P = skies.patches;
    const std::vector<double> D = coefficients.mean(), err = coefficients.stdErr();
    for (double v : D)
        if (!std::isfinite(v))
            throw Error("internal error: a daylight coefficient is not finite");
    std::vector<double> area(cells);
    for (std::size_t c = 0; c < cells; ++c)
        area[c] = sensors.cells[c].side_m * sensors.cells[c].side_m;
    const DirectSunSource sun = [&](std::size_t first, std::size_t count) { return directSun->cells(first, count); };
    const AnnualResult res = annualStudy(D, err, area, skies, s, s.exactSun ? &sun : nullptr);
    const double studySeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // The cells: as the sensors' CSV names and places them, then the metrics.
    SensorFile file = cellRows(sensors, paths.csv);
    std::string csv = "sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,mean_lux,mean_std_err_lux,da_pct,udi_low_pct,"
                      "udi_useful_pct,udi_high_pct,ase_hours,sun_mean_lux\n";
    std::vector<double> da(cells);
    for (std::size_t c = 0; c < cells; ++c) {
        const SensorRow& r = file.rows[c];
        const AnnualCell& a = res.cells[c];
        da[c] = a.da_pct;
        csv += cat(sensorCsvPlace(r), ",", num(a.mean_lux), ",", num(a.meanStdErr_lux), ",",
                   num(a.da_pct), ",", num(a.udiLow_pct), ",", num(a.udiUseful_pct), ",", num(a.udiHigh_pct), ",",
                   a.aseHours, ",", num(a.sunMean_lux), "\n");
    }
    out.add(paths.csv, csv);
    FalseColorScale scale = autoScale(da, false, "% DA");
    scale.min = 0.0;
    scale.max = 100.0;
    scale.steps = 10;
    for (SensorPicture& pic : sensorPictures(file, da, "daylight autonomy", "%", scale, paths.png,
                                             cat("daylight autonomy DA", num(s.daLux), ", ", weatherName(weather))))
        out.add(pic.path, std::move(pic.png));
    out.add(paths.matrix, radianceMatrix(D.data(), cells, P, 3));
    out.add(paths.directMatrix, radianceMatrix(D.data() + cells * P, cells, P, 3));

    nlohmann::json j = {
        {"weather", weather.path},
        {"place", weather.place},
        {"latitude_deg", weather.latitudeDeg},
        {"longitude_deg", weather.longitudeDeg},
        {"time_zone_h", weather.timeZoneHours},
        {"sky_patches_mf", s.mf},
        {"sky_patches", P},
        {"occupied", {s.occupiedFrom, s.occupiedTo}},
        {"occupied_hours", skies.occupiedHours},
        {"daylit_hours", skies.sky.size()},
        {"dark_hours", skies.darkHours},
        {"uniform_sky_hours", skies.fallbackHours},
        {"missing_hours", skies.missingHours},
        {"ground_albedo", s.groundAlbedo},
        {"learning", s.learnForYear ? "year" : "unit"},
        {"sun", s.exactSun ? "exact" : "patch"},
        {"sun_points", s.exactSun ? nlohmann::json(s.sunPoints) : nlohmann::json(nullptr)},
        {"direct_sun_samples", directSun ? directSun->samples() : 0},
        {"direct_sun_seconds", directSun ? directSun->seconds() : 0.0},
        {"thresholds",
         {{"da_lux", s.daLux},
          {"sda_share_pct", s.sdaSharePct},
          {"ase_lux", s.aseLux},
          {"ase_hours", s.aseHours},
          {"udi_lux", {s.udiLow_lux, s.udiHigh_lux}}}},
        {"sda_pct", res.sda_pct},
        {"ase_pct", res.ase_pct},
        {"mean_da_pct", res.meanDa_pct},
        {"mean_udi_useful_pct", res.meanUdiUseful_pct},
        {"mean_lux", res.mean_lux},
        {"hourly_noise_rel", res.hourlyNoise_rel},
        {"study_seconds", studySeconds},
        {"outputs", {{"csv", paths.csv}, {"png", paths.pngs}, {"matrix", paths.matrix}, {"direct_matrix", paths.directMatrix}}}};
    lines->push_back(cat("annual: ", weatherName(weather), ", ", skies.occupiedHours, " occupied hours (", skies.sky.size(),
                         " daylit), ", cells, " cells x ", P, " patches: sDA", num(s.daLux), "/", num(s.sdaSharePct), "% ",
                         num(res.sda_pct), " %, ASE", num(s.aseLux), "/", num(s.aseHours), "h ", num(res.ase_pct),
                         " %, mean DA ", num(res.meanDa_pct), " %, mean UDI ", num(s.udiLow_lux), "-", num(s.udiHigh_lux),
                         " ", num(res.meanUdiUseful_pct), " %; hourly noise ", num(100.0 * res.hourlyNoise_rel), " %"));
    if (skies.missingHours)
        lines->push_back(cat("annual: ", skies.missingHours, " daylight hours lack the irradiance their sky needs and count "
                             "as dark; the first: ", skies.firstMissing));
    if (skies.fallbackHours)
        lines->push_back(cat("annual: ", skies.fallbackHours,
                             " hours whose Perez sky would be negative somewhere took a uniform sky of their diffuse light"));
    return j;
}

}  // namespace fen
