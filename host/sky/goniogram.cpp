// goniogram.cpp — the bilinear sky table (goniogram.h): checks, evaluation, exact cell
// integrals, illuminance, refinement; the uniform and user-table skies of DESIGN.md §6.
//
// The cell integrals are products of 1-D integrals of the hat weights (1 - t, t) against sin,
// sin^2, sin cos (theta) and 1, sin, cos (phi). They are written around the interval's midpoint
// with sin(y)/y - cos(y) and y - sin(y) expanded in series for small y, so that a cell of any
// size, even one at the pole, loses no digits to cancellation.
#include "sky/goniogram.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "util/error.h"

namespace fen {

namespace {

constexpr double kHalfPi =
    M_PI / 2;  // the double nearest pi/2: exactly what "theta ends at pi/2" means
constexpr double kTwoPi = 2 * M_PI;
constexpr double kRadPerDeg = M_PI / 180;

// a + t (b - a): exact at t = 0, and exact for a == b, which keeps a constant row constant.
double lerp(double a, double b, double t)
{
    return a + t * (b - a);
}

// sin(y)/y - cos(y)
double sincMinusCos(double y)
{
    if (std::abs(y) < 0.05) {
        const double y2 = y * y;
        return y2 * (1.0 / 3 - y2 * (1.0 / 30 - y2 * (1.0 / 840 - y2 / 45360)));
    }
    return std::sin(y) / y - std::cos(y);
}

// y - sin(y)
double yMinusSin(double y)
{
    if (std::abs(y) < 0.05) {
        const double y2 = y * y;
        return y * y2 * (1.0 / 6 - y2 * (1.0 / 120 - y2 * (1.0 / 5040 - y2 / 362880)));
    }
    return y - std::sin(y);
}

// ∫ over [a, b] of (1 - t) k and t k, t = (x - a) / (b - a). With m the midpoint and d the half
// width: (E -+ O / d) / 2, E = ∫ k, O = ∫ (x - m) k.
struct Hat {
    double w0, w1;
};
Hat hat(double evenPart, double oddOverD)
{
    return {0.5 * evenPart - oddOverD, 0.5 * evenPart + oddOverD};
}

struct ThetaWeights {
    Hat sin, sin2, sinCos;
};
ThetaWeights thetaWeights(double a, double b)
{
    const double m = 0.5 * (a + b), d = 0.5 * (b - a);
    const double sm = std::sin(m), cm = std::cos(m), s2m = std::sin(2 * m), c2m = std::cos(2 * m);
    const double s1 = sincMinusCos(d), s2 = sincMinusCos(2 * d);
    ThetaWeights w;
    w.sin = hat(2 * sm * std::sin(d), cm * s1);
    w.sin2 = hat(2 * d * sm * sm + 0.5 * c2m * yMinusSin(2 * d), 0.25 * s2m * s2);
    w.sinCos = hat(0.5 * s2m * std::sin(2 * d), 0.25 * c2m * s2);
    return w;
}

struct PhiWeights {
    Hat one, sin, cos;
};
PhiWeights phiWeights(double a, double b)
{
    const double m = 0.5 * (a + b), d = 0.5 * (b - a);
    const double sm = std::sin(m), cm = std::cos(m), sd = std::sin(d), s1 = sincMinusCos(d);
    PhiWeights w;
    w.one = {d, d};
    w.sin = hat(2 * sm * sd, cm * s1);
    w.cos = hat(2 * cm * sd, -sm * s1);
    return w;
}

// A rectangle of (theta, phi) with the bilinear corner values v[a][b] at (theta_a, phi_b).
struct Patch {
    double t0, t1, p0, p1;
    double v[2][2];
};

double sumHat(const Hat& ht, const Hat& hp, const double (&v)[2][2])
{
    return ht.w0 * (hp.w0 * v[0][0] + hp.w1 * v[0][1]) +
           ht.w1 * (hp.w0 * v[1][0] + hp.w1 * v[1][1]);
}

// ∫_patch w g dw, w = (sin t sin p, cos t, -sin t cos p), dw = sin t dt dp.
glm::dvec3 directionIntegral(const Patch& c)
{
    const ThetaWeights wt = thetaWeights(c.t0, c.t1);
    const PhiWeights wp = phiWeights(c.p0, c.p1);
    return {sumHat(wt.sin2, wp.sin, c.v), sumHat(wt.sinCos, wp.one, c.v),
            -sumHat(wt.sin2, wp.cos, c.v)};
}

bool angleIn(double x, double lo, double hi)
{
    // x moved into [lo, lo + 2 pi)
    double y = std::fmod(x - lo, kTwoPi);
    if (y < 0)
        y += kTwoPi;
    return lo + y <= hi;
}

// Exact minimum and maximum of w . n over a patch: at a corner, on an edge where the edge's
// 1-D function is extremal, or at +-n itself (a linear function on the sphere has no other
// critical points).
void dotRange(const glm::dvec3& n, const Patch& c, double* lo, double* hi)
{
    double mn = std::numeric_limits<double>::infinity(), mx = -mn;
    auto at = [&](double t, double p) {
        const double v = glm::dot(skyDirection(t, p), n);
        mn = std::min(mn, v);
        mx = std::max(mx, v);
    };
    for (double t : {c.t0, c.t1})
        for (double p : {c.p0, c.p1})
            at(t, p);
    // theta = const: w . n = sin t (nx sin p - nz cos p) + ny cos t,
    // extremal at p = alpha and alpha + pi
    const double alpha = std::atan2(n.x, -n.z);
    for (double p : {alpha, alpha + M_PI})
        if (angleIn(p, c.p0, c.p1))
            for (double t : {c.t0, c.t1})
                at(t, p);
    // phi = const: w . n = P sin t + ny cos t, extremal at t = beta + k pi
    for (double p : {c.p0, c.p1}) {
        const double beta = std::atan2(n.x * std::sin(p) - n.z * std::cos(p), n.y);
        for (double t : {beta - M_PI, beta, beta + M_PI})
            if (t >= c.t0 && t <= c.t1)
                at(t, p);
    }
    for (double sign : {1.0, -1.0}) {
        double t, p;
        skyAngles(sign * n, &t, &p);
        if (t >= c.t0 && t <= c.t1 && angleIn(p, c.p0, c.p1))
            at(t, p);
    }
    *lo = mn;
    *hi = mx;
}

double bilinear(const Patch& c, double s, double u)  // s, u in [0, 1]
{
    return lerp(lerp(c.v[0][0], c.v[0][1], u), lerp(c.v[1][0], c.v[1][1], u), s);
}

// ∫_patch g max(0, w . n) dw for a patch that the plane may cut: exact on the pieces that lie on
// one side, 4 x 4 Gauss-Legendre on cut pieces below kLeafRad across. Near the cut the integrand
// is below kLeafRad * g, so the kink's error is O(kLeafRad^2) of the total: about 1e-8 at 5e-3
// rad, measured against the uniform sky's closed form for tilted planes (the brief: 1e-6).
double clippedIntegral(const glm::dvec3& n, const Patch& c, int depth)
{
    constexpr double kLeafRad = 5e-3;
    if (!(c.t1 > c.t0))
        return 0.0;  // the zero-width cell of a horizon step: nothing to integrate
    const double arcT = c.t1 - c.t0, arcP = std::sin(c.t1) * (c.p1 - c.p0);
    // Cheap bound first: w . n moves by at most the arc length, which is below arcT + arcP.
    double cornerMin = std::numeric_limits<double>::infinity(), cornerMax = -cornerMin;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const double v = glm::dot(skyDirection(a ? c.t1 : c.t0, b ? c.p1 : c.p0), n);
            cornerMin = std::min(cornerMin, v);
            cornerMax = std::max(cornerMax, v);
        }
    double lo = cornerMax - (arcT + arcP), hi = cornerMin + (arcT + arcP);
    if (lo < 0 && hi > 0)
        dotRange(n, c, &lo, &hi);
    if (lo >= 0)
        return glm::dot(directionIntegral(c), n);
    if (hi <= 0)
        return 0.0;
    if (arcT + arcP < kLeafRad || depth > 60) {
        static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                    0.8611363115940526};
        static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                    0.3478548451374538};
        double sum = 0;
        for (int a = 0; a < 4; ++a) {
            const double s = 0.5 * (1 + x[a]), t = c.t0 + s * (c.t1 - c.t0);
            for (int b = 0; b < 4; ++b) {
                const double u = 0.5 * (1 + x[b]), p = c.p0 + u * (c.p1 - c.p0);
                const double cosine = glm::dot(skyDirection(t, p), n);
                if (cosine > 0)
                    sum += w[a] * w[b] * bilinear(c, s, u) * cosine * std::sin(t);
            }
        }
        return sum * 0.25 * (c.t1 - c.t0) * (c.p1 - c.p0);
    }
    // Split the longer side (in arc length), both when they are comparable, so pieces stay square.
    const bool splitT = arcT >= 0.5 * arcP, splitP = arcP >= 0.5 * arcT;
    const int nt = splitT ? 2 : 1, np = splitP ? 2 : 1;
    double sum = 0;
    for (int a = 0; a < nt; ++a)
        for (int b = 0; b < np; ++b) {
            Patch q;
            const double s0 = double(a) / nt, s1 = double(a + 1) / nt;
            const double u0 = double(b) / np, u1 = double(b + 1) / np;
            q.t0 = lerp(c.t0, c.t1, s0);
            q.t1 = a + 1 == nt ? c.t1 : lerp(c.t0, c.t1, s1);
            q.p0 = lerp(c.p0, c.p1, u0);
            q.p1 = b + 1 == np ? c.p1 : lerp(c.p0, c.p1, u1);
            q.v[0][0] = bilinear(c, s0, u0);
            q.v[0][1] = bilinear(c, s0, u1);
            q.v[1][0] = bilinear(c, s1, u0);
            q.v[1][1] = bilinear(c, s1, u1);
            sum += clippedIntegral(n, q, depth + 1);
        }
    return sum;
}

