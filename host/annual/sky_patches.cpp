// sky_patches.cpp — Reinhart's sky patches (sky_patches.h).
#include "annual/sky_patches.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "sky/goniogram.h"
#include "util/error.h"

namespace fen {

namespace {

constexpr double kDeg = M_PI / 180.0;

void requireMF(int mf)
{
    if (mf < 1 || mf > kMaxSkyPatchMF)
        throw Error(cat("sky subdivision MF ", mf, ": must be 1..", kMaxSkyPatchMF));
}

// Patches in row r (as kernels/lib/sky_patch.h sky_patch_row_count).
int rowCount(int r, int mf)
{
    static const int tregenza[7] = {30, 30, 24, 24, 18, 12, 6};
    return r >= 7 * mf ? 1 : mf * tregenza[r / mf];
}

double rowAlpha(int mf) { return 90.0 / (7.0 * mf + 0.5); }

}  // namespace

std::size_t skyPatchCount(int mf)
{
    requireMF(mf);
    std::size_t n = 1;
    for (int r = 0; r <= 7 * mf; ++r)
        n += static_cast<std::size_t>(rowCount(r, mf));
    return n;
}

std::vector<SkyPatch> skyPatches(int mf)
{
    requireMF(mf);
    std::vector<SkyPatch> out;
    SkyPatch ground;
    ground.altLoDeg = -90.0;
    ground.altHiDeg = 0.0;
    ground.solidAngle_sr = 2.0 * M_PI;
    ground.centre = {0.0, -1.0, 0.0};
    out.push_back(ground);
    const double alpha = rowAlpha(mf);
    for (int r = 0; r <= 7 * mf; ++r) {
        const int n = rowCount(r, mf);
        const double lo = r * alpha, hi = r == 7 * mf ? 90.0 : (r + 1) * alpha;
        const double width = 360.0 / n;
        for (int c = 0; c < n; ++c) {
            SkyPatch p;
            p.altLoDeg = lo;
            p.altHiDeg = hi;
            p.aziCentreDeg = c * width;
            p.aziWidthDeg = width;
            p.solidAngle_sr = width * kDeg * (std::sin(hi * kDeg) - std::sin(lo * kDeg));
            const double alt = r == 7 * mf ? 90.0 : 0.5 * (lo + hi), azi = p.aziCentreDeg * kDeg;
            p.centre = {std::cos(alt * kDeg) * std::sin(azi), std::sin(alt * kDeg), -std::cos(alt * kDeg) * std::cos(azi)};
            out.push_back(p);
        }
    }
    return out;
}

std::size_t skyPatchOf(const glm::dvec3& towardsSky, int mf)
{
    requireMF(mf);
    const glm::dvec3 d = glm::normalize(towardsSky);
    if (!(d.y > 0.0))
        return 0;
    const double alpha = rowAlpha(mf);
    const double alt = std::asin(std::min(d.y, 1.0)) / kDeg;
    const int row = std::min(static_cast<int>(alt / alpha), 7 * mf);
    std::size_t first = 1;
    for (int r = 0; r < row; ++r)
        first += static_cast<std::size_t>(rowCount(r, mf));
    const int n = rowCount(row, mf);
    double azi = std::atan2(d.x, -d.z) / kDeg;
    if (azi < 0.0)
        azi += 360.0;
    const double inc = 360.0 / n;
    int col = static_cast<int>((azi + 0.5 * inc) / inc);
    if (col >= n)
        col = 0;
    return first + static_cast<std::size_t>(col);
}

SunInPatch sunInPatch(const std::vector<SkyPatch>& patches, int mf, const glm::dvec3& towardsSun, double sunNormal_lux)
{
    if (!(sunNormal_lux > 0.0) || !(towardsSun.y > 0.0))
        return {};
    const std::size_t k = skyPatchOf(towardsSun, mf);
    return {k, sunNormal_lux / patches[k].solidAngle_sr};
}

void addSunToPatches(std::vector<double>& patches, int mf, const glm::dvec3& towardsSun, double sunNormal_lux)
{
    const SunInPatch sun = sunInPatch(skyPatches(mf), mf, towardsSun, sunNormal_lux);
    patches[sun.patch] += sun.luminance_cd_m2;
}

PatchPoints patchPoints(int mf)
{
    const std::vector<SkyPatch> all = skyPatches(mf);
    PatchPoints pts;
    pts.first.assign(all.size() + 1, 0);
    // A midpoint rule in (sin altitude, azimuth), where the solid angle is uniform, of 4 / MF rows
    // (at least 2; a row is 12 / MF degrees high) and as many columns, or one per 2 degrees of
    // azimuth if more: 4 x 6 points for MF 1's patches, 2 x 2 for MF 4's and finer. (8 x 12 points
    // changed the CIE clear sky's patches by 0.0001 of their illuminance.)
    const int rows = std::max(2, 4 / mf);
    for (std::size_t k = 1; k < all.size(); ++k) {
        pts.first[k] = pts.directions.size();
        const SkyPatch& p = all[k];
        const int na = rows, nz = std::max(rows, static_cast<int>(std::ceil(0.5 * p.aziWidthDeg)));
        const double s0 = std::sin(p.altLoDeg * kDeg), s1 = std::sin(p.altHiDeg * kDeg);
        for (int i = 0; i < na; ++i) {
            const double s = s0 + (s1 - s0) * (i + 0.5) / na, c = std::sqrt(std::max(0.0, 1.0 - s * s));
            for (int j = 0; j < nz; ++j) {
                const double azi = (p.aziCentreDeg + p.aziWidthDeg * ((j + 0.5) / nz - 0.5)) * kDeg;
                pts.directions.push_back({c * std::sin(azi), s, -c * std::cos(azi)});
            }
        }
    }
    pts.first[all.size()] = pts.directions.size();
    return pts;
}

std::vector<double> patchMeans(const PatchPoints& pts, const std::function<double(const glm::dvec3&)>& luminance)
{
    std::vector<double> out(pts.first.size() - 1, 0.0);
    for (std::size_t k = 1; k + 1 < pts.first.size(); ++k) {
        double sum = 0.0;
        for (std::size_t i = pts.first[k]; i < pts.first[k + 1]; ++i)
            sum += luminance(pts.directions[i]);
        out[k] = sum / static_cast<double>(pts.first[k + 1] - pts.first[k]);
    }
    return out;
}

std::vector<double> patchProjectedSolidAngles(int mf)
{
    const std::vector<SkyPatch> all = skyPatches(mf);
    std::vector<double> out(all.size(), 0.0);
    for (std::size_t k = 1; k < all.size(); ++k) {
        const double s0 = std::sin(all[k].altLoDeg * kDeg), s1 = std::sin(all[k].altHiDeg * kDeg);
        out[k] = all[k].aziWidthDeg * kDeg * 0.5 * (s1 * s1 - s0 * s0);
    }
    return out;
}

std::vector<double> patchLuminance(const Goniogram* sky, int mf, const glm::dvec3& towardsSun, double sunNormal_lux)
{
    std::vector<double> out(skyPatchCount(mf), 0.0);
    if (sky) {
        out = patchMeans(patchPoints(mf), [sky](const glm::dvec3& d) { return sky->evalDirection(d); });
        out[0] = sky->groundLuminance();
    }
    addSunToPatches(out, mf, towardsSun, sunNormal_lux);
    return out;
}

}  // namespace fen
