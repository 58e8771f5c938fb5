// render_options.cpp — registering and checking the options of `fenestra render` (render_options.h).
#include "render/render_options.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <CLI/CLI.hpp>

#include "emission/strategy_registry.h"
#include "trace/device_bvh.h"
#include "util/error.h"

namespace fen {

namespace {

template <class T>
void requireRange(const std::optional<T>& v, const char* option, T lo, T hi, const char* why = "")
{
    if (v && !(*v >= lo && *v <= hi))
        throw Error(cat(option, " ", *v, ": must be in ", lo, "..", hi, why));
}

void requirePositiveFinite(const std::optional<double>& v, const char* option, double hi)
{
    if (v && !(std::isfinite(*v) && *v > 0.0 && *v <= hi))
        throw Error(cat(option, " ", *v, ": must be a positive, finite number, at most ", hi));
}

void requireName(const std::optional<std::string>& v, const char* option)
{
    if (v && v->empty())
        throw Error(cat(option, " '': give a file name"));
}

}  // namespace

void addRenderOptions(CLI::App& r, RenderOptions& o)
{
    r.add_option("scene", o.scenePath, "glTF scene (.gltf or .glb)")->required();
    r.add_option("--out", o.outPath, "Output PATH.exr (PATH.png and PATH.json beside it)")->required();
    r.add_option("--paths", o.pathsText, "Light paths to trace, 1 to 2^56 (1000000, 2e9)");
    r.add_option("--time", o.timeSeconds, "Render for about this many seconds instead");
    r.add_option("--width", o.width, "Image width, 1 to 16384 (default: 640, or from --height)");
    r.add_option("--height", o.height, "Image height, 1 to 16384 (default: from the camera's aspect ratio)");
    r.add_option("--camera", o.camera, "Camera node name (or camera name); default the first");
    r.add_option("--seed", o.seed, "Random seed, 0 to 2^32 - 1 (default 1)");
    r.add_option("--device", o.device, "OpenCL device: index or name substring");
    r.add_option("--max-bounces", o.maxBounces,
                 "Surface interactions per path: a guard against endless paths, Russian roulette ends them (default 1024)");
    r.add_option("--roi", o.roi, "Region x0,y0,x1,y1 for the statistics (default: whole image)");
    r.add_option("--region", o.regions,
                 "Named region NAME=x0,y0,x1,y1 also reported in the JSON (regions.NAME); repeatable");
    r.add_option("--reference", o.referencePath, "Reference EXR: report RMSE and relative MSE");
    o.emission.add(r);  // --method, --portals and every strategy's options
    r.add_option("--layout", o.layout, "BVH layout: bvh2, bvh4 or bvh8 (default: the device's)");
    r.add_option("--batches", o.batches, "Independent batches for the noise estimate, 2 to 65536 (default 16)");
    r.add_option("--camera-spp", o.cameraSpp,
                 "Camera-pass samples per pixel per batch, for the sky seen directly, 1 to 4096: every pixel's, "
                 "or with --camera-pass balanced the least a pixel gets (default 1)");
    r.add_option("--camera-pass", o.cameraPass,
                 "How the camera pass spends its samples: balanced (each pixel in proportion to its own noise, "
                 "the total balanced against the light tracer's; default) or fixed (--camera-spp everywhere)");
    r.add_option("--kernels", o.kernels,
                 "How the stages run: fused (one kernel per path, default on a CPU) or wavefront (default on a GPU)");
    std::string rouletteDefaults;  // each strategy's own (emission/strategy_registry.h)
    for (const StrategyDescriptor* d : emissionStrategies())
        rouletteDefaults += (rouletteDefaults.empty() ? "" : ", ") + std::to_string(d->rouletteDepth) + " for " + d->name;
    r.add_option("--roulette-depth", o.rouletteDepth,
                 "Russian roulette from this surface interaction on; before it every path goes on (default " +
                     rouletteDefaults + ")");
    r.add_option("--split", o.split,
                 "At its first diffuse hit, a path weighing k >= 2 times the mean emitted weight goes on as min(k, N) "
                 "branches of 1/k the weight (1: never; default 1)");
    r.add_option("--split-weight", o.splitWeight,
                 "With --split: the weight unit k counts in, as a multiple of the mean emitted weight (default 1)");
    r.add_option("--pool", o.poolSize, "Path slots on the device (default: 2^16 CPU, 2^21 GPU)");
    r.add_option("--exposure", o.exposure, "PNG preview exposure (default: ROI mean to mid-grey)");
    r.add_option("--checkpoint", o.checkpointPath,
                 "Save the render's state to this file now and then, and when interrupted");
    r.add_option("--checkpoint-every", o.checkpointEvery, "How often: N min, N s or N batches (default 10min)");
    r.add_option("--resume", o.resumePath, "Continue the render saved in this checkpoint (same scene and options)");
    addSkySunOptions(&r, &o.skySun);
    addSensorOptions(&r, &o.sensors);
    addAnnualOptions(&r, &o.annual);
    r.add_flag("--progress", o.progressOn, "Show progress even when stderr is not a terminal");
    r.add_flag("--no-progress", o.progressOff, "Never show progress");
}

namespace {

// --checkpoint-every: "10min", "30 s", "4 batches" (units: min, m, s, batches, b).
void parseCheckpointEvery(const std::string& text, RenderOptions* s)
{
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    std::string unit = text.substr(used);
    unit.erase(0, unit.find_first_not_of(' '));
    const bool ok = used > 0 && std::isfinite(v) && v > 0.0;
    if (ok && (unit == "min" || unit == "m")) {
        s->checkpointSeconds = 60.0 * v;
    } else if (ok && unit == "s") {
        s->checkpointSeconds = v;
    } else if (ok && (unit == "batches" || unit == "b" || unit == "batch") && v == std::floor(v) && v <= 1024.0) {
        s->checkpointBatches = static_cast<int>(v);
    } else {
        throw Error(cat("--checkpoint-every '", printable(text, 40),
                        "': give a positive number and a unit: 10min, 30s or 4batches"));
    }
}

// A count as a user types it: digits, or a number in decimal or scientific notation that is a
// whole number (2e9). Anything else, and anything beyond `max`, is an error quoting the text.
std::int64_t parseCount(const std::string& text, const char* option, std::int64_t max, const char* range)
{
    const auto bad = [&] { return Error(cat(option, " ", printable(text, 40), ": must be a whole number from 1 to ", range)); };
    if (text.empty() || text.find_first_not_of("0123456789.eE+-") != std::string::npos)
        throw bad();
    std::size_t used = 0;
    long double v = 0;
    try {
        v = std::stold(text, &used);
    } catch (const std::exception&) {
        throw bad();
    }
    if (used != text.size() || !(v >= 1) || v != std::floor(v) || v > static_cast<long double>(max))
        throw bad();
    return static_cast<std::int64_t>(v);
}

}  // namespace

void validateRenderOptions(RenderOptions& o)
{
    parseCheckpointEvery(o.checkpointEvery, &o);
    validateAnnualOptions(o.annual, o.skySun, o.sensors);
    validateSensorOptions(o.sensors, o.skySun);
    if (o.sensors.noImage) {
        // Nothing of the image's: a render for its sensors alone.
        const char* imageOption = o.width ? "--width" : o.height ? "--height" : o.roi ? "--roi" : !o.regions.empty() ? "--region"
                                  : o.referencePath ? "--reference" : o.exposure ? "--exposure" : !o.camera.empty() ? "--camera"
                                  : o.cameraSpp ? "--camera-spp" : o.cameraPass ? "--camera-pass" : nullptr;
        if (imageOption)
            throw Error(cat(imageOption, " is about the image, and --no-image renders none"));
    }
    if (o.pathsText)
        o.paths = parseCount(*o.pathsText, "--paths", kMaxRenderPaths, "2^56 (72057594037927936, the most a render can number)");
    if (o.paths && o.timeSeconds)
        throw Error("give either --paths or --time, not both");
    if (!o.paths && !o.timeSeconds)
        throw Error("give --paths (light paths to trace) or --time (seconds to render)");
    requirePositiveFinite(o.timeSeconds, "--time", kMaxRenderSeconds);
    requireRange(o.width, "--width", 1, 16384);
    requireRange(o.height, "--height", 1, 16384);
    requireRange(o.seed, "--seed", std::int64_t{0}, std::int64_t{0xFFFFFFFF});
    requireRange(o.maxBounces, "--max-bounces", 1, 1 << 20);
    requireRange(o.batches, "--batches", 2, 65536, " (the noise estimate needs two)");
    requireRange(o.cameraSpp, "--camera-spp", 1, 4096);
    requireRange(o.poolSize, "--pool", std::int64_t{1}, std::int64_t{1} << 26);
    requirePositiveFinite(o.exposure, "--exposure", 1e30);
    // The renderer's own bound (renderer.cpp), and no deeper than a path may go.
    requireRange(o.rouletteDepth, "--roulette-depth", 0, std::min(64, o.maxBouncesValue()),
                 " (at most 64, and at most --max-bounces)");
    requireRange(o.split, "--split", 1, 1024);
    requireRange(o.skySun.groundAlbedo, "--ground-albedo", 0.0, 1.0, " (0: no ground glow)");
    if (o.splitWeight && !(std::isfinite(*o.splitWeight) && *o.splitWeight > 0.0))
        throw Error(cat("--split-weight ", *o.splitWeight, ": must be a positive, finite multiple of the mean weight"));
    requireName(o.checkpointPath, "--checkpoint");
    requireName(o.resumePath, "--resume");
    requireName(o.referencePath, "--reference");
    if (o.cameraPass && *o.cameraPass != "balanced" && *o.cameraPass != "fixed")
        throw Error(cat("--camera-pass '", printable(*o.cameraPass, 40), "': must be balanced or fixed"));
    if (o.kernels && *o.kernels != "fused" && *o.kernels != "wavefront")
        throw Error(cat("--kernels '", printable(*o.kernels, 40), "': must be fused or wavefront"));
    if (o.progressOn && o.progressOff)
        throw Error("give --progress or --no-progress, not both");
    if (o.progressOn || o.progressOff)
        o.progress = o.progressOn;
    if (o.layout) {
        o.bvhWidth = bvhLayoutWidth(*o.layout);
        if (o.bvhWidth == 0)
            throw Error(cat("--layout '", printable(*o.layout, 40), "': takes one of bvh2, bvh4, bvh8"));
    }
}

}  // namespace fen