// How many equal pieces an interval of length h needs so that none exceeds maxStep (the
// 1e-12 forgives a step that is maxStep up to rounding).
std::size_t pieces(double h, double maxStep)
{
    if (std::isinf(maxStep))
        return 1;
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(h / maxStep * (1 - 1e-12))));
}

// Nodes [from, to] of x strictly increasing from exactly `first` to exactly `last`.
void checkAxis(const std::vector<double>& x, std::size_t from, std::size_t to, const char* name, double first,
               const char* firstName, double last, const char* lastName, const std::string& where)
{
    for (std::size_t k = from; k <= to; ++k) {
        if (!std::isfinite(x[k]))
            throw Error(cat(where, ": goniogram ", name, " node ", k, " is not finite"));
        if (k > from && !(x[k] > x[k - 1]))
            throw Error(cat(where, ": goniogram ", name, " must be strictly increasing (node ", k,
                            " = ", x[k], " after ", x[k - 1], ")"));
    }
    if (x[from] != first || x[to] != last)
        throw Error(cat(where, ": goniogram ", name, from > 0 ? "'s ground rows" : "", " must start at exactly ",
                        firstName, " and end at exactly ", lastName, " (got ", x[from], " .. ", x[to], ")"));
}

void checkAxis(const std::vector<double>& x, const char* name, double last, const char* lastName,
               const std::string& where)
{
    if (x.size() < 2)
        throw Error(
            cat(where, ": goniogram ", name, " needs at least 2 nodes (got ", x.size(), ")"));
    checkAxis(x, 0, x.size() - 1, name, 0.0, "0", last, lastName, where);
}

}  // namespace

