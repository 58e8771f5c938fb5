// render_options.h — the options of `fenestra render` (DESIGN.md §5): their typed values, each with
// an explicit "not given" (std::optional: no value doubles as "unset"), registered on the render
// subcommand by addRenderOptions() and checked against their documented ranges by
// validateRenderOptions() before anything is loaded or rendered -- a value out of range is a
// one-line fen::Error naming the option, the value and the range. The emission strategies' own
// options live in their blocks (emission/emission_options.h), the sky and sun's in
// sky/sky_sun_options.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "annual/annual_options.h"
#include "emission/emission_options.h"
#include "sensor/sensor_options.h"
#include "sky/sky_sun_options.h"

namespace CLI {
class App;
}

namespace fen {

// Path indices carry a split branch in their top byte (kernels/lib/shade_path.h): 2^56 paths is
// the most one render can number.
constexpr std::int64_t kMaxRenderPaths = std::int64_t{1} << 56;
constexpr double kMaxRenderSeconds = 365.0 * 24 * 3600;

struct RenderOptions {
    std::string scenePath;
    std::string outPath;                   // PATH.exr; PATH.png and PATH.json are written beside it
    std::optional<std::string> pathsText;  // --paths as typed: 1000000, 2e9 (parsed by validateRenderOptions)
    std::optional<std::int64_t> paths;     // its value
    std::optional<double> timeSeconds;     // --time
    std::optional<int> width, height;      // not given: from the camera (camera_setup.h)
    std::string camera;
    std::optional<std::int64_t> seed;      // not given: 1
    std::string device;
    std::optional<int> maxBounces;         // not given: 1024
    std::optional<std::string> roi;        // "x0,y0,x1,y1"; not given: the whole image
    std::vector<std::string> regions;      // --region NAME=x0,y0,x1,y1, repeatable
    std::optional<std::string> referencePath;
    EmissionOptions emission;              // --method, --portals and every strategy's own options
    std::optional<std::string> layout;     // --layout bvh2|bvh4|bvh8; not given: the device's
    int bvhWidth = 0;                      // from --layout (validateRenderOptions); 0: the device's
    std::optional<int> batches;            // not given: 16
    std::optional<int> cameraSpp;          // not given: 1
    std::optional<std::string> cameraPass; // --camera-pass balanced|fixed; not given: balanced
    std::optional<std::int64_t> poolSize;  // not given: the device's
    std::optional<double> exposure;        // not given: the ROI's mean to mid-grey
    std::optional<std::string> kernels;    // --kernels wavefront|fused; not given: the device's
    std::optional<int> rouletteDepth;      // not given: the method's (strategy_registry.h)
    std::optional<int> split;              // not given: RenderSettings' splitMax
    std::optional<double> splitWeight;     // not given: RenderSettings' splitWeight
    std::optional<bool> progress;          // not given: when stderr is a terminal
    bool progressOn = false, progressOff = false;  // the flags behind `progress`
    std::optional<std::string> checkpointPath;     // --checkpoint
    std::string checkpointEvery = "10min";         // --checkpoint-every: N min | N s | N batches
    double checkpointSeconds = 600.0;              // ... as validateRenderOptions reads it
    int checkpointBatches = 0;                     //     (batches: 0 when given in time)
    std::optional<std::string> resumePath;         // --resume
    SkySunOptions skySun;                  // --sky, --sun, ... (sky/sky_sun_options.h)
    SensorOptions sensors;                 // --sensor-points, --work-plane, --daylight-factor, ...
    AnnualOptions annual;                  // --annual FILE.epw, --sky-patches, --occupied, ...

    std::uint32_t seedValue() const { return static_cast<std::uint32_t>(seed.value_or(1)); }
    int maxBouncesValue() const { return maxBounces.value_or(1024); }
    int batchesValue() const { return batches.value_or(16); }
};

// Registers every option of `fenestra render` on `render`, writing into `o`.
void addRenderOptions(CLI::App& render, RenderOptions& o);

// Checks every given value against its range, and the combinations (--paths or --time, not both;
// --progress or --no-progress), and sets what follows from them (bvhWidth, progress). Throws
// fen::Error naming the option, the value and the range.
void validateRenderOptions(RenderOptions& o);

}  // namespace fen
