// render_cmd.h — options of `fenestra render` (host/main.cpp registers them, the emission options
// through emission/emission_options.h; render_cmd.cpp runs the render).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "emission/emission_options.h"
#include "sky/sky_sun_options.h"

namespace fen {

struct RenderOptions {
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
    EmissionOptions emission;       // --method, --portals and every strategy's own options
    int bvhWidth = 0;
    int batches = 16;
    int cameraSpp = 1;
    std::uint32_t poolSize = 0;
    double exposure = 0.0;          // PNG preview; 0 = automatic
    std::string kernels;            // --kernels wavefront|fused; empty: the device's default
    std::optional<int> rouletteDepth;   // not given: the method's (defaultRouletteDepth())
    std::optional<int> split;           // not given: RenderSettings' splitMax
    std::optional<double> splitWeight;  // not given: RenderSettings' splitWeight
    std::optional<bool> progress;       // not given: when stderr is a terminal
    std::string checkpointPath;     // --checkpoint
    std::string checkpointEvery = "10min";  // --checkpoint-every: N min | N s | N batches
    std::string resumePath;         // --resume
    SkySunOptions skySun;           // --sky, --sun, ... (sky/sky_sun_options.h)
};

// Returns the exit status: 0, or 130 when a signal stopped the render early (its outputs are
// written, for the batches finished).
int runRender(const RenderOptions& opt);

}  // namespace fen
