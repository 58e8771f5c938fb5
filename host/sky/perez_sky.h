// perez_sky.h — the Perez all-weather sky (Perez, Seals, Michalsky 1993, "All-weather model for sky
// luminance distribution -- preliminary configuration and validation", Solar Energy 50(3)),
// tabulated as a goniogram (DESIGN.md §1 "Weather files").
//
// The sky of a measured hour: from its direct normal and diffuse horizontal irradiance (a weather
// file's) the model derives the sky's clearness epsilon and brightness Delta,
//   epsilon = ((D_h + I_n) / D_h + kappa Z^3) / (1 + kappa Z^3),   kappa = 1.041, Z in radians
//   Delta   = D_h m / (E_sc E_0)          m: Kasten's air mass, E_0: Spencer's eccentricity factor,
//                                         E_sc = 1367 W/m^2,
// and from (Z, epsilon, Delta) the five coefficients of
//   L / L_zenith = [1 + a exp(b / cos zeta)] [1 + c exp(d gamma) + e cos^2 gamma] / (same at the zenith)
// (zeta: the element's zenith angle, gamma: its angle from the sun): in each of 8 clearness bins
// x = x1 + x2 Z + Delta (x3 + x4 Z) for x = a..e, except c and d in the first (overcast) bin,
//   c = exp((Delta (c1 + c2 Z))^c3) - c4,   d = -exp(Delta (d1 + d2 Z)) + d3 + Delta d4,
// with Delta raised to at least 0.2 for 1.065 < epsilon < 2.8 (the paper's correction). The 160
// coefficients are the paper's Table 1; tests/host/weather_sky_test.cpp checks a..e against Radiance's
// gendaylit for the same (sun, epsilon, Delta) over all eight bins.
//
// The formula is the CIE standard general sky's (cie_sky.h) with another indicatrix offset: with
// k = 1 + c exp(d pi/2) > 0, 1 + c exp(d gamma) + e cos^2 gamma = k [1 + (c/k)(exp(d gamma) -
// exp(d pi/2)) + (e/k) cos^2 gamma], and k cancels in L / L_zenith, so the sky is tabulated by the
// CIE sky's own grid design and checks (0.1 % everywhere). Scaled so that its diffuse horizontal
// illuminance is the hour's (lux): the weather file's measured value, not a luminous efficacy model.
#pragma once

#include <string>

#include "sky/cie_sky.h"
#include "sky/goniogram.h"

namespace fen {

struct PerezCondition {
    double epsilon = 1.0;  // sky clearness, >= 1
    double delta = 0.0;    // sky brightness
};

// epsilon and Delta of an hour: the sun at zenith angle sunZenithRad (< pi/2), day of the year
// 1..366, direct normal and diffuse horizontal irradiance (W/m^2, diffuse > 0). Throws fen::Error
// naming `where` for inputs outside that.
PerezCondition perezCondition(double sunZenithRad, int dayOfYear, double directNormal_W_m2,
                              double diffuseHorizontal_W_m2, const std::string& where);

// The model's a..e (as the CIE formula's fields: a, b gradation; c, d, e indicatrix) for the sun at
// sunZenithRad, exactly as the paper gives them (epsilon >= 1; Delta >= 0).
CieSkyType perezCoefficients(double sunZenithRad, const PerezCondition& condition);

// L / L_zenith of the model towards (zenith angle zetaRad <= pi/2, angle from the sun gammaRad).
double perezRelativeLuminance(const CieSkyType& coefficients, double sunZenithRad, double zetaRad, double gammaRad);
// The same from the cosines of zeta (> 0) and gamma: no trigonometry but one acos (the annual
// study evaluates it some ten million times a year of hours).
double perezRelativeLuminanceCos(const CieSkyType& coefficients, double sunZenithRad, double cosZeta, double cosGamma);

// Luminous efficacy (lm/W) of the diffuse horizontal and the direct normal irradiance (Perez,
// Ineichen, Seals, Michalsky, Stewart 1990, "Modeling daylight availability and irradiance
// components from direct and global irradiance", Solar Energy 44(5), Table 4), for a weather
// file that gives irradiance without illuminance: per clearness bin, diffuse a + b W + c cos Z +
// d ln Delta, direct max(0, a + b W + c exp(5.73 Z - 5) + d Delta), W = exp(0.07 T_d - 0.075) cm
// the precipitable water from the dew point T_d (deg C).
double perezDiffuseEfficacy(double sunZenithRad, const PerezCondition& condition, double dewPoint_C);
double perezDirectEfficacy(double sunZenithRad, const PerezCondition& condition, double dewPoint_C);

// Whether the formula with these coefficients stays positive and finite over the whole sky (b < 0,
// so the gradation is bounded at the horizon; both factors positive): what perezSky() requires.
bool perezLuminanceBounded(const CieSkyType& coefficients);

// The sky of `condition` for the sun at (sunAltitudeDeg in [0, 90], sunAzimuthDeg) with diffuse
// horizontal illuminance diffuseHorizontal_lux (> 0). Errors name `where` and the field; a
// condition whose luminance would be negative somewhere is an error too (the model's fit can go
// below zero far outside its data).
Goniogram perezSky(const PerezCondition& condition, double diffuseHorizontal_lux, double sunAltitudeDeg,
                   double sunAzimuthDeg, const std::string& where);

}  // namespace fen
