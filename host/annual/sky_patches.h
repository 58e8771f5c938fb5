// sky_patches.h — Reinhart's subdivision of the sky into patches (DESIGN.md §8 "Daylight
// coefficients"): the columns of a daylight-coefficient matrix, and a sky as one luminance per patch.
//
// Numbered as Radiance's reinhart.cal numbers them (and kernels/lib/sky_patch.h, the device's twin),
// so that fenestra's matrices line up with Radiance's: patch 0 the ground (every direction below the
// horizon), then rows of altitude alpha = 90 / (7 MF + 0.5) degrees from the horizon up, row r holding
// MF x (30, 30, 24, 24, 18, 12, 6)[r / MF] patches of equal azimuth width, the first centred on
// north, then towards east; the last row (r = 7 MF) is one cap round the zenith. MF 1 is Tregenza's
// 145 sky patches; each doubling of MF about quadruples them. Azimuth from north (-z) towards east
// (+x), y up, as every direction in fenestra (sky/goniogram.h).
// A daylight coefficient D[s][p] is the illuminance at sensor cell s per unit luminance (cd/m^2)
// of patch p, so sr; a sky of patch luminances L_p gives E_s = sum_p D[s][p] L_p.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace fen {

class Goniogram;

constexpr int kMaxSkyPatchMF = 16;  // 36,866 patches; the matrices grow with cells x patches

struct SkyPatch {
    double altLoDeg = 0.0, altHiDeg = 0.0;  // altitude band (the ground: -90..0)
    double aziCentreDeg = 0.0, aziWidthDeg = 360.0;
    double solidAngle_sr = 0.0;
    glm::dvec3 centre{0.0, 1.0, 0.0};  // unit, towards the patch's centre (the ground: straight down)
};

// Patches of subdivision MF (ground included): 146 for MF 1, 578 for MF 2, 2306 for MF 4.
std::size_t skyPatchCount(int mf);
std::vector<SkyPatch> skyPatches(int mf);
// The patch a direction towards the sky (any non-zero length) falls in.
std::size_t skyPatchOf(const glm::dvec3& towardsSky, int mf);

// A sky as patch luminances (cd/m^2): each patch's mean luminance over its solid angle (the
// goniogram integrated on a grid of at least 8 x 8 points a patch, finer for wide patches), the
// ground its glow (0 without one). With a sun: its normal illuminance sunNormal_lux added to the
// patch it stands in, as luminance over that patch's solid angle -- so the patch vector keeps the sky's and the
// sun's illuminance of any plane that does not cut the patch (Radiance's two-phase method puts the
// sun in patches the same way; its gendaymtx spreads it over the four nearest).
std::vector<double> patchLuminance(const Goniogram* sky, int mf, const glm::dvec3& towardsSun = glm::dvec3(0.0),
                                   double sunNormal_lux = 0.0);
// The points a patch's mean luminance is taken over, equally spaced in solid angle: patch k's are
// directions[first[k] .. first[k + 1]) (none for the ground, k = 0). Made once, used for every sky.
struct PatchPoints {
    std::vector<glm::dvec3> directions;  // unit, towards the sky
    std::vector<std::size_t> first;      // patches + 1 entries
};
PatchPoints patchPoints(int mf);
// Each sky patch's mean of `luminance` (towards a unit direction) over its points (entry 0, the
// ground, left 0); and each patch's projected solid angle (the integral of cos(zenith)), so that
// sum_p mean_p proj_p is the sky's horizontal illuminance.
std::vector<double> patchMeans(const PatchPoints& points, const std::function<double(const glm::dvec3&)>& luminance);
std::vector<double> patchProjectedSolidAngles(int mf);
// Where the sun goes in a patch sky: the patch it stands in and the luminance its normal
// illuminance adds there (over that patch's solid angle); {0, 0} with no sun (none, or below the
// horizon). `patches`: skyPatches(mf), made once by a caller that places many suns.
struct SunInPatch {
    std::size_t patch = 0;
    double luminance_cd_m2 = 0.0;
};
SunInPatch sunInPatch(const std::vector<SkyPatch>& patches, int mf, const glm::dvec3& towardsSun, double sunNormal_lux);
// The same sky when each patch is already known: only the sun added (in place).
void addSunToPatches(std::vector<double>& patches, int mf, const glm::dvec3& towardsSun, double sunNormal_lux);

}  // namespace fen
