// render_cmd.h — options of `fenestra render` (host/main.cpp parses them, render_cmd.cpp runs).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sky/sky_sun_options.h"

namespace fen {

struct RenderOptions {
    static constexpr int kUnset = std::numeric_limits<int>::min();
    std::string scenePath;
    std::string outPath;            // PATH.exr; PATH.png and PATH.json are written beside it
    std::uint64_t paths = 0;        // --paths
    double timeSeconds = 0.0;       // --time
    int width = 0, height = 0;      // 0 = from the camera (camera_setup.h)
    std::string camera;
    std::uint32_t seed = 1;
    std::string device;
    int maxBounces = 1024;
    std::string roi;                // "x0,y0,x1,y1"
    std::vector<std::string> regions;  // --region NAME=x0,y0,x1,y1, repeatable
    std::string referencePath;
    // adaptive: unbiased without marking, and the most efficient on every shipped scene
    // (README "Which method when", docs/results/).
    std::string method = "adaptive";
    std::string portals;            // --portals NAME,NAME
    std::string portalOverlap = "reject";
    double portalComplement = -1.0; // -1: the default of EmissionSettings
    std::string base = "uniform";   // --base (adaptive)
    std::string adaptiveEstimate;   // --adaptive-estimate pooled|squares
    int adaptiveInitialDepth = -1;  // -1: the default of AdaptiveOptions (emission/strategy.h)
    int adaptiveMaxDepth = -1;
    int adaptiveInitialSkyDepth = -1;
    int adaptiveMaxSkyDepth = -1;
    double adaptiveDefensive = -1.0;
    double adaptiveDiskShare = -1.0;
    double adaptiveSplit = -1.0;
    std::uint64_t adaptiveFirstPass = 0;
    std::uint32_t adaptiveMaxCells = 0;
    double adaptivePrior = -1.0;
    std::string adaptiveWeights;    // --adaptive-weights predicted|equal
    std::string adaptiveTarget;     // --adaptive-target relative|absolute
    std::string adaptiveGuide;      // --adaptive-guide on|off
    double adaptiveGuideShare = -1.0;
    int adaptiveGuideVoxels = -1;
    int bvhWidth = 0;
    int batches = 16;
    int cameraSpp = 1;
    std::uint32_t poolSize = 0;
    double exposure = 0.0;          // PNG preview; 0 = automatic
    std::string kernels;            // --kernels wavefront|fused; empty: the device's default
    int rouletteDepth = -1;         // -1: the method's, defaultRouletteDepth()
    int split = kUnset;             // unset: the default of RenderSettings (splitMax)
    double splitWeight = std::numeric_limits<double>::quiet_NaN();  // NaN: RenderSettings' default
    int progress = -1;              // -1: when stderr is a terminal; 0 off; 1 on
    std::string checkpointPath;     // --checkpoint
    std::string checkpointEvery = "10min";  // --checkpoint-every: N min | N s | N batches
    std::string resumePath;         // --resume
    SkySunOptions skySun;           // --sky, --sun, ... (sky/sky_sun_options.h)
};

// Returns the exit status: 0, or 130 when a signal stopped the render early (its outputs are
// written, for the batches finished).
int runRender(const RenderOptions& opt);

struct EmissionSettings;
// The emission settings the options ask for; errors name the option.
EmissionSettings emissionSettings(const RenderOptions& opt);

}  // namespace fen