glm::dvec3 skyDirection(double thetaRad, double phiRad)
{
    const double st = std::sin(thetaRad);
    return {st * std::sin(phiRad), std::cos(thetaRad), -st * std::cos(phiRad)};
}

void skyAngles(const glm::dvec3& towardsSky, double* thetaRad, double* phiRad)
{
    const glm::dvec3& d = towardsSky;
    *thetaRad = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
    double p = std::atan2(d.x, -d.z);
    if (p < 0)
        p += kTwoPi;
    if (p >= kTwoPi)  // -tiny + 2 pi rounds to 2 pi
        p = 0;
    *phiRad = p;
}

Goniogram::Goniogram(std::vector<double> theta, std::vector<double> phi, std::vector<double> values,
                     const std::string& where)
    : theta_(std::move(theta)), phi_(std::move(phi)), values_(std::move(values))
{
    // theta: the sky's nodes 0 .. pi/2; over the whole sphere, then pi/2 again .. pi (the ground's).
    if (theta_.size() >= 2 && theta_.back() == M_PI) {
        const auto h = std::find(theta_.begin(), theta_.end(), kHalfPi);
        if (h == theta_.end() || h + 1 == theta_.end() || h[1] != kHalfPi)
            throw Error(cat(where, ": goniogram theta ends at pi, so it must hold pi/2 twice: the sky's horizon row, ",
                            "then the ground's"));
        horizon_ = static_cast<std::size_t>(h - theta_.begin());
        checkAxis(theta_, 0, horizon_, "theta", 0.0, "0", kHalfPi, "pi/2", where);
        checkAxis(theta_, horizon_ + 1, theta_.size() - 1, "theta", kHalfPi, "pi/2", M_PI, "pi", where);
    } else {
        checkAxis(theta_, "theta", kHalfPi, "pi/2 (or, with a ground, at pi)", where);
        horizon_ = theta_.size() - 1;
    }
    checkAxis(phi_, "phi", kTwoPi, "2 pi", where);
    const std::size_t nt = theta_.size(), np = phi_.size();
    if (values_.size() != nt * np)
        throw Error(cat(where, ": goniogram has ", values_.size(), " values, expected ", nt, " x ",
                        np, " = ", nt * np));
    for (std::size_t i = 0; i < nt; ++i)
        for (std::size_t j = 0; j < np; ++j) {
            const double v = value(i, j);
            if (!std::isfinite(v))
                throw Error(
                    cat(where, ": goniogram value at node (", i, ", ", j, ") is not finite"));
            if (v < 0)
                throw Error(cat(where, ": goniogram value at node (", i, ", ", j, ") is negative (",
                                v, ")"));
        }
    for (std::size_t i = 0; i < nt; ++i)
        if (value(i, 0) != value(i, np - 1))
            throw Error(cat(where, ": goniogram columns phi = 0 and phi = 2 pi are the same ",
                            "directions but differ at theta node ", i, " (", value(i, 0), " vs ",
                            value(i, np - 1), ")"));
    for (std::size_t j = 1; j < np; ++j)
        if (value(0, j) != value(0, 0))
            throw Error(cat(where, ": goniogram row theta = 0 is one direction and must be ",
                            "constant (node (0, ", j, ") = ", value(0, j), ", node (0, 0) = ",
                            value(0, 0), ")"));
    if (hasGround())
        for (std::size_t j = 1; j < np; ++j)
            if (value(nt - 1, j) != value(nt - 1, 0))
                throw Error(cat(where, ": goniogram row theta = pi is one direction and must be ",
                                "constant (node (", nt - 1, ", ", j, ") = ", value(nt - 1, j), ", node (", nt - 1,
                                ", 0) = ", value(nt - 1, 0), ")"));
}

