// fuzz_weather.cpp — libFuzzer entry: any bytes as an EPW weather file, through the reader
// (io/weather_file.h) and, for its first records, the hour's sun and Perez sky
// (sky/weather_sky.h, sky/perez_sky.h: the condition, the coefficients, the tabulated sky).
//
// Acceptable outcomes: a file and skies, or a one-line fen::Error; anything else (a crash, a hang,
// a sanitizer report, another exception, a NaN in a sky's table) is a finding.
// Usage: scripts/fuzz.sh --target weather.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/weather_file.h"
#include "sky/perez_sky.h"
#include "sky/weather_sky.h"
#include "fuzz_checks.h"
#include "util/error.h"

using fen::fuzz::requireOneLine;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        const fen::WeatherFile w =
            fen::readWeatherText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.epw");
        for (std::size_t i = 0; i < w.records.size() && i < 3; ++i) {
            try {
                const fen::HourSky h = fen::hourSky(w, w.records[i], "--weather");
                const fen::Goniogram g = fen::perezSky(h.condition, h.diffuseHorizontal_lux, h.sunAltitudeDeg,
                                                       h.sunAzimuthDeg, "--weather");
                for (const double v : g.values())
                    if (!std::isfinite(v) || v < 0.0)
                        __builtin_trap();
                if (!std::isfinite(h.sunNormal_lux) || h.sunNormal_lux < 0.0)
                    __builtin_trap();
            } catch (const fen::Error& e) {
                requireOneLine(e.what());
            }
        }
    } catch (const fen::Error& e) {
        requireOneLine(e.what());
    }
    return 0;
}
