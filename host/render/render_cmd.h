// render_cmd.h — options of `fenestra render` (host/main.cpp parses them, render_cmd.cpp runs).
#pragma once

#include <cstdint>
#include <string>

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
    int maxBounces = 64;
    std::string roi;                // "x0,y0,x1,y1"
    std::string referencePath;
    std::string method = "uniform";
    std::string portals;            // --portals NAME,NAME
    std::string portalOverlap = "reject";
    int bvhWidth = 0;
    int batches = 16;
    int cameraSpp = 1;
    std::uint32_t poolSize = 0;
    double exposure = 0.0;          // PNG preview; 0 = automatic
    int progress = -1;              // -1: when stderr is a terminal; 0 off; 1 on
};

int runRender(const RenderOptions& opt);

}  // namespace fen
