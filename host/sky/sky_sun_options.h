// sky_sun_options.h — the sky and the sun from the command line (DESIGN.md §1, "Sun and sky from
// the command line"): a scene exported from Blender has no sky (glTF cannot carry Blender's World)
// and its sun's strength in the wrong unit, so `fenestra render` can supply or override both:
//   --sky cie:N | uniform | none      the sky (CIE standard general sky type 1..15)
//   --sky-zenith L | --sky-lux E       its zenith luminance (cd/m²) or its horizontal illuminance (lux)
//   --sun ALT,AZ | none                the sun's position (degrees; azimuth from north towards east)
//   --site LAT,LON --sun-at TIME       ... or from a place and a moment (solar_position.h)
//   --sun-lux E                        the sun's normal illuminance (lux)
//   --ground-albedo A                  the ground's albedo, 0..1: its glow below the horizon (0: off)
//   --weather F.epw --weather-hour MM-DD:HH   the sun and a Perez sky of one hour of a weather file
//                                      (weather_sky.h); replaces all of the above but the ground
// Invariants: whatever is given replaces what the file says, and nothing else changes; a CIE sky
// always takes its sun position from the sun used (given or the file's); every inconsistency is a
// one-line fen::Error naming the option before anything is rendered.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace CLI {
class App;
}

namespace fen {

struct SkySunOptions {
    std::optional<std::string> sky;        // --sky
    std::optional<double> skyZenith_cd_m2; // --sky-zenith
    std::optional<double> skyLux;          // --sky-lux
    std::optional<std::string> sun;        // --sun ALT,AZ | none
    std::optional<double> sunLux;          // --sun-lux
    std::optional<std::string> site;       // --site LAT,LON
    std::optional<std::string> sunAt;      // --sun-at
    std::optional<double> groundAlbedo;    // --ground-albedo
    std::optional<std::string> weather;    // --weather FILE.epw
    std::optional<std::string> weatherHour; // --weather-hour MM-DD:HH
};

// Registers the options above on `render` (the `fenestra render` subcommand).
void addSkySunOptions(CLI::App* render, SkySunOptions* options);

// What the sky and sun of a render are, for the JSON output and the messages.
struct SkySunReport {
    std::vector<std::string> warnings;
};

// Applies the options to `scene` (sky and sun). Returns warnings for the user: a scene left with no
// sky; a sun brighter than any on Earth (Blender's exporter writes W/m² x 683 as lux).
SkySunReport applySkySunOptions(const SkySunOptions& options, Scene* scene);

// Horizontal illuminance (lux) of a CIE sky of `type` with unit zenith luminance, the sun at
// (altitude, azimuth) degrees: the factor between --sky-lux and --sky-zenith.
double cieHorizontalIlluminancePerZenith(int type, double sunAltitudeDeg, double sunAzimuthDeg);

}  // namespace fen