double Goniogram::eval(double thetaRad, double phiRad) const
{
    if (std::isnan(thetaRad) || std::isnan(phiRad) || std::isinf(phiRad))
        return std::numeric_limits<double>::quiet_NaN();
    if (thetaRad < 0) {
        thetaRad = -thetaRad;
        phiRad += M_PI;
    }
    const bool below = thetaRad > kHalfPi;
    if (below && !hasGround())
        return 0.0;
    double p = std::fmod(phiRad, kTwoPi);
    if (p < 0)
        p += kTwoPi;
    if (p >= kTwoPi)
        p = 0;
    const std::size_t np = phi_.size();
    const std::size_t j =
        static_cast<std::size_t>(std::upper_bound(phi_.begin(), phi_.end(), p) - phi_.begin()) - 1;
    const double u = (p - phi_[j]) / (phi_[j + 1] - phi_[j]);
    auto row = [&](std::size_t i) { return lerp(values_[i * np + j], values_[i * np + j + 1], u); };
    // The sky's rows [0, horizon_], or the ground's [horizon_ + 1, last].
    const std::size_t first = below ? horizon_ + 1 : 0, last = below ? theta_.size() - 1 : horizon_;
    if (thetaRad >= theta_[last])  // the horizon row (or the nadir) itself, so that a node there is exact
        return row(last);
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(theta_.begin() + first, theta_.begin() + last + 1, thetaRad) -
                                 theta_.begin()) -
        1;
    const double t = (thetaRad - theta_[i]) / (theta_[i + 1] - theta_[i]);
    return lerp(row(i), row(i + 1), t);
}

