// annual_options.h — the annual-study options of `fenestra render` (DESIGN.md §8 "Annual daylight"):
//   --annual FILE.epw         an annual study: daylight coefficients of the sensors, then the
//                             weather file's occupied hours through them (annual_study.h)
//   --sky-patches MF          the coefficients' Reinhart subdivision (default 1: 145 patches + ground)
//   --occupied FROM-TO        occupied hours, the weather file's standard time (default 8-18)
//   --da-lux LUX              daylight autonomy's threshold (default 300)
//   --sda-share PCT           the DA a cell needs to count towards sDA (default 50)
//   --ase-lux LUX, --ase-hours H   annual sunlight exposure's thresholds (default 1000 lux, 250 h)
//   --udi LOW,HIGH            useful daylight illuminance's band (default 100,2000 lux)
//   --annual-learning year|unit   what adaptive emission learns the coefficients for: the year's
//                             mean sky (default), or the unit sky (coefficients to reuse with other
//                             weather: no patch favoured)
//   --annual-sun exact|patch  the sun's direct light at its own position hour by hour (default: the
//                             five-phase method, annual/direct_sun.h), or in its patch (two-phase)
//   --annual-sun-points N     exact: N x N jittered points a cell and hour (default 4)
// An annual study renders the sensors alone under a sky of 1 cd/m^2 everywhere (the ground too) and
// no sun; so it takes no sky, sun, weather hour or daylight-factor option.
// --ground-albedo sets the ground's reflectance in the hours' skies (default 0.2, as Radiance's
// gendaymtx). Checked before anything is loaded.
#pragma once

#include <optional>
#include <string>

#include "annual/annual_study.h"
#include "sensor/sensor_options.h"
#include "sky/sky_sun_options.h"

namespace CLI {
class App;
}

namespace fen {

struct AnnualOptions {
    std::optional<std::string> weather;  // --annual
    std::optional<int> mf;
    std::optional<std::string> occupied;
    std::optional<double> daLux, sdaShare, aseLux, aseHours;
    std::optional<std::string> udi;
    std::optional<std::string> learning;
    std::optional<std::string> sun;
    std::optional<int> sunPoints;
    AnnualSettings settings;             // from the above (validateAnnualOptions)
};

void addAnnualOptions(CLI::App* render, AnnualOptions* options);

// Checks ranges and combinations (naming the option), fills `settings`, and for --annual sets
// --no-image.
void validateAnnualOptions(AnnualOptions& options, const SkySunOptions& skySun, SensorOptions& sensors);

}  // namespace fen
