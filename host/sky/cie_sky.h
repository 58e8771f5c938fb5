// cie_sky.h — the CIE standard general sky (ISO 15469:2004 / CIE S 011/E:2003), tabulated as a
// goniogram (DESIGN.md §1 "Sky", §6 `"type": "cie"`).
//
// Relative luminance of a sky element at zenith angle Z and azimuth az, the sun at (Zs, az_s),
// chi the angle between them:
//   gradation  phi(Z)  = 1 + a exp(b / cos Z)                      (phi = 1 at Z = 90 deg)
//   indicatrix f(chi)  = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi
//   L / L_zenith       = f(chi) phi(Z) / (f(Zs) phi(0))
// The 15 (a, b, c, d, e) sets are Table 1 of ISO 15469:2004 / CIE S 011/E:2003 (six gradation
// groups I-VI x six indicatrix groups 1-6). The values were checked against two independent
// public transcriptions: the R package rcaiman (inst/external/15_CIE_standard_skies.csv, citing
// CIE 2004 and Li et al. 2016) and DigitalRune's CieSkyParameters (Type1..Type15); both agree
// with the table in cie_sky.cpp digit for digit.
//
// A CIE sky never includes the sun itself (§6): the sun is only the directional light.
#pragma once

#include <string>

#include "sky/goniogram.h"

namespace fen {

struct CieSkyType {
    double a, b;     // gradation
    double c, d, e;  // indicatrix
};

// The parameters of type 1..15; throws fen::Error for any other number.
const CieSkyType& cieSkyType(int type);

// L / L_zenith at a sky point (zenith angle, azimuth from north towards east) for the sun at
// (sunZenith, sunAzimuth), all radians; 0 below the horizon (zenith > pi/2). Exactly the
// formula above; 1 at the zenith to rounding. Throws fen::Error for a type outside 1..15.
double cieRelativeLuminance(int type, double zenithRad, double azimuthRad, double sunZenithRad,
                            double sunAzimuthRad);

// The CIE sky of `type` (1..15) with zenith luminance `zenithLuminance_cd_m2` (>= 0) for the sun
// at altitude sunAltitudeDeg in [0, 90] and azimuth sunAzimuthDeg (any finite value, wrapped),
// tabulated as a bilinear goniogram. Errors name `where` and the key: "<where>.cie_type: ...",
// "<where>.zenith_luminance: ...", "<where>.sun_altitude_deg: ...", "<where>.sun_azimuth_deg: ...".
//
// Accuracy: |g - L| / L < 0.1 % everywhere on the hemisphere, the sun's own direction included
// (L: the formula above times L_zenith), although f has a cone-shaped cusp there. The grid is
// uneven. The sun's direction is a node. Theta steps are at most 1 degree (so that sampling a
// cell by its integral sees little change of sin theta inside it), graded down towards the
// sun's theta (to 0.07 degree next to the sun for the types with a bright corona, 0.2 degree for
// the faint ones) and wherever the gradation bends sharply (to 0.25 degree in the last degrees
// above the horizon for types 14, 15). Phi steps are graded the same way, in arc length, towards
// the sun's azimuth; the grid also carries the mirror image of phi = 0 about the sun's azimuth,
// so it is symmetric about the sun's vertical plane to rounding. Every cell is then checked
// against the formula at its centre and edge midpoints at 0.08 % and split where it fails (a
// safety net; the design as it stands passes). Measured (tests/host/sky_test.cpp, and a sweep
// of all 15 types over sun altitudes 0..90 in 0.5 degree steps at random azimuths): largest
// error 0.067 %, largest grid 42,924 cells (type 14, low sun). Types 1, 3 and 5 do not depend on
// the sun's position, nor does any type with the sun at the zenith depend on azimuth: 4 phi
// cells suffice (types 1, 3, 5: 364 to 384 cells in all).
Goniogram cieSky(int type, double zenithLuminance_cd_m2, double sunAltitudeDeg,
                 double sunAzimuthDeg, const std::string& where = "sky");

// The same tabulation for any parameters of the formula above (the Perez all-weather sky is one,
// perez_sky.h): the grid design and the per-cell check adapt to p. Errors as cieSky's.
Goniogram cieFormulaSky(const CieSkyType& p, double zenithLuminance_cd_m2, double sunAltitudeDeg,
                        double sunAzimuthDeg, const std::string& where = "sky");

}  // namespace fen