double Goniogram::evalDirection(const glm::dvec3& towardsSky) const
{
    if (towardsSky.y < 0 && !hasGround())
        return 0.0;
    double t, p;
    skyAngles(towardsSky, &t, &p);
    return eval(t, p);
}

double Goniogram::cellIntegralSin(std::size_t i, std::size_t j) const
{
    const Hat ht = thetaWeights(theta_[i], theta_[i + 1]).sin;
    const double halfDphi = 0.5 * (phi_[j + 1] - phi_[j]);
    return halfDphi * (ht.w0 * (value(i, j) + value(i, j + 1)) +
                       ht.w1 * (value(i + 1, j) + value(i + 1, j + 1)));
}

double Goniogram::cellIntegralFlat(std::size_t i, std::size_t j) const
{
    return 0.25 * (theta_[i + 1] - theta_[i]) * (phi_[j + 1] - phi_[j]) *
           (value(i, j) + value(i, j + 1) + value(i + 1, j) + value(i + 1, j + 1));
}

glm::dvec3 Goniogram::cellDirectionIntegral(std::size_t i, std::size_t j) const
{
    const Patch c{theta_[i],
                  theta_[i + 1],
                  phi_[j],
                  phi_[j + 1],
                  {{value(i, j), value(i, j + 1)}, {value(i + 1, j), value(i + 1, j + 1)}}};
    return directionIntegral(c);
}

double Goniogram::integral() const
{
    double sum = 0;
    for (std::size_t i = 0; i + 1 < theta_.size(); ++i)
        for (std::size_t j = 0; j + 1 < phi_.size(); ++j)
            sum += cellIntegralSin(i, j);
    return sum;
}

double Goniogram::illuminance(const glm::dvec3& normal) const
{
    const glm::dvec3 n = glm::normalize(normal);
    // The rows' and columns' 1-D weights and trig once, not per cell.
    const std::size_t nt = theta_.size(), np = phi_.size();
    std::vector<ThetaWeights> wt(nt - 1);
    std::vector<PhiWeights> wp(np - 1);
    std::vector<double> st(nt), ct(nt), sp(np), cp(np);
    for (std::size_t i = 0; i < nt; ++i) {
        st[i] = std::sin(theta_[i]);
        ct[i] = std::cos(theta_[i]);
        if (i + 1 < nt)
            wt[i] = thetaWeights(theta_[i], theta_[i + 1]);
    }
    for (std::size_t j = 0; j < np; ++j) {
        sp[j] = std::sin(phi_[j]);
        cp[j] = std::cos(phi_[j]);
        if (j + 1 < np)
            wp[j] = phiWeights(phi_[j], phi_[j + 1]);
    }
    auto cosine = [&](std::size_t i, std::size_t j) {
        return st[i] * (n.x * sp[j] - n.z * cp[j]) + n.y * ct[i];
    };
    double sum = 0;
    for (std::size_t i = 0; i + 1 < nt; ++i)
        for (std::size_t j = 0; j + 1 < np && theta_[i + 1] > theta_[i]; ++j) {
            const Patch c{theta_[i],
                          theta_[i + 1],
                          phi_[j],
                          phi_[j + 1],
                          {{value(i, j), value(i, j + 1)}, {value(i + 1, j), value(i + 1, j + 1)}}};
            // w . n moves by less than the arc length inside the cell (see clippedIntegral).
            const double k00 = cosine(i, j), k01 = cosine(i, j + 1), k10 = cosine(i + 1, j),
                         k11 = cosine(i + 1, j + 1);
            const double arc = (c.t1 - c.t0) + st[i + 1] * (c.p1 - c.p0);
            if (std::min({k00, k01, k10, k11}) + arc <= 0)
                continue;
            if (std::max({k00, k01, k10, k11}) - arc >= 0) {
                const glm::dvec3 f(sumHat(wt[i].sin2, wp[j].sin, c.v),
                                   sumHat(wt[i].sinCos, wp[j].one, c.v),
                                   -sumHat(wt[i].sin2, wp[j].cos, c.v));
                sum += glm::dot(f, n);
                continue;
            }
            sum += clippedIntegral(n, c, 0);
        }
    return sum;
}

