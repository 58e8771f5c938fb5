// solar_position.cpp — NOAA's solar position algorithm (solar_position.h).
#include "sky/solar_position.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sky/goniogram.h"
#include "util/error.h"

namespace fen {

namespace {

constexpr double kDeg = M_PI / 180.0;

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
std::int64_t daysFromCivil(std::int64_t y, unsigned m, unsigned d)
{
    y -= m <= 2;
    const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
    const unsigned yoe = static_cast<unsigned>(y - era * 400);
    const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

bool leapYear(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

double wrap360(double a)
{
    a = std::fmod(a, 360.0);
    return a < 0.0 ? a + 360.0 : a;
}

// NOAA's refraction correction (degrees) for a geometric elevation (degrees).
double refractionDeg(double e)
{
    double arcsec = 0.0;
    if (e > 85.0)
        arcsec = 0.0;
    else if (e > 5.0) {
        const double t = std::tan(e * kDeg);
        arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5.0);
    } else if (e > -0.575)
        arcsec = 1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)));
    else
        arcsec = -20.772 / std::tan(e * kDeg);
    return arcsec / 3600.0;
}

}  // namespace

LocalTime parseLocalTime(const std::string& text, const std::string& option)
{
    const auto bad = [&](const std::string& why) {
        return Error(cat(option, " '", printable(text, 60), "': ", why,
                         " (expected YYYY-MM-DDTHH:MM[:SS] and a UTC offset, e.g. 2026-06-21T14:00+02:00 or ...Z)"));
    };
    LocalTime t;
    int n = 0;
    if (std::sscanf(text.c_str(), "%4d-%2d-%2d%n", &t.year, &t.month, &t.day, &n) != 3 || n != 10 ||
        text.size() < 16 || (text[10] != 'T' && text[10] != ' '))
        throw bad("not a date and time");
    std::size_t p = 11;
    auto digits = [&](std::size_t at, int count, int* out) {
        if (at + static_cast<std::size_t>(count) > text.size())
            return false;
        int v = 0;
        for (int k = 0; k < count; ++k) {
            const char c = text[at + static_cast<std::size_t>(k)];
            if (c < '0' || c > '9')
                return false;
            v = v * 10 + (c - '0');
        }
        *out = v;
        return true;
    };
    if (!digits(p, 2, &t.hour) || text[p + 2] != ':' || !digits(p + 3, 2, &t.minute))
        throw bad("not a time of day");
    p += 5;
    if (p < text.size() && text[p] == ':') {
        int s = 0;
        if (!digits(p + 1, 2, &s))
            throw bad("not a time of day");
        t.second = s;
        p += 3;
        if (p < text.size() && text[p] == '.') {
            double frac = 0.0, scale = 0.1;
            ++p;
            const std::size_t start = p;
            while (p < text.size() && text[p] >= '0' && text[p] <= '9') {
                frac += (text[p] - '0') * scale;
                scale /= 10.0;
                ++p;
            }
            if (p == start)
                throw bad("not a time of day");
            t.second += frac;
        }
    }
    if (p >= text.size())
        throw bad("no UTC offset");
    if (text[p] == 'Z' && p + 1 == text.size()) {
        t.utcOffsetMinutes = 0;
    } else if ((text[p] == '+' || text[p] == '-') && p + 6 == text.size() && text[p + 3] == ':') {
        int oh = 0, om = 0;
        if (!digits(p + 1, 2, &oh) || !digits(p + 4, 2, &om) || oh > 14 || om > 59)
            throw bad("not a UTC offset");
        t.utcOffsetMinutes = (text[p] == '-' ? -1 : 1) * (oh * 60 + om);
    } else {
        throw bad("no UTC offset");
    }
    static const int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (t.year < 1 || t.month < 1 || t.month > 12 || t.day < 1 ||
        t.day > days[t.month - 1] + (t.month == 2 && leapYear(t.year)))
        throw bad("no such date");
    if (t.hour > 24 || t.minute > 59 || t.second >= 61.0 || (t.hour == 24 && (t.minute > 0 || t.second > 0.0)))
        throw bad("no such time of day");
    if (t.year < 1800 || t.year > 2200)
        throw bad("the algorithm is for the years 1800 to 2200");
    return t;
}

double julianDate(const LocalTime& t)
{
    const double days = static_cast<double>(daysFromCivil(t.year, static_cast<unsigned>(t.month),
                                                          static_cast<unsigned>(t.day)));
    const double seconds = t.hour * 3600.0 + t.minute * 60.0 + t.second - t.utcOffsetMinutes * 60.0;
    return 2440587.5 + days + seconds / 86400.0;
}

