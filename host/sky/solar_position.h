// solar_position.h — where the sun is, seen from a place on Earth at a moment (DESIGN.md §1, "Sun
// and sky from the command line"): NOAA's solar position algorithm (the equations of NOAA's Solar
// Calculator, after J. Meeus, "Astronomical Algorithms", 1991: the sun's apparent longitude, the
// obliquity and the declination from the Julian century), with two refinements that bring it
// within 0.01 degrees of SPA -- the hour angle from the right ascension and the apparent sidereal
// time (Meeus 12.4) instead of NOAA's equation-of-time series, and the topocentric parallax
// (8.794 arc seconds times the cosine of the altitude) -- and the atmospheric refraction NOAA's
// calculator applies. NOAA's own sheet was 0.014 degrees off at worst on the table below.
//
// Checked against NREL's SPA (Reda and Andreas 2004, as pvlib implements it) on 400 places and
// moments, 1990-2060, latitudes -66..66 (tests/data/solar_position_pvlib.csv, made by
// scripts/solar_reference.py): see tests/host/solar_position_test.cpp for the bound asserted.
// Time is UTC (UT1 taken equal to UTC: at most 0.9 s, 0.004 degrees of hour angle).
#pragma once

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace fen {

// A moment as written: civil date and time with the UTC offset it was given in.
struct LocalTime {
    int year = 2000, month = 1, day = 1, hour = 0, minute = 0;
    double second = 0.0;
    int utcOffsetMinutes = 0;  // +02:00 -> 120
};

// Parses ISO 8601 "YYYY-MM-DDTHH:MM[:SS[.s]](Z|+HH:MM|-HH:MM)"; the offset is required (a moment
// without one names no moment). Throws fen::Error naming `option` and the value.
LocalTime parseLocalTime(const std::string& text, const std::string& option);

// Julian date (UT) of a moment.
double julianDate(const LocalTime& t);

struct SolarPosition {
    double altitudeDeg = 0.0;          // above the horizon, without refraction
    double apparentAltitudeDeg = 0.0;  // with NOAA's refraction (standard atmosphere)
    double azimuthDeg = 0.0;           // from north towards east, [0, 360)
    double declinationDeg = 0.0;
    double equationOfTimeMin = 0.0;
};

// latitudeDeg in [-90, 90] (north positive), longitudeDeg in [-180, 180] (east positive).
SolarPosition solarPosition(double latitudeDeg, double longitudeDeg, const LocalTime& t);

// The unit direction towards a sky point at altitude and azimuth (degrees) in fenestra's frame:
// +x east, +y up, -z north (the sky's own skyDirection, sky/goniogram.h, in degrees of altitude);
// and back, the azimuth in [0, 360).
glm::dvec3 directionFromAltitudeAzimuth(double altitudeDeg, double azimuthDeg);
void altitudeAzimuthOf(const glm::dvec3& towards, double* altitudeDeg, double* azimuthDeg);

}  // namespace fen
