// annual_study.cpp — annual metrics from daylight coefficients (annual_study.h).
#include "annual/annual_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "annual/sky_patches.h"
#include "sky/goniogram.h"
#include "sky/perez_sky.h"
#include "sky/weather_sky.h"
#include "util/error.h"
#include "util/in_shares.h"

namespace fen {

namespace {

constexpr double kDeg = M_PI / 180.0;

// Whether the record's hour (ending at r.hour) lies within the occupied hours.
bool occupied(const WeatherRecord& r, const AnnualSettings& s)
{
    return r.hour - 1 >= s.occupiedFrom && r.hour <= s.occupiedTo;
}

}  // namespace

AnnualSkies annualSkies(const WeatherFile& file, const AnnualSettings& s)
{
    AnnualSkies out;
    out.patches = skyPatchCount(s.mf);
    const std::vector<double> projected = patchProjectedSolidAngles(s.mf);
    const std::vector<SkyPatch> patches = skyPatches(s.mf);
    const PatchPoints points = patchPoints(s.mf);
    // The hours first (cheap: the sun's position and the sky's condition), in the file's order.
    std::vector<HourSky> hours;
    for (const WeatherRecord& r : file.records) {
        if (!occupied(r, s))
            continue;
        ++out.occupiedHours;
        if (hourIsDark(file, r)) {
            ++out.darkHours;
            continue;
        }
        try {
            hours.push_back(hourSky(file, r, "--annual"));
        } catch (const Error& e) {
            // A daylight hour whose record lacks what its sky needs: taken as dark, and reported.
            if (out.missingHours++ == 0)
                out.firstMissing = e.what();
            continue;
        }
        char label[16];
        std::snprintf(label, sizeof label, "%02d-%02d:%02d", r.month, r.day, r.hour);
        out.hourLabel.emplace_back(label);
    }
    // Then their patch skies, shared between the machine's threads (each hour its own slot).
    const std::size_t n = hours.size();
    out.sky.resize(n);
    out.sunPatch.assign(n, 0);
    out.sunLuminance.assign(n, 0.0);
    out.sunDirection.assign(n, glm::dvec3(0.0, 1.0, 0.0));
    out.sunNormal_lux.assign(n, 0.0);
    std::vector<char> fallback(n, 0);
    const auto work = [&](std::size_t first, std::size_t last) {
        for (std::size_t k = first; k < last; ++k) {
            const HourSky& h = hours[k];
            const glm::dvec3 sun = skyDirection((90.0 - h.sunAltitudeDeg) * kDeg, h.sunAzimuthDeg * kDeg);
            // The Perez sky (perez_sky.h) straight from its formula at each patch's points,
            // scaled so that the patches give the hour's diffuse horizontal illuminance.
            const double z = (90.0 - h.sunAltitudeDeg) * kDeg;
            const CieSkyType co = perezCoefficients(z, h.condition);
            std::vector<double> v;
            if (perezLuminanceBounded(co)) {
                v = patchMeans(points, [&](const glm::dvec3& d) {
                    return perezRelativeLuminanceCos(co, z, d.y, std::clamp(glm::dot(d, sun), -1.0, 1.0));
                });
            } else {
                v.assign(out.patches, 1.0);
                fallback[k] = 1;
            }
            double horizontal = 0.0;
            for (std::size_t p = 1; p < v.size(); ++p)
                horizontal += v[p] * projected[p];
            for (double& x : v)
                x *= h.diffuseHorizontal_lux / horizontal;
            const double global_lux = h.diffuseHorizontal_lux + h.sunNormal_lux * std::max(0.0, sun.y);
            v[0] = s.groundAlbedo * global_lux / M_PI;
            const SunInPatch inPatch = sunInPatch(patches, s.mf, sun, h.sunNormal_lux);
            out.sunPatch[k] = inPatch.patch;
            out.sunLuminance[k] = inPatch.luminance_cd_m2;
            out.sunDirection[k] = sun;
            out.sunNormal_lux[k] = inPatch.patch ? h.sunNormal_lux : 0.0;  // as its patch: none below the horizon
            v[inPatch.patch] += inPatch.luminance_cd_m2;
            out.sky[k] = std::move(v);
        }
    };
    inShares(n, work);
    for (char f : fallback)
        out.fallbackHours += f;
    return out;
}

std::vector<double> annualPatchWeights(const AnnualSkies& skies, int mf)
{
    const std::vector<double> proj = patchProjectedSolidAngles(mf);
    std::vector<double> w(skies.patches, 0.0);
    for (const auto& v : skies.sky)
        for (std::size_t p = 0; p < w.size(); ++p)
            w[p] += v[p];
    double horizontal = 0.0, mean = 0.0;
    for (std::size_t p = 0; p < w.size(); ++p) {
        horizontal += w[p] * proj[p];
        mean += w[p] / static_cast<double>(w.size());
    }
    if (!(horizontal > 0.0))
        return std::vector<double>(w.size(), 1.0);  // no daylight at all: the unit sky
    for (double& x : w)
        x = std::max(x, 1e-3 * mean) * M_PI / horizontal;
    return w;
}

AnnualResult annualStudy(const std::vector<double>& coefficients, const std::vector<double>& stdErr,
                         const std::vector<double>& area_m2, const AnnualSkies& skies, const AnnualSettings& s,
                         const DirectSunSource* directSun)
{
    const std::size_t cells = area_m2.size(), P = skies.patches, hours = skies.sky.size();
    if (coefficients.size() != 3 * cells * P || stdErr.size() != coefficients.size())
        throw Error(cat("annual study: coefficient matrices of ", coefficients.size(), " entries for ", cells,
                        " cells and ", P, " patches"));
    if (s.exactSun && !directSun)
        throw Error("annual study: the sun apart from the sky needs its direct light");
    // The mean patch vector over the occupied hours (dark ones count as zero), and with the sun
    // apart, the mean of the sun's own luminance in each patch.
    std::vector<double> meanSky(P, 0.0), meanSun(P, 0.0);
    const double occupiedHours = std::max(1, skies.occupiedHours);
    for (std::size_t h = 0; h < hours; ++h) {
        for (std::size_t p = 0; p < P; ++p)
            meanSky[p] += skies.sky[h][p] / occupiedHours;
        if (s.exactSun)
            meanSun[skies.sunPatch[h]] += skies.sunLuminance[h] / occupiedHours;
    }
    AnnualResult res;
    res.cells.resize(cells);
    std::vector<double> noiseSq(cells, 0.0), signalSq(cells, 0.0);
    // The cells in pieces whose direct sun (hours floats a cell) fits in 64 MB; within a piece,
    // shared between the machine's threads, each writing its own.
    const std::size_t piece = std::max<std::size_t>(1, (std::size_t{64} << 20) / (4 * std::max<std::size_t>(hours, 1)));
    for (std::size_t first = 0; first < cells; first += piece) {
        const std::size_t count = std::min(piece, cells - first);
        const std::vector<float> S = s.exactSun ? (*directSun)(first, count) : std::vector<float>();
        if (s.exactSun && S.size() != count * hours)
            throw Error(cat("annual study: ", S.size(), " direct-sun values for ", count, " cells x ", hours, " hours"));
        const auto work = [&](std::size_t a, std::size_t b) {
            std::vector<double> var(P);
            for (std::size_t c = first + a; c < first + b; ++c) {
                const double* D = coefficients.data() + c * P;
                const double* Dd = coefficients.data() + (cells + c) * P;
                const double* E = stdErr.data() + c * P;
                const double* Ed = stdErr.data() + (cells + c) * P;
                const double* Ei = stdErr.data() + (2 * cells + c) * P;
                // var(D), var(D_indirect), and their covariance from the batches: D = D_direct +
                // D_indirect, so cov(D, D_indirect) = (var D - var D_direct + var D_indirect) / 2
                const auto sunPatchVar = [&](std::size_t p, double sky, double sun) {
                    const double vd = E[p] * E[p], vdd = Ed[p] * Ed[p], vi = Ei[p] * Ei[p];
                    return sky * sky * vd + sun * sun * vi + sky * sun * (vd - vdd + vi);
                };
                const float* Sc = s.exactSun ? S.data() + (c - first) * hours : nullptr;
                for (std::size_t p = 0; p < P; ++p)
                    var[p] = E[p] * E[p];
                AnnualCell& out = res.cells[c];
                int da = 0, low = 0, useful = 0, high = 0, ase = 0;
                double sum = 0.0, sunSum = 0.0;
                for (std::size_t h = 0; h < hours; ++h) {
                    const double* v = skies.sky[h].data();
                    double e = 0.0, n = 0.0;
                    for (std::size_t p = 0; p < P; ++p) {
                        e += D[p] * v[p];
                        n += var[p] * v[p] * v[p];
                    }
                    const std::size_t ps = skies.sunPatch[h];
                    const double ls = skies.sunLuminance[h];
                    double sun = Dd[ps] * ls;  // the sun's direct light, from its patch
                    if (Sc) {
                        // the sun apart: its patch's direct light out, its own in (annual_study.h)
                        sun = Sc[h];
                        e += sun - Dd[ps] * ls;
                        n += sunPatchVar(ps, v[ps] - ls, ls) - var[ps] * v[ps] * v[ps];
                    }
                    sum += e;
                    sunSum += sun;
                    noiseSq[c] += n;
                    signalSq[c] += e * e;
                    da += e >= s.daLux;
                    low += e < s.udiLow_lux;
                    useful += e >= s.udiLow_lux && e <= s.udiHigh_lux;
                    high += e > s.udiHigh_lux;
                    ase += (Sc || ps) && sun >= s.aseLux;
                }
                low += skies.occupiedHours - static_cast<int>(hours);  // the dark hours
                out.mean_lux = sum / occupiedHours;
                out.sunMean_lux = sunSum / occupiedHours;
                double m = 0.0;
                for (std::size_t p = 0; p < P; ++p)
                    m += sunPatchVar(p, meanSky[p] - meanSun[p], meanSun[p]);
                out.meanStdErr_lux = std::sqrt(m);
                out.da_pct = 100.0 * da / occupiedHours;
                out.udiLow_pct = 100.0 * low / occupiedHours;
                out.udiUseful_pct = 100.0 * useful / occupiedHours;
                out.udiHigh_pct = 100.0 * high / occupiedHours;
                out.aseHours = ase;
            }
        };
        inShares(count, work);
    }
    double area = 0.0, sdaArea = 0.0, aseArea = 0.0, noise = 0.0, signal = 0.0;
    for (std::size_t c = 0; c < cells; ++c) {
        const AnnualCell& cell = res.cells[c];
        const double a = area_m2[c];
        area += a;
        sdaArea += cell.da_pct >= s.sdaSharePct ? a : 0.0;
        aseArea += cell.aseHours > s.aseHours ? a : 0.0;
        res.meanDa_pct += cell.da_pct * a;
        res.meanUdiUseful_pct += cell.udiUseful_pct * a;
        res.mean_lux += cell.mean_lux * a;
        noise += noiseSq[c];
        signal += signalSq[c];
    }
    if (area > 0.0) {
        res.sda_pct = 100.0 * sdaArea / area;
        res.ase_pct = 100.0 * aseArea / area;
        res.meanDa_pct /= area;
        res.meanUdiUseful_pct /= area;
        res.mean_lux /= area;
    }
    res.hourlyNoise_rel = signal > 0.0 ? std::sqrt(noise / signal) : 0.0;
    return res;
}

}  // namespace fen