SolarPosition solarPosition(double latitudeDeg, double longitudeDeg, const LocalTime& t)
{
    if (!(latitudeDeg >= -90.0 && latitudeDeg <= 90.0) || !(longitudeDeg >= -180.0 && longitudeDeg <= 180.0))
        throw Error(cat("latitude ", latitudeDeg, ", longitude ", longitudeDeg,
                        ": must be in [-90, 90] and [-180, 180] degrees"));
    const double jd = julianDate(t);
    const double jc = (jd - 2451545.0) / 36525.0;  // Julian centuries since J2000.0
    const double l0 = wrap360(280.46646 + jc * (36000.76983 + jc * 0.0003032));  // mean longitude
    const double m = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);           // mean anomaly
    const double e = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);      // eccentricity
    const double c = std::sin(m * kDeg) * (1.914602 - jc * (0.004817 + 0.000014 * jc)) +
                     std::sin(2.0 * m * kDeg) * (0.019993 - 0.000101 * jc) + std::sin(3.0 * m * kDeg) * 0.000289;
    const double omega = 125.04 - 1934.136 * jc;
    const double lambda = l0 + c - 0.00569 - 0.00478 * std::sin(omega * kDeg);  // apparent longitude
    const double eps0 = 23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
    const double eps = eps0 + 0.00256 * std::cos(omega * kDeg);                   // obliquity, corrected
    const double decl = std::asin(std::sin(eps * kDeg) * std::sin(lambda * kDeg));
    // The hour angle from the right ascension and the apparent sidereal time (Meeus 12.4 and the
    // nutation in right ascension), not from the equation-of-time series NOAA's sheet uses.
    const double alpha = std::atan2(std::cos(eps * kDeg) * std::sin(lambda * kDeg), std::cos(lambda * kDeg)) / kDeg;
    const double d = jd - 2451545.0;
    const double gmst = 280.46061837 + 360.98564736629 * d + jc * jc * (0.000387933 - jc / 38710000.0);
    const double gast = gmst - 0.00478 * std::sin(omega * kDeg) * std::cos(eps * kDeg);
    const double y = std::pow(std::tan(eps * kDeg / 2.0), 2.0);
    const double l0r = l0 * kDeg, mr = m * kDeg;
    const double eot = 4.0 / kDeg *
                       (y * std::sin(2.0 * l0r) - 2.0 * e * std::sin(mr) + 4.0 * e * y * std::sin(mr) * std::cos(2.0 * l0r) -
                        0.5 * y * y * std::sin(4.0 * l0r) - 1.25 * e * e * std::sin(2.0 * mr));
    double hourAngle = std::fmod(gast + longitudeDeg - alpha, 360.0);  // (-180, 180]: afternoon positive
    if (hourAngle > 180.0)
        hourAngle -= 360.0;
    if (hourAngle <= -180.0)
        hourAngle += 360.0;
    const double lat = latitudeDeg * kDeg;
    const double cosZ = std::clamp(std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(hourAngle * kDeg),
                                   -1.0, 1.0);
    const double zenith = std::acos(cosZ);
    // Topocentric: seen from the Earth's surface, not its centre, the sun stands lower by its
    // horizontal parallax (8.794 arc seconds at 1 AU) times the cosine of its altitude; its
    // azimuth does not change (to first order), so the azimuth below uses the geocentric zenith.
    const double topoZenith = zenith + 8.794 / 3600.0 * kDeg * std::sin(zenith);
    SolarPosition s;
    s.altitudeDeg = 90.0 - topoZenith / kDeg;
    s.apparentAltitudeDeg = s.altitudeDeg + refractionDeg(s.altitudeDeg);
    s.declinationDeg = decl / kDeg;
    s.equationOfTimeMin = eot;
    // Azimuth from north towards east, from the hour angle's sign (afternoon: west of south).
    const double denom = std::cos(lat) * std::sin(zenith);
    double az = 0.0;
    if (std::abs(denom) > 1e-12) {
        const double a = std::acos(std::clamp((std::sin(lat) * cosZ - std::sin(decl)) / denom, -1.0, 1.0)) / kDeg;
        az = hourAngle > 0.0 ? wrap360(a + 180.0) : wrap360(540.0 - a);
    } else {
        az = latitudeDeg > 0.0 ? 180.0 : 0.0;  // at a pole or the sun at the zenith: undefined; take south/north
    }
    s.azimuthDeg = az;
    return s;
}

glm::dvec3 directionFromAltitudeAzimuth(double altitudeDeg, double azimuthDeg)
{
    return skyDirection((90.0 - altitudeDeg) * kDeg, azimuthDeg * kDeg);
}

void altitudeAzimuthOf(const glm::dvec3& towards, double* altitudeDeg, double* azimuthDeg)
{
    double theta = 0.0, phi = 0.0;
    skyAngles(towards, &theta, &phi);
    *altitudeDeg = 90.0 - theta / kDeg;
    *azimuthDeg = phi / kDeg;
}

}  // namespace fen
