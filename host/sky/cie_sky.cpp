// cie_sky.cpp — the CIE standard general sky and its goniogram (cie_sky.h).
//
// Grid design. Bilinear interpolation of a smooth L errs by about (h_t^2 L_tt + h_p^2 L_pp) / 8
// in a cell of steps h_t, h_p; relative to L that asks for h^2 <= 8 tol / (|L''| / L). Three
// things curve L:
//   - the indicatrix around the sun: f(chi) has slope f'(0) != 0 at chi = 0, a cone. In the cell
//     whose corner is the sun bilinear misses the cone by at most 0.15 h |f'|/f; at distance r
//     from the sun the cone's sideways curvature is (|f'|/f) / r, and along chi |f''|/f. So the
//     arc step near the sun is h(r) = max(h0, sqrt(8 tol r / (cMax r + sMax))), with sMax and
//     cMax the largest |f'|/f and |f''|/f of the type and h0 = tol / (0.15 sMax);
//   - the gradation phi(Z) = 1 + a exp(b / cos Z), flat at the horizon but sharply bent a few
//     degrees above it when |b| is small (types 12-15): theta step from |phi''|/phi, plus the
//     cross term 2 (|f'|/f)(|phi'|/phi), sampled along theta;
//   - nothing else: theta steps are capped at 1 degree (so that sampling a cell by its integral
//     sees little change of sin theta inside it), phi steps at the curvature cap of f.
// A row's distance from the sun is at least |theta - theta_s|. Columns are graded in arc length
// at m = sin of the largest theta that the sun's grading reaches, so that near the sun phi steps
// are at least as fine in arc as theta steps at the same distance (rows farther away are far
// from the sun anyway). Because the budget adds three error terms and the bounds are estimates,
// every cell is then checked against the formula at its centre and edge midpoints and split
// where it errs by more than kCheckTol: a safety net, which the design as it stands never needs
// (and which converges in 4 rounds when the design tolerances are loosened 5x, tried by hand).
#include "sky/cie_sky.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <glm/geometric.hpp>

#include "util/error.h"