double Goniogram::cellClippedIntegral(std::size_t i, std::size_t j, const glm::dvec3& n) const
{
    const Patch c{theta_[i],
                  theta_[i + 1],
                  phi_[j],
                  phi_[j + 1],
                  {{value(i, j), value(i, j + 1)}, {value(i + 1, j), value(i + 1, j + 1)}}};
    return clippedIntegral(n, c, 0);
}

Goniogram Goniogram::refined(double maxThetaStepRad, double maxPhiStepRad) const
{
    if (!(maxThetaStepRad > 0) || !(maxPhiStepRad > 0))
        throw Error(cat("Goniogram::refined: step limits must be > 0 (got ", maxThetaStepRad, ", ",
                        maxPhiStepRad, ")"));
    // A new node is old node k plus fraction f of the way to node k + 1 (f = 0: the old node).
    struct Where {
        double x;
        std::size_t k;
        double f;
    };
    auto split = [](const std::vector<double>& x, double maxStep) {
        std::vector<Where> out;
        for (std::size_t k = 0; k + 1 < x.size(); ++k) {
            const double h = x[k + 1] - x[k];
            const std::size_t n = pieces(h, maxStep);
            if (out.size() + n > 100000000)
                throw Error("Goniogram::refined: the refined grid would be absurdly large");
            for (std::size_t s = 0; s < n; ++s) {
                const double f = double(s) / double(n);
                out.push_back({s == 0 ? x[k] : x[k] + h * f, k, f});
            }
        }
        out.push_back({x.back(), x.size() - 1, 0.0});
        return out;
    };
    const std::vector<Where> nt = split(theta_, maxThetaStepRad), np = split(phi_, maxPhiStepRad);
    std::vector<double> th, ph, v;
    th.reserve(nt.size());
    ph.reserve(np.size());
    v.reserve(nt.size() * np.size());
    for (const Where& w : nt)
        th.push_back(w.x);
    for (const Where& w : np)
        ph.push_back(w.x);
    const std::size_t oldNp = phi_.size();
    auto rowValue = [&](std::size_t i, const Where& c) {
        const double a = values_[i * oldNp + c.k];
        return c.f == 0 ? a : lerp(a, values_[i * oldNp + c.k + 1], c.f);
    };
    for (const Where& r : nt)
        for (const Where& c : np) {
            const double a = rowValue(r.k, c);
            v.push_back(r.f == 0 ? a : lerp(a, rowValue(r.k + 1, c), r.f));
        }
    return Goniogram(std::move(th), std::move(ph), std::move(v), "Goniogram::refined");
}

Goniogram Goniogram::withGround(double groundLuminance_cd_m2, const std::string& where) const
{
    if (hasGround())
        throw Error(cat(where, ": the sky has a ground already"));
    if (!std::isfinite(groundLuminance_cd_m2) || groundLuminance_cd_m2 < 0)
        throw Error(cat(where, ": the ground's luminance must be finite and >= 0 (got ", groundLuminance_cd_m2, ")"));
    std::vector<double> th = theta_, v = values_;
    const std::size_t np = phi_.size();
    for (int k = 0; k <= kGroundThetaSteps; ++k) {
        th.push_back(k == 0 ? kHalfPi : k == kGroundThetaSteps ? M_PI : kHalfPi + kHalfPi * k / kGroundThetaSteps);
        v.insert(v.end(), np, groundLuminance_cd_m2);
    }
    return Goniogram(std::move(th), phi_, std::move(v), where);
}

