// sky_patches_test.cpp — Reinhart's sky patches (host/annual/sky_patches.h) against Radiance's own
// numbering (tests/data/reinhart_rbin.csv, made by scripts/radiance/reinhart_reference.py with rcalc
// and reinhart.cal), their solid angles against closed forms, patch skies against the goniogram
// they come from, and the annual study (host/annual/annual_study.h): the shipped weather file's
// occupied hours and their patch skies against the file's own illuminance, and the metrics of
// coefficient matrices whose answers are known.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "annual/annual_study.h"
#include "annual/sky_patches.h"
#include "io/weather_file.h"
#include "shared/fen_openings.h"
#include "shared/fen_render.h"
#include "sky/cie_sky.h"
#include "sky/goniogram.h"
#include "sky/perez_sky.h"
#include "sky/weather_sky.h"
#include "util/error.h"

namespace fen {
namespace {

const std::string kEpw = std::string(FEN_SCENES_DIR) + "/weather/tmy_45.000_8.000_2005_2016.epw";

TEST(SkyPatches, CountsAndSolidAnglesAreReinharts)
{
    // Radiance's Nrbins: 146, 578, 2306 (ground included).
    EXPECT_EQ(skyPatchCount(1), 146u);
    EXPECT_EQ(skyPatchCount(2), 578u);
    EXPECT_EQ(skyPatchCount(4), 2306u);
    for (int mf : {1, 2, 4, 8}) {
        const std::vector<SkyPatch> p = skyPatches(mf);
        ASSERT_EQ(p.size(), skyPatchCount(mf));
        double omega = 0.0, projected = 0.0;
        const std::vector<double> proj = patchProjectedSolidAngles(mf);
        for (std::size_t k = 1; k < p.size(); ++k) {
            omega += p[k].solidAngle_sr;
            projected += proj[k];
            EXPECT_EQ(skyPatchOf(p[k].centre, mf), k) << "MF " << mf << " patch " << k;
        }
        EXPECT_NEAR(omega, 2.0 * M_PI, 1e-12);
        EXPECT_NEAR(projected, M_PI, 1e-12);
        EXPECT_EQ(skyPatchOf(glm::dvec3(0.3, -0.2, 0.1), mf), 0u);
    }
    EXPECT_THROW(skyPatchCount(0), Error);
    EXPECT_THROW(skyPatchCount(kMaxSkyPatchMF + 1), Error);
}

// A path keeps its sky patch in its flags' bits FEN_PATH_PATCH_SHIFT to 23, under the opening
// code (shared/fen_render.h): the finest subdivision's numbers must fit there.
TEST(SkyPatches, TheFinestPatchNumberFitsUnderThePathsOpeningCode)
{
    EXPECT_LE(skyPatchCount(kMaxSkyPatchMF) - 1, std::size_t{FEN_PATH_PATCH_MASK});
    EXPECT_EQ(FEN_PATH_PATCH_SHIFT + 16u, FEN_PATH_OPENING_SHIFT);
    EXPECT_EQ(FEN_PATH_PATCH_MASK, 0xffffu);
}

TEST(SkyPatches, NumberedAsRadiancesReinhartCal)
{
    std::ifstream in(std::string(FEN_TEST_DATA_DIR) + "/reinhart_rbin.csv");
    ASSERT_TRUE(in);
    std::string line;
    std::getline(in, line);
    int rows = 0;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        double x, y, z;
        int mf, bin;
        char c;
        ASSERT_TRUE(s >> x >> c >> y >> c >> z >> c >> mf >> c >> bin) << line;
        EXPECT_EQ(skyPatchOf(glm::dvec3(x, y, z), mf), static_cast<std::size_t>(bin)) << line;
        ++rows;
    }
    EXPECT_EQ(rows, 1200);
}

TEST(SkyPatches, PatchSkiesKeepTheGoniogramsIlluminance)
{
    // A uniform sky: every patch its luminance. The CIE clear sky with its sun in the south-east:
    // the patches' means give the sky's horizontal illuminance within the midpoint rule's error,
    // and the brightest patch is where the sun stands. The patches' illuminance differs from the
    // sky's by how luminance and cosine vary together inside a patch: second order in the patch
    // size, so a quarter with each doubling of MF (measured +0.44, +0.11, +0.03 %).
    const Goniogram uniform = uniformSky(250.0);
    const std::vector<double> u = patchLuminance(&uniform, 2);
    for (std::size_t k = 1; k < u.size(); ++k)
        EXPECT_NEAR(u[k], 250.0, 1e-9);
    EXPECT_EQ(u[0], 0.0);
    const Goniogram clear = cieSky(12, 5000.0, 40.0, 135.0);
    for (int mf : {1, 2, 4}) {
        const std::vector<double> v = patchLuminance(&clear, mf);
        const std::vector<double> proj = patchProjectedSolidAngles(mf);
        double e = 0.0;
        std::size_t brightest = 1;
        for (std::size_t k = 1; k < v.size(); ++k) {
            e += v[k] * proj[k];
            if (v[k] > v[brightest])
                brightest = k;
        }
        const double exact = clear.illuminance(glm::dvec3(0.0, 1.0, 0.0));
        std::printf("[ patches  ] CIE clear sky, MF %d: patches give %.6g lux, the sky %.6g (%+.3f %%)\n", mf, e, exact,
                    100.0 * (e / exact - 1.0));
        EXPECT_NEAR(e, exact, 0.005 / (mf * mf) * exact) << "MF " << mf;
        const double c = std::cos(40.0 * M_PI / 180.0);
        const glm::dvec3 sun(c * std::sin(135.0 * M_PI / 180.0), std::sin(40.0 * M_PI / 180.0),
                             -c * std::cos(135.0 * M_PI / 180.0));
        EXPECT_EQ(brightest, skyPatchOf(sun, mf)) << "MF " << mf;
        // The sun added to its patch keeps its normal illuminance over that patch's solid angle.
        const std::vector<double> withSun = patchLuminance(&clear, mf, sun, 80000.0);
        EXPECT_NEAR((withSun[brightest] - v[brightest]) * skyPatches(mf)[brightest].solidAngle_sr, 80000.0, 1e-6);
    }
}

TEST(AnnualStudy, PerezFromCosinesIsPerezFromAngles)
{
    // The annual study's fast form of the Perez formula against the formula itself.
    for (double eps : {1.02, 1.4, 3.0, 7.0})
        for (double sunZ : {0.2, 0.8, 1.3}) {
            const CieSkyType co = perezCoefficients(sunZ, PerezCondition{eps, 0.2});
            for (double zeta : {0.0, 0.4, 1.0, 1.5})
                for (double gamma : {0.01, 0.5, 1.7, 3.1}) {
                    const double a = perezRelativeLuminance(co, sunZ, zeta, gamma);
                    EXPECT_NEAR(perezRelativeLuminanceCos(co, sunZ, std::cos(zeta), std::cos(gamma)), a, 1e-12 * std::abs(a));
                }
        }
}

TEST(AnnualStudy, TheShippedYearsOccupiedHoursKeepTheFilesIlluminance)
{
    const WeatherFile w = readWeatherFile(kEpw);
    AnnualSettings s;
    const AnnualSkies skies = annualSkies(w, s);
    // 8-18 is ten hours a day; dark hours are those whose middle has the sun down (winter 8-9 and
    // 17-18) or no diffuse light.
    EXPECT_EQ(skies.occupiedHours, 3650);
    EXPECT_EQ(skies.occupiedHours, static_cast<int>(skies.sky.size()) + skies.darkHours + skies.missingHours);
    EXPECT_EQ(skies.missingHours, 0);
    EXPECT_GT(skies.sky.size(), 3300u);
    const std::vector<double> proj = patchProjectedSolidAngles(s.mf);
    const std::vector<SkyPatch> patches = skyPatches(s.mf);
    std::size_t k = 0;
    for (const WeatherRecord& r : w.records) {
        if (r.hour - 1 < s.occupiedFrom || r.hour > s.occupiedTo || hourIsDark(w, r))
            continue;
        ASSERT_LT(k, skies.sky.size());
        const HourSky h = hourSky(w, r, "test");
        const std::vector<double>& v = skies.sky[k];
        // The sky's patches (the sun's taken out) give the file's diffuse horizontal illuminance.
        double diffuse = 0.0;
        for (std::size_t p = 1; p < v.size(); ++p)
            diffuse += (v[p] - (p == skies.sunPatch[k] ? skies.sunLuminance[k] : 0.0)) * proj[p];
        EXPECT_NEAR(diffuse, h.diffuseHorizontal_lux, 1e-9 * h.diffuseHorizontal_lux + 1e-9) << skies.hourLabel[k];
        // The sun in its patch: its normal illuminance over the patch, and so its horizontal
        // illuminance within the patch's altitude band.
        if (h.sunNormal_lux > 0.0) {
            const SkyPatch& sp = patches[skies.sunPatch[k]];
            EXPECT_NEAR(skies.sunLuminance[k] * sp.solidAngle_sr, h.sunNormal_lux, 1e-9 * h.sunNormal_lux);
            EXPECT_GE(h.sunAltitudeDeg, sp.altLoDeg - 1e-9);
            EXPECT_LE(h.sunAltitudeDeg, sp.altHiDeg + 1e-9);
        }
        // The ground glows at 0.2 of the global horizontal illuminance over pi.
        const double sinAlt = std::sin(h.sunAltitudeDeg * M_PI / 180.0);
        EXPECT_NEAR(v[0], 0.2 * (h.diffuseHorizontal_lux + h.sunNormal_lux * sinAlt) / M_PI, 1e-9 * v[0] + 1e-12);
        ++k;
    }
    EXPECT_EQ(k, skies.sky.size());
}

TEST(AnnualStudy, MetricsOfKnownMatrices)
{
    // Two cells, one patch column that matters: cell 0 sees 1 sr of the zenith cap, cell 1 half of
    // it; direct light likewise for cell 0 alone. Hours: 10 occupied, with zenith luminance 100,
    // 200, ..., 1000 cd/m^2 and the sun (in the cap) adding 2000 cd/m^2 to the last three.
    const int mf = 1;
    const std::size_t P = skyPatchCount(mf), cells = 2, cap = P - 1;
    AnnualSkies skies;
    skies.patches = P;
    skies.occupiedHours = 12;  // two of them dark
    skies.darkHours = 2;
    for (int h = 1; h <= 10; ++h) {
        std::vector<double> v(P, 0.0);
        v[cap] = 100.0 * h + (h >= 8 ? 2000.0 : 0.0);
        skies.sky.push_back(v);
        skies.sunPatch.push_back(h >= 8 ? cap : 0);
        skies.sunLuminance.push_back(h >= 8 ? 2000.0 : 0.0);
        skies.hourLabel.push_back("h");
    }
    std::vector<double> D(3 * cells * P, 0.0), se(D.size(), 0.0);
    D[0 * P + cap] = 1.0;
    D[1 * P + cap] = 0.5;
    D[(cells + 0) * P + cap] = 1.0;
    D[(2 * cells + 1) * P + cap] = 0.5;
    se[0 * P + cap] = 0.01;
    AnnualSettings s;
    s.exactSun = false;  // the sun in its patch: the direct matrix's column
    s.aseHours = 2.0;  // 3 hours of sun over 1000 lux at cell 0: more than 2
    const AnnualResult r = annualStudy(D, se, {1.0, 3.0}, skies, s);
    ASSERT_EQ(r.cells.size(), 2u);
    // cell 0: 100..700, 2800..3000 lux -> >= 300 lux in 8 of 12 hours; < 100: h1? (100 is not below) + 2 dark
    EXPECT_NEAR(r.cells[0].da_pct, 100.0 * 8 / 12, 1e-12);
    EXPECT_NEAR(r.cells[0].udiLow_pct, 100.0 * 2 / 12, 1e-12);
    EXPECT_NEAR(r.cells[0].udiUseful_pct, 100.0 * 7 / 12, 1e-12);
    EXPECT_NEAR(r.cells[0].udiHigh_pct, 100.0 * 3 / 12, 1e-12);
    EXPECT_EQ(r.cells[0].aseHours, 3);
    // cell 1: 50..350, 1400..1500 lux -> >= 300 in 5 hours (h 6, 7 and the sunny three)
    EXPECT_NEAR(r.cells[1].da_pct, 100.0 * 5 / 12, 1e-12);
    EXPECT_NEAR(r.cells[1].udiLow_pct, 100.0 * 3 / 12, 1e-12);  // 50 lux and the dark two
    EXPECT_EQ(r.cells[1].aseHours, 0);
    const double mean0 = (100.0 * 55 + 6000.0) / 12;
    EXPECT_NEAR(r.cells[0].mean_lux, mean0, 1e-9);
    EXPECT_NEAR(r.cells[1].mean_lux, 0.5 * mean0, 1e-9);
    EXPECT_NEAR(r.cells[0].meanStdErr_lux, 0.01 * mean0, 1e-9);
    // sDA: cell 0 (area 1) reaches 50 % DA, cell 1 (area 3) does not; ASE: cell 0 only.
    EXPECT_NEAR(r.sda_pct, 25.0, 1e-12);
    EXPECT_NEAR(r.ase_pct, 25.0, 1e-12);
    EXPECT_NEAR(r.meanDa_pct, (100.0 * 8 / 12 + 3 * 100.0 * 5 / 12) / 4, 1e-12);
    EXPECT_THROW(annualStudy(std::vector<double>(3), std::vector<double>(3), {1.0}, skies, s), Error);
    s.exactSun = true;
    EXPECT_THROW(annualStudy(D, se, {1.0, 3.0}, skies, s), Error);  // no direct sun given

    // The sun apart (five-phase): cell 0's patch column is 0.6 direct and 0.4 indirect, and the
    // pass gives it 1500 lux of direct sun in the sunny hours, cell 1 none (its column is all
    // indirect). E = D v - D_direct L_sun + S.
    D[(cells + 0) * P + cap] = 0.6;
    D[(2 * cells + 0) * P + cap] = 0.4;
    se[(cells + 0) * P + cap] = 0.015;
    se[(2 * cells + 0) * P + cap] = 0.02;
    std::vector<std::size_t> asked;
    const DirectSunSource sun = [&](std::size_t first, std::size_t count) {
        asked.push_back(count);
        std::vector<float> S(count * 10, 0.0f);
        for (std::size_t c = first; c < first + count; ++c)
            for (int h = 8; h <= 10; ++h)
                S[(c - first) * 10 + (h - 1)] = c == 0 ? 1500.0f : 0.0f;
        return S;
    };
    s.aseHours = 2.0;
    const AnnualResult x = annualStudy(D, se, {1.0, 3.0}, skies, s, &sun);
    EXPECT_EQ(asked, std::vector<std::size_t>{2});  // both cells in one piece
    // cell 0: 100..700, then 100 h + 2000 - 1200 + 1500 lux
    EXPECT_NEAR(x.cells[0].mean_lux, (100.0 * 55 + 3 * 2300.0) / 12, 1e-9);
    EXPECT_EQ(x.cells[0].aseHours, 3);
    EXPECT_NEAR(x.cells[0].sunMean_lux, 3 * 1500.0 / 12, 1e-9);
    EXPECT_NEAR(x.cells[0].da_pct, 100.0 * 8 / 12, 1e-12);
    // cell 1: 0.5 of the sky, its sun's light all indirect: as before
    EXPECT_NEAR(x.cells[1].mean_lux, 0.5 * mean0, 1e-9);
    EXPECT_EQ(x.cells[1].aseHours, 0);
    EXPECT_EQ(x.cells[1].sunMean_lux, 0.0);
    // the yearly mean's standard error: the sun's patch weighs D by its sky, D_indirect by the sun,
    // their covariance (var D - var D_direct + var D_indirect) / 2 from the three variances
    const double sky = mean0 - 6000.0 / 12, sunMean = 6000.0 / 12;
    EXPECT_NEAR(x.cells[0].meanStdErr_lux,
                std::sqrt(sky * sky * 1e-4 + sunMean * sunMean * 4e-4 + sky * sunMean * (1e-4 - 2.25e-4 + 4e-4)), 1e-9);
    EXPECT_NEAR(x.ase_pct, 25.0, 1e-12);
}

}  // namespace
}  // namespace fen