namespace fen {

namespace {

constexpr double kHalfPi = M_PI / 2;
constexpr double kTwoPi = 2 * M_PI;
constexpr double kRadPerDeg = M_PI / 180;

// ISO 15469:2004 / CIE S 011/E:2003, Table 1: gradation group (a, b), indicatrix group (c, d, e).
const CieSkyType kCieTypes[15] = {
    // {a, b, c, d, e}             type, group: description
    {4.0, -0.70, 0, -1.0, 0.00},    //  1 I.1   overcast, steep gradation, azimuthally uniform
    {4.0, -0.70, 2, -1.5, 0.15},    //  2 I.2   overcast, steep gradation, brighter sunwards
    {1.1, -0.80, 0, -1.0, 0.00},    //  3 II.1  overcast, moderate gradation, azimuthally uniform
    {1.1, -0.80, 2, -1.5, 0.15},    //  4 II.2  overcast, moderate gradation, brighter sunwards
    {0.0, -1.00, 0, -1.0, 0.00},    //  5 III.1 uniform luminance
    {0.0, -1.00, 2, -1.5, 0.15},    //  6 III.2 partly cloudy, no gradation, brighter sunwards
    {0.0, -1.00, 5, -2.5, 0.30},    //  7 III.3 partly cloudy, no gradation, bright circumsolar
    {0.0, -1.00, 10, -3.0, 0.45},   //  8 III.4 partly cloudy, no gradation, distinct solar corona
    {-1.0, -0.55, 2, -1.5, 0.15},   //  9 IV.2  partly cloudy, obscured sun
    {-1.0, -0.55, 5, -2.5, 0.30},   // 10 IV.3  partly cloudy, brighter circumsolar region
    {-1.0, -0.55, 10, -3.0, 0.45},  // 11 IV.4  white-blue sky, distinct solar corona
    {-1.0, -0.32, 10, -3.0, 0.45},  // 12 V.4   CIE standard clear sky, low turbidity
    {-1.0, -0.32, 16, -3.0, 0.30},  // 13 V.5   CIE standard clear sky, polluted atmosphere
    {-1.0, -0.15, 16, -3.0, 0.30},  // 14 VI.5  cloudless turbid sky, broad solar corona
    {-1.0, -0.15, 24, -2.8, 0.15},  // 15 VI.6  white-blue turbid sky, broad solar corona
};

// Error budget of the design (relative): cone around the sun, the indicatrix's curvature, the
// gradation; and the acceptance test of every cell.
constexpr double kTolCusp = 5e-4;
constexpr double kTolIndicatrix = 8e-4;
constexpr double kTolGradation = 3e-4;
constexpr double kCheckTol = 8e-4;

class CieModel {
public:
    CieModel(const CieSkyType& p, double sunZenithRad, double sunAzimuthRad)
        : p_(p),
          sun_(skyDirection(sunZenithRad, sunAzimuthRad)),
          fEnd_(std::exp(p.d * kHalfPi)),
          norm_(1.0 / (indicatrix(sunZenithRad) * gradation(1.0)))
    {
    }
    const CieSkyType& params() const { return p_; }
    double gradation(double cosZ) const
    {
        return cosZ > 0 ? 1 + p_.a * std::exp(p_.b / cosZ) : 1.0;
    }
    double indicatrix(double chi) const
    {
        const double c = std::cos(chi);
        return 1 + p_.c * (std::exp(p_.d * chi) - fEnd_) + p_.e * c * c;
    }
    // L / L_zenith towards the unit vector v (v.y = cos Z >= 0).
    double relative(const glm::dvec3& v) const
    {
        const double chi = std::atan2(glm::length(glm::cross(v, sun_)), glm::dot(v, sun_));
        return indicatrix(chi) * gradation(v.y) * norm_;
    }

private:
    CieSkyType p_;
    glm::dvec3 sun_;
    double fEnd_;
    double norm_;
};

// Nodes from x0 (excluded) to end (included), each step at most step(x) at both of its ends.
std::vector<double> march(double x0, double end, const std::function<double(double)>& step)
{
    std::vector<double> out;
    const double dir = end > x0 ? 1.0 : -1.0;
    double x = x0;
    for (;;) {
        double h = step(x);
        h = std::min(h, step(x + dir * h));
        const double remaining = std::abs(end - x);
        if (remaining <= h * (1 + 1e-9)) {
            out.push_back(end);
            return out;
        }
        if (remaining < 2 * h)  // two equal steps rather than a sliver at the end
            h = 0.5 * remaining;
        x += dir * h;
        out.push_back(x);
    }
}

// Sorted, without near-duplicates; keeps the first and last exactly.
void sortUnique(std::vector<double>* x)
{
    std::sort(x->begin(), x->end());
    std::vector<double> out;
    for (double v : *x) {
        if (!out.empty() && v - out.back() < 1e-9) {
            if (v == x->back())
                out.back() = v;
            continue;
        }
        out.push_back(v);
    }
    *x = std::move(out);
}

double wrapTwoPi(double x)
{
    double y = std::fmod(x, kTwoPi);
    if (y < 0)
        y += kTwoPi;
    if (y >= kTwoPi)
        y = 0;
    return y;
}

struct Grid {
    std::vector<double> theta, phi;
};

// The grid before the per-cell check (see the file comment).
Grid designGrid(const CieModel& model, double sunZenithRad, double sunAzimuthRad)
{
    const CieSkyType& p = model.params();
    // Largest relative slope and curvature of the indicatrix over chi in [0, pi].
    double sMax = 0, cMax = 0;
    constexpr int kChiSamples = 2000;
    for (int k = 0; k <= kChiSamples; ++k) {
        const double chi = M_PI * k / kChiSamples;
        const double f = model.indicatrix(chi), ex = std::exp(p.d * chi);
        const double f1 = p.c * p.d * ex - p.e * std::sin(2 * chi);
        const double f2 = p.c * p.d * p.d * ex - 2 * p.e * std::cos(2 * chi);
        sMax = std::max(sMax, std::abs(f1) / f);
        cMax = std::max(cMax, std::abs(f2) / f);
    }
    const double inf = std::numeric_limits<double>::infinity();
    const bool sunMatters = sMax > 0 || cMax > 0;
    const double h0 = sMax > 0 ? kTolCusp / (0.15 * sMax) : inf;
    auto sunStep = [&](double r) {  // arc step at distance r from the sun
        if (!sunMatters)
            return inf;
        return std::max(h0, std::sqrt(8 * kTolIndicatrix * r / (cMax * r + sMax)));
    };

    // Gradation: |phi''| / phi + 2 sMax |phi'| / phi on a fine theta table, then a running
    // maximum over a window so that the march cannot step over a peak.
    constexpr int kGradSamples = 4096, kWindow = 24;
    std::vector<double> curv(kGradSamples + 1, 0.0), curvMax(kGradSamples + 1, 0.0);
    for (int k = 0; k <= kGradSamples; ++k) {
        const double z = kHalfPi * k / kGradSamples, cz = std::cos(z), sz = std::sin(z);
        if (cz <= 0 || p.a == 0)
            continue;
        const double g1 = p.b * sz / (cz * cz), g2 = p.b * (1 + sz * sz) / (cz * cz * cz);
        const double ex = p.a * std::exp(p.b / cz), ph = 1 + ex;
        curv[k] = (std::abs(ex * (g2 + g1 * g1)) + 2 * sMax * std::abs(ex * g1)) / ph;
    }
    for (int k = 0; k <= kGradSamples; ++k)
        for (int w = std::max(0, k - kWindow); w <= std::min(kGradSamples, k + kWindow); ++w)
            curvMax[k] = std::max(curvMax[k], curv[w]);
    auto gradStep = [&](double z) {
        const int k =
            std::clamp(static_cast<int>(std::lround(z / kHalfPi * kGradSamples)), 0, kGradSamples);
        return curvMax[k] > 0 ? std::sqrt(8 * kTolGradation / curvMax[k]) : inf;
    };

    Grid g;
    const double capTheta = kRadPerDeg;
    auto thetaStep = [&](double z) {
        return std::min({capTheta, gradStep(z), sunStep(std::abs(z - sunZenithRad))});
    };
    if (sunZenithRad > 0) {
        g.theta = march(sunZenithRad, 0.0, thetaStep);
        std::reverse(g.theta.begin(), g.theta.end());
    }
    g.theta.push_back(sunZenithRad);
    if (sunZenithRad < kHalfPi) {
        const std::vector<double> up = march(sunZenithRad, kHalfPi, thetaStep);
        g.theta.insert(g.theta.end(), up.begin(), up.end());
    }

    if (!sunMatters || sunZenithRad == 0) {  // L does not depend on phi
        g.phi = {0, kHalfPi, M_PI, 3 * kHalfPi, kTwoPi};
        return g;
    }
    // Phi: capped by the indicatrix's curvature alone; graded around the sun in arc length,
    // converted with the largest sin(theta) of the rows that the sun's grading reaches.
    const double capPhi =
        cMax > 0 ? std::min(kHalfPi, 0.9 * std::sqrt(8 * kTolIndicatrix / cMax)) : kHalfPi;
    const double den = 8 * kTolIndicatrix - capPhi * capPhi * cMax;
    const double reach = den > 0 ? capPhi * capPhi * sMax / den : M_PI;
    const double m = std::sin(std::min(sunZenithRad + reach, kHalfPi));
    auto phiStep = [&](double x) {
        return std::min(capPhi, sunStep(m * std::abs(x - sunAzimuthRad)) / m);
    };
    std::vector<double> phi = march(sunAzimuthRad, sunAzimuthRad + M_PI, phiStep);
    const std::vector<double> down = march(sunAzimuthRad, sunAzimuthRad - M_PI, phiStep);
    phi.insert(phi.end(), down.begin(), down.end());
    phi.push_back(sunAzimuthRad);
    phi.push_back(2 * sunAzimuthRad);  // mirror image of phi = 0: keeps the grid symmetric
    for (double& x : phi)
        x = wrapTwoPi(x);
    phi.push_back(0.0);
    phi.push_back(kTwoPi);
    sortUnique(&phi);
    g.phi = std::move(phi);
    return g;
}

// Node angles with their cos and sin, so that the directions of a tensor grid cost no trig.
struct Axis {
    std::vector<double> x, c, s;
    explicit Axis(const std::vector<double>& v) : x(v), c(v.size()), s(v.size())
    {
        for (std::size_t k = 0; k < v.size(); ++k) {
            c[k] = std::cos(v[k]);
            s[k] = std::sin(v[k]);
        }
    }
};
double relativeAt(const CieModel& model, const Axis& t, std::size_t i, const Axis& p, std::size_t j)
{
    return model.relative({t.s[i] * p.s[j], t.c[i], -t.s[i] * p.c[j]});
}

// L / L_zenith at the grid's nodes, after checking every cell at its centre and at the midpoints
// of its edges (each interior edge once, the horizon edge too) and splitting the theta or phi
// intervals that fail. Phi splits are mirrored about the sun's azimuth: the grid stays symmetric.
std::vector<double> tabulate(const CieModel& model, double sunAzimuth, Grid* grid)
{
    std::vector<double> rel;
    for (int round = 0;; ++round) {
        const Axis t(grid->theta), p(grid->phi);
        const std::size_t nt = t.x.size(), np = p.x.size();
        rel.assign(nt * np, 0.0);
        for (std::size_t i = 0; i < nt; ++i)
            for (std::size_t j = 0; j < np; ++j)
                rel[i * np + j] = relativeAt(model, t, i, p, j);
        for (std::size_t j = 0; j < np; ++j)  // one direction: exactly constant
            rel[j] = rel[0];
        for (std::size_t i = 0; i < nt; ++i)  // same directions: exactly equal
            rel[i * np + np - 1] = rel[i * np];
        if (round == 8)
            break;  // not reached in practice; the grid is still valid, only coarser than asked

        std::vector<double> tm(nt - 1), pm(np - 1);
        for (std::size_t i = 0; i + 1 < nt; ++i)
            tm[i] = 0.5 * (t.x[i] + t.x[i + 1]);
        for (std::size_t j = 0; j + 1 < np; ++j)
            pm[j] = 0.5 * (p.x[j] + p.x[j + 1]);
        tm.push_back(kHalfPi);  // the horizon edge, as a "row" of its own
        const Axis tMid(tm), pMid(pm);
        auto err = [](double interpolated, double exact) {
            return std::abs(interpolated - exact) / exact;
        };
        std::vector<char> splitT(nt - 1, 0), splitP(np - 1, 0);
        bool any = false;
        for (std::size_t i = 0; i + 1 < nt; ++i)
            for (std::size_t j = 0; j + 1 < np; ++j) {
                const double v00 = rel[i * np + j], v01 = rel[i * np + j + 1];
                const double v10 = rel[(i + 1) * np + j], v11 = rel[(i + 1) * np + j + 1];
                const double eT = err(0.5 * (v00 + v10), relativeAt(model, tMid, i, p, j));
                const double eP = err(0.5 * (v00 + v01), relativeAt(model, t, i, pMid, j));
                const double eC =
                    err(0.25 * (v00 + v01 + v10 + v11), relativeAt(model, tMid, i, pMid, j));
                bool st = eT > kCheckTol, sp = eP > kCheckTol;
                if (eC > kCheckTol && !st && !sp) {
                    const double arcT = t.x[i + 1] - t.x[i],
                                 arcP = t.s[i + 1] * (p.x[j + 1] - p.x[j]);
                    (arcT >= arcP ? st : sp) = true;
                }
                if (st)
                    splitT[i] = 1;
                if (sp)
                    splitP[j] = 1;
                any = any || st || sp;
            }
        for (std::size_t j = 0; j + 1 < np; ++j) {
            const std::size_t last = (nt - 1) * np;
            if (err(0.5 * (rel[last + j] + rel[last + j + 1]),
                    relativeAt(model, tMid, nt - 1, pMid, j)) > kCheckTol) {
                splitP[j] = 1;
                any = true;
            }
        }
        if (!any)
            break;
        for (std::size_t i = 0; i + 1 < nt; ++i)
            if (splitT[i])
                grid->theta.push_back(tm[i]);
        for (std::size_t j = 0; j + 1 < np; ++j)
            if (splitP[j]) {
                grid->phi.push_back(pm[j]);
                grid->phi.push_back(wrapTwoPi(2 * sunAzimuth - pm[j]));  // keep the mirror image
            }
        sortUnique(&grid->theta);
        sortUnique(&grid->phi);
        grid->phi.front() = 0.0;
        grid->phi.back() = kTwoPi;
    }

    return rel;
}

}  // namespace

const CieSkyType& cieSkyType(int type)
{
    if (type < 1 || type > 15)
        throw Error(
            cat("CIE standard general sky type ", type, " does not exist (types are 1..15)"));
    return kCieTypes[type - 1];
}

double cieRelativeLuminance(int type, double zenithRad, double azimuthRad, double sunZenithRad,
                            double sunAzimuthRad)
{
    const CieModel model(cieSkyType(type), sunZenithRad, sunAzimuthRad);
    if (zenithRad > kHalfPi)
        return 0.0;
    return model.relative(skyDirection(zenithRad, azimuthRad));
}

Goniogram cieFormulaSky(const CieSkyType& p, double zenithLuminance_cd_m2, double sunAltitudeDeg,
                        double sunAzimuthDeg, const std::string& where)
{
    if (!std::isfinite(zenithLuminance_cd_m2) || zenithLuminance_cd_m2 < 0)
        throw Error(cat(where, ".zenith_luminance: must be finite and >= 0 cd/m^2 (got ",
                        zenithLuminance_cd_m2, ")"));
    if (!std::isfinite(sunAltitudeDeg) || sunAltitudeDeg < 0 || sunAltitudeDeg > 90)
        throw Error(cat(where, ".sun_altitude_deg: must be in [0, 90] (got ", sunAltitudeDeg, ")"));
    if (!std::isfinite(sunAzimuthDeg))
        throw Error(cat(where, ".sun_azimuth_deg: must be finite (got ", sunAzimuthDeg, ")"));

    const double sunZenith = sunAltitudeDeg == 0 ? kHalfPi : (90 - sunAltitudeDeg) * kRadPerDeg;
    double azDeg = std::fmod(sunAzimuthDeg, 360.0);
    if (azDeg < 0)
        azDeg += 360.0;
    const double sunAzimuth = wrapTwoPi(azDeg * kRadPerDeg);
    const CieModel model(p, sunZenith, sunAzimuth);
    Grid grid = designGrid(model, sunZenith, sunAzimuth);

    const std::vector<double> rel = tabulate(model, sunAzimuth, &grid);
    std::vector<double> values(rel.size());
    for (std::size_t k = 0; k < rel.size(); ++k)
        values[k] = zenithLuminance_cd_m2 * rel[k];
    return Goniogram(std::move(grid.theta), std::move(grid.phi), std::move(values), where);
}

Goniogram cieSky(int type, double zenithLuminance_cd_m2, double sunAltitudeDeg,
                 double sunAzimuthDeg, const std::string& where)
{
    if (type < 1 || type > 15)
        throw Error(cat(where, ".cie_type: must be an integer 1..15 (got ", type, ")"));
    return cieFormulaSky(kCieTypes[type - 1], zenithLuminance_cd_m2, sunAltitudeDeg, sunAzimuthDeg, where);
}

}  // namespace fen