Goniogram uniformSky(double luminance_cd_m2, const std::string& where)
{
    if (!std::isfinite(luminance_cd_m2) || luminance_cd_m2 < 0)
        throw Error(cat(where, ".luminance: must be finite and >= 0 (got ", luminance_cd_m2, ")"));
    constexpr int kThetaSteps = 90, kPhiSteps = 4;
    std::vector<double> th(kThetaSteps + 1), ph(kPhiSteps + 1);
    for (int i = 0; i <= kThetaSteps; ++i)
        th[i] = i == kThetaSteps ? kHalfPi : kHalfPi * i / kThetaSteps;
    for (int j = 0; j <= kPhiSteps; ++j)
        ph[j] = j == kPhiSteps ? kTwoPi : kTwoPi * j / kPhiSteps;
    return Goniogram(std::move(th), std::move(ph),
                     std::vector<double>(th.size() * ph.size(), luminance_cd_m2), where);
}

namespace {

// One axis of a user table in degrees: checked against DESIGN.md §6, converted to radians with
// the ends exact.
std::vector<double> tableAxis(const std::vector<double>& deg, double endDeg, double endRad,
                              const char* key, const std::string& where)
{
    if (deg.size() < 2)
        throw Error(cat(where, ".", key, ": needs at least 2 values (got ", deg.size(), ")"));
    for (std::size_t k = 0; k < deg.size(); ++k) {
        if (!std::isfinite(deg[k]))
            throw Error(cat(where, ".", key, "[", k, "]: not finite (", deg[k], ")"));
        if (k > 0 && !(deg[k] > deg[k - 1]))
            throw Error(cat(where, ".", key, ": must be strictly increasing (", key, "[", k,
                            "] = ", deg[k], " after ", deg[k - 1], ")"));
    }
    if (deg.front() != 0.0 || deg.back() != endDeg)
        throw Error(cat(where, ".", key, ": must start at 0 and end at ", endDeg, " (got ",
                        deg.front(), " .. ", deg.back(), ")"));
    std::vector<double> rad(deg.size());
    for (std::size_t k = 0; k < deg.size(); ++k)
        rad[k] = k == 0 ? 0.0 : k + 1 == deg.size() ? endRad : deg[k] * kRadPerDeg;
    return rad;
}

}  // namespace

Goniogram tableSky(const std::vector<double>& zenithDeg, const std::vector<double>& azimuthDeg,
                   const std::vector<std::vector<double>>& luminance, const std::string& where)
{
    std::vector<double> th = tableAxis(zenithDeg, 90.0, kHalfPi, "zenith_deg", where);
    std::vector<double> ph = tableAxis(azimuthDeg, 360.0, kTwoPi, "azimuth_deg", where);
    if (luminance.size() != th.size())
        throw Error(cat(where, ".luminance: has ", luminance.size(), " rows, expected ", th.size(),
                        " (one per zenith_deg value)"));
    std::vector<double> v;
    v.reserve(th.size() * ph.size());
    for (std::size_t i = 0; i < luminance.size(); ++i) {
        const std::vector<double>& row = luminance[i];
        if (row.size() != ph.size())
            throw Error(cat(where, ".luminance[", i, "]: has ", row.size(), " values, expected ",
                            ph.size(), " (one per azimuth_deg value)"));
        for (std::size_t j = 0; j < row.size(); ++j) {
            if (!std::isfinite(row[j]))
                throw Error(cat(where, ".luminance[", i, "][", j, "]: not finite (", row[j], ")"));
            if (row[j] < 0)
                throw Error(
                    cat(where, ".luminance[", i, "][", j, "]: negative luminance ", row[j]));
        }
        if (row.front() != row.back())
            throw Error(cat(where, ".luminance[", i,
                            "]: azimuth 0 and 360 are the same direction, but ", "luminance[", i,
                            "][0] = ", row.front(), " and luminance[", i, "][", row.size() - 1,
                            "] = ", row.back()));
        if (i == 0)
            for (std::size_t j = 1; j < row.size(); ++j)
                if (row[j] != row[0])
                    throw Error(cat(
                        where,
                        ".luminance[0]: zenith 0 is one direction, so the row must be constant, "
                        "but luminance[0][",
                        j, "] = ", row[j], " and luminance[0][0] = ", row[0]));
        v.insert(v.end(), row.begin(), row.end());
    }
    const Goniogram table(std::move(th), std::move(ph), std::move(v), where);
    return table.refined(kRadPerDeg, std::numeric_limits<double>::infinity());
}

}  // namespace fen
