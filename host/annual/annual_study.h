// annual_study.h — climate-based daylight metrics from daylight coefficients (DESIGN.md §8
// "Annual daylight"): a weather file's occupied hours turned into patch skies, each hour's
// illuminance at every sensor cell as the coefficient matrix times the hour's patch vector, and
// the metrics building codes ask for (IES LM-83; Nabil and Mardaljevic's UDI).
//
// Per occupied hour (the weather file's hours ending within [from + 1, to] in its standard time,
// so 8-18 is 10 hours a day, 3,650 a year): with the sun above the horizon at the middle of the
// hour and diffuse light, the Perez all-weather sky of the hour (sky/weather_sky.h) averaged over
// each Reinhart patch, the sun's direct normal illuminance in the patch it stands in, and the
// ground glowing at rho E_global / pi (sky_patches.h); otherwise dark (0 lux). An hour whose Perez
// sky would go negative somewhere (the model's fit, far outside its data: gendaylit refuses them
// too) takes a uniform sky of the same diffuse illuminance instead, and an hour whose record lacks
// the irradiance is dark; both are counted and reported.
//   E_s(h)      = sum_p D[s][p] L_p(h)                 all light, every bounce
//   E_sun,s(h)  = D_direct[s][p_sun] L_sun(h)          the sun's light straight through nothing but glass
// With the sun apart from the sky (`exactSun`, the default: the five-phase method), the sun's
// direct light is not taken from its patch but computed at its own position, hour by hour
// (annual/direct_sun.h, S[s][h]); its patch keeps only what the sun gives after a bounce:
//   E_s(h)      = sum_p D[s][p] L_p(h) - D_direct[s][p_sun] L_sun(h) + S[s][h]
//               = sum_{p != p_sun} D[s][p] L_p(h) + D[s][p_sun] (L_p_sun(h) - L_sun(h))
//                 + D_indirect[s][p_sun] L_sun(h) + S[s][h]
//   E_sun,s(h)  = S[s][h]
//   DA          = share of occupied hours with E >= daLux              (per cell, %)
//   sDA         = share of the sensors' area with DA >= sdaShare       (%)
//   ASE         = share of the area with E_sun >= aseLux for more than aseHours occupied hours (%)
//   UDI         = shares of occupied hours below udiLow, within [udiLow, udiHigh], above udiHigh
// Noise: the coefficients' own standard errors (their batches) give each cell's mean illuminance
// over the occupied hours a standard error, sqrt(sum_p (mean_h L_p)^2 var D[s][p]) (the same
// coefficients serve every hour), and the hours' illuminance a relative RMS noise. With the sun
// apart, the second line's form: a patch weighs D by its sky and D_indirect by the sun, with the
// covariance of the two from the batches (cov(D, D_indirect) = (var D - var D_direct +
// var D_indirect) / 2, since D = D_direct + D_indirect); the covariances between patches are left
// out, with either sun. S's own quadrature error is not counted: it is independent from hour to
// hour and small beside the coefficients' (docs/annual.md).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "io/weather_file.h"

namespace fen {

struct AnnualSettings {
    int mf = 1;                         // Reinhart subdivision of the coefficients
    int occupiedFrom = 8, occupiedTo = 18;  // hours of the day, the weather file's standard time
    double groundAlbedo = 0.2;
    double daLux = 300.0, sdaSharePct = 50.0;
    double aseLux = 1000.0, aseHours = 250.0;
    double udiLow_lux = 100.0, udiHigh_lux = 2000.0;
    bool learnForYear = true;  // adaptive emission learns for the year's mean sky (annualPatchWeights)
    bool exactSun = true;      // the sun's direct light at its own position (direct_sun.h), not its patch's
    int sunPoints = 4;         // ... from sunPoints x sunPoints jittered points a cell and hour
};

// The occupied hours' skies as patch vectors.
struct AnnualSkies {
    std::size_t patches = 0;
    std::vector<std::vector<double>> sky;  // per daylit occupied hour: patch luminances (sun included)
    std::vector<std::size_t> sunPatch;     // ... the sun's patch (0: no sun)
    std::vector<double> sunLuminance;      // ... and the luminance the sun adds to it (cd/m^2)
    std::vector<glm::dvec3> sunDirection;  // ... the direction towards the sun (unit; y up, -z north)
    std::vector<double> sunNormal_lux;     // ... and its direct normal illuminance
    std::vector<std::string> hourLabel;    // ... "MM-DD:HH"
    int occupiedHours = 0;   // all, dark ones included: the metrics' denominator
    int darkHours = 0;       // the sun down (or no diffuse light) at the middle of the hour
    int fallbackHours = 0;   // a uniform sky in place of a Perez sky that would go negative
    int missingHours = 0;    // daylight hours without the irradiance to make a sky: taken as dark
    std::string firstMissing;  // the first of them, for the warning
};
AnnualSkies annualSkies(const WeatherFile& file, const AnnualSettings& s);

// Each patch's weight for what a learning strategy learns (RenderSettings::skyPatchWeights): the
// occupied hours' mean patch luminance, scaled so that its horizontal illuminance is the unit sky's
// (pi lux); every patch at least 10^-3 of the mean, so that none is left unlearned.
std::vector<double> annualPatchWeights(const AnnualSkies& skies, int mf);

struct AnnualCell {
    double mean_lux = 0.0, meanStdErr_lux = 0.0;  // over the occupied hours
    double da_pct = 0.0;
    double udiLow_pct = 0.0, udiUseful_pct = 0.0, udiHigh_pct = 0.0;
    int aseHours = 0;                             // occupied hours of direct sun >= aseLux
    double sunMean_lux = 0.0;                     // the direct sun's mean over the occupied hours
};

struct AnnualResult {
    std::vector<AnnualCell> cells;
    double sda_pct = 0.0, ase_pct = 0.0;          // shares of the sensors' area
    double meanDa_pct = 0.0, meanUdiUseful_pct = 0.0, mean_lux = 0.0;  // area-weighted means
    double hourlyNoise_rel = 0.0;  // RMS over cells and daylit hours of sd(E) over the RMS of E
};

// The sun's direct illuminance S at cells [first, first + count) for every daylit hour of
// AnnualSkies, cell-major (lux): annual/direct_sun.h.
using DirectSunSource = std::function<std::vector<float>(std::size_t first, std::size_t count)>;

// `coefficients`, `stdErr`: the three matrices (all light, direct, indirect), each cells x patches
// row-major (DeviceSensors::readMatrices); `area_m2` per cell; `directSun` with s.exactSun (else
// null). Asks directSun for the cells in pieces of at most 64 MB.
AnnualResult annualStudy(const std::vector<double>& coefficients, const std::vector<double>& stdErr,
                         const std::vector<double>& area_m2, const AnnualSkies& skies, const AnnualSettings& s,
                         const DirectSunSource* directSun = nullptr);

}  // namespace fen
