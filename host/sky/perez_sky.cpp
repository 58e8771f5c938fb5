// perez_sky.cpp — the Perez all-weather sky (perez_sky.h).
#include "sky/perez_sky.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace fen {

namespace {

constexpr double kHalfPi = M_PI / 2;

// Perez, Seals, Michalsky 1993, Table 1: per clearness bin, for a, b, c, d, e in turn, x1..x4.
const double kBounds[8] = {1.0, 1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};
const double kTable[8][5][4] = {
    {{1.3525, -0.2576, -0.2690, -1.4366},
     {-0.7670, 0.0007, 1.2734, -0.1233},
     {2.8000, 0.6004, 1.2375, 1.0000},
     {1.8734, 0.6297, 0.9738, 0.2809},
     {0.0356, -0.1246, -0.5718, 0.9938}},
    {{-1.2219, -0.7730, 1.4148, 1.1016},
     {-0.2054, 0.0367, -3.9128, 0.9156},
     {6.9750, 0.1774, 6.4477, -0.1239},
     {-1.5798, -0.5081, -1.7812, 0.1080},
     {0.2624, 0.0672, -0.2190, -0.4285}},
    {{-1.1000, -0.2515, 0.8952, 0.0156},
     {0.2782, -0.1812, -4.5000, 1.1766},
     {24.7219, -13.0812, -37.7000, 34.8438},
     {-5.0000, 1.5218, 3.9229, -2.6204},
     {-0.0156, 0.1597, 0.4199, -0.5562}},
    {{-0.5484, -0.6654, -0.2672, 0.7117},
     {0.7234, -0.6219, -5.6812, 2.6297},
     {33.3389, -18.3000, -62.2500, 52.0781},
     {-3.5000, 0.0016, 1.1477, 0.1062},
     {0.4659, -0.3296, -0.0876, -0.0329}},
    {{-0.6000, -0.3566, -2.5000, 2.3250},
     {0.2937, 0.0496, -5.6812, 1.8415},
     {21.0000, -4.7656, -21.5906, 7.2492},
     {-3.5000, -0.1554, 1.4062, 0.3988},
     {0.0032, 0.0766, -0.0656, -0.1294}},
    {{-1.0156, -0.3670, 1.0078, 1.4051},
     {0.2875, -0.5328, -3.8500, 3.3750},
     {14.0000, -0.9999, -7.1406, 7.5469},
     {-3.4000, -0.1078, -1.0750, 1.5702},
     {-0.0672, 0.4016, 0.3017, -0.4844}},
    {{-1.0000, 0.0211, 0.5025, -0.5119},
     {-0.3000, 0.1922, 0.7023, -1.6317},
     {19.0000, -5.0000, 1.2438, -1.9094},
     {-4.0000, 0.0250, 0.3844, 0.2656},
     {1.0468, -0.3788, -2.4517, 1.4656}},
    {{-1.0500, 0.0289, 0.4260, 0.3590},
     {-0.3250, 0.1156, 0.7781, 0.0025},
     {31.0625, -14.5000, -46.1148, 55.3750},
     {-7.2312, 0.4050, 13.3500, 0.6234},
     {1.5000, -0.6426, 1.8564, 0.5636}},
};

// Perez et al. 1990, Table 4: luminous efficacy coefficients a, b, c, d per clearness bin.
const double kDiffuseEfficacy[8][4] = {{97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},
                                       {104.97, 2.96, -5.53, -8.77},   {102.39, 5.59, -13.95, -13.90},
                                       {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
                                       {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98}};
const double kDirectEfficacy[8][4] = {{57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},
                                      {109.83, -4.90, -1.71, -8.81}, {110.34, -5.84, -1.99, -4.56},
                                      {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
                                      {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};

double precipitableWater_cm(double dewPoint_C)
{
    return std::exp(0.07 * dewPoint_C - 0.075);
}

int clearnessBin(double epsilon)
{
    int bin = 0;
    while (bin < 7 && epsilon >= kBounds[bin + 1])
        ++bin;
    return bin;
}

// Spencer (1971): the sun's irradiance over its mean, for day `day` of the year.
double eccentricity(int day)
{
    const double g = 2 * M_PI * (day - 1) / 365.0;
    return 1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2 * g) +
           0.000077 * std::sin(2 * g);
}

// Kasten (1966): the relative optical air mass at zenith angle z (radians, < pi/2).
double airMass(double z)
{
    const double zDeg = z * 180.0 / M_PI;
    return 1.0 / (std::cos(z) + 0.15 * std::pow(93.885 - zDeg, -1.253));
}

}  // namespace

PerezCondition perezCondition(double sunZenithRad, int dayOfYear, double directNormal_W_m2,
                              double diffuseHorizontal_W_m2, const std::string& where)
{
    if (!(sunZenithRad >= 0.0 && sunZenithRad < kHalfPi))
        throw Error(cat(where, ": the sun is not above the horizon (zenith angle ", sunZenithRad * 180 / M_PI,
                        " degrees)"));
    if (dayOfYear < 1 || dayOfYear > 366)
        throw Error(cat(where, ": day of the year ", dayOfYear, " is not 1..366"));
    if (!(diffuseHorizontal_W_m2 > 0.0) || !std::isfinite(diffuseHorizontal_W_m2))
        throw Error(cat(where, ": diffuse horizontal irradiance ", diffuseHorizontal_W_m2,
                        " W/m^2 must be positive (a sky without light has no distribution)"));
    if (!(directNormal_W_m2 >= 0.0) || !std::isfinite(directNormal_W_m2))
        throw Error(cat(where, ": direct normal irradiance ", directNormal_W_m2, " W/m^2 must be >= 0"));
    const double kz3 = 1.041 * sunZenithRad * sunZenithRad * sunZenithRad;
    PerezCondition c;
    c.epsilon = ((diffuseHorizontal_W_m2 + directNormal_W_m2) / diffuseHorizontal_W_m2 + kz3) / (1.0 + kz3);
    c.delta = diffuseHorizontal_W_m2 * airMass(sunZenithRad) / (1367.0 * eccentricity(dayOfYear));
    return c;
}

CieSkyType perezCoefficients(double sunZenithRad, const PerezCondition& condition)
{
    const double z = sunZenithRad, eps = condition.epsilon;
    double delta = condition.delta;
    if (eps > 1.065 && eps < 2.8)
        delta = std::max(delta, 0.2);
    const int bin = clearnessBin(eps);
    const auto& t = kTable[bin];
    const auto lin = [&](int k) { return t[k][0] + t[k][1] * z + delta * (t[k][2] + t[k][3] * z); };
    CieSkyType p{lin(0), lin(1), lin(2), lin(3), lin(4)};
    if (bin == 0) {
        p.c = std::exp(std::pow(delta * (t[2][0] + t[2][1] * z), t[2][2])) - t[2][3];
        p.d = -std::exp(delta * (t[3][0] + t[3][1] * z)) + t[3][2] + delta * t[3][3];
    }
    return p;
}

double perezDiffuseEfficacy(double sunZenithRad, const PerezCondition& condition, double dewPoint_C)
{
    const double* k = kDiffuseEfficacy[clearnessBin(condition.epsilon)];
    return k[0] + k[1] * precipitableWater_cm(dewPoint_C) + k[2] * std::cos(sunZenithRad) +
           k[3] * std::log(std::max(condition.delta, 1e-6));
}

double perezDirectEfficacy(double sunZenithRad, const PerezCondition& condition, double dewPoint_C)
{
    const double* k = kDirectEfficacy[clearnessBin(condition.epsilon)];
    return std::max(0.0, k[0] + k[1] * precipitableWater_cm(dewPoint_C) + k[2] * std::exp(5.73 * sunZenithRad - 5.0) +
                             k[3] * condition.delta);
}

double perezRelativeLuminance(const CieSkyType& p, double sunZenithRad, double zetaRad, double gammaRad)
{
    const auto gradation = [&](double zeta) { return 1.0 + p.a * std::exp(p.b / std::cos(zeta)); };
    const auto indicatrix = [&](double gamma) {
        const double c = std::cos(gamma);
        return 1.0 + p.c * std::exp(p.d * gamma) + p.e * c * c;
    };
    return gradation(zetaRad) * indicatrix(gammaRad) / (gradation(0.0) * indicatrix(sunZenithRad));
}

double perezRelativeLuminanceCos(const CieSkyType& p, double sunZenithRad, double cosZeta, double cosGamma)
{
    const double cz = std::cos(sunZenithRad);
    const double gradation = 1.0 + p.a * std::exp(p.b / cosZeta), zenith = 1.0 + p.a * std::exp(p.b);
    const double indicatrix = 1.0 + p.c * std::exp(p.d * std::acos(cosGamma)) + p.e * cosGamma * cosGamma;
    const double atZenith = 1.0 + p.c * std::exp(p.d * sunZenithRad) + p.e * cz * cz;
    return gradation * indicatrix / (zenith * atZenith);
}

bool perezLuminanceBounded(const CieSkyType& p)
{
    // The gradation must stay finite and positive down to the horizon, where exp(b / cos zeta)
    // grows without bound unless b < 0 (its least is then at the zenith), and the indicatrix
    // positive over every angle from the sun.
    if (!(p.b < 0.0 && 1.0 + p.a * std::exp(p.b) > 0.0 && 1.0 + p.c * std::exp(p.d * kHalfPi) > 0.0))
        return false;
    for (int i = 0; i <= 1800; ++i) {
        const double gamma = M_PI * i / 1800.0, c = std::cos(gamma);
        if (!(1.0 + p.c * std::exp(p.d * gamma) + p.e * c * c > 0.0))
            return false;
    }
    return true;
}

Goniogram perezSky(const PerezCondition& condition, double diffuseHorizontal_lux, double sunAltitudeDeg,
                   double sunAzimuthDeg, const std::string& where)
{
    if (!(condition.epsilon >= 1.0) || !std::isfinite(condition.epsilon))
        throw Error(cat(where, ".epsilon: the sky's clearness must be >= 1 (got ", condition.epsilon, ")"));
    if (!(condition.delta >= 0.0) || !std::isfinite(condition.delta))
        throw Error(cat(where, ".delta: the sky's brightness must be >= 0 (got ", condition.delta, ")"));
    if (!(diffuseHorizontal_lux > 0.0) || !std::isfinite(diffuseHorizontal_lux))
        throw Error(cat(where, ".diffuse_lux: must be positive (got ", diffuseHorizontal_lux, ")"));
    if (!(sunAltitudeDeg >= 0.0 && sunAltitudeDeg <= 90.0))
        throw Error(cat(where, ".sun_altitude_deg: must be in [0, 90] (got ", sunAltitudeDeg, ")"));
    const double z = (90.0 - sunAltitudeDeg) * M_PI / 180.0;
    const CieSkyType p = perezCoefficients(z, condition);
    const bool positive = perezLuminanceBounded(p);
    if (!positive)
        throw Error(cat(where, ": the Perez model gives a negative or unbounded luminance for clearness ",
                        condition.epsilon, ", brightness ", condition.delta, " and the sun at ", sunAltitudeDeg,
                        " degrees (a, b, c, d, e = ", p.a, ", ", p.b, ", ", p.c, ", ", p.d, ", ", p.e,
                        "): the model's fit fails here, as it does for a sun this low; choose another hour"));
    const double k = 1.0 + p.c * std::exp(p.d * kHalfPi);
    const CieSkyType asCie{p.a, p.b, p.c / k, p.d, p.e / k};
    const Goniogram unit = cieFormulaSky(asCie, 1.0, sunAltitudeDeg, sunAzimuthDeg, where);
    const double scale = diffuseHorizontal_lux / unit.illuminance(glm::dvec3(0.0, 1.0, 0.0));
    std::vector<double> values = unit.values();
    for (double& v : values)
        v *= scale;
    return Goniogram(unit.theta(), unit.phi(), std::move(values), where);
}

}  // namespace fen
