// renderer.h — the light-tracing render loop (DESIGN.md §2, §4, §5).
//
// A pool of path slots on the device; per iteration emit -> intersect -> shade -> connect
// (kernels/*.cl), until the batch's paths are all emitted and dead. Paths are rendered in B
// equal, independent batches: each batch's pixels are accumulated in 128-bit fixed point (bit-
// identical for a given seed and device), converted on the host, and folded into a running sum
// and sum of squares, so every pixel carries its own standard error without a reference.
// The camera pass adds the sky seen directly once per batch. With a time budget, a short
// calibration batch (not counted) sizes the batches so that about B of them fill the time.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cl/context.h"
#include "io/image.h"
#include "emission/portal_emission.h"
#include "render/device_scene.h"
#include "render/emission_setup.h"
#include "render/image_stats.h"
#include "scene/scene.h"
#include "sky/goniogram.h"

namespace fen {

enum class EmissionMethod { Uniform, Portal };
EmissionMethod parseEmissionMethod(const std::string& s);  // uniform | portal

struct RenderSettings {
    EmissionMethod method = EmissionMethod::Uniform;
    std::string portals;         // --portals: node names replacing the scene's marking
    PortalOverlap overlap = PortalOverlap::Reject;
    std::uint64_t paths = 0;     // total light paths; 0 = use timeSeconds
    double timeSeconds = 0.0;
    int batches = 16;            // independent batches (>= 2): the noise estimate's sample size
    int cameraSpp = 1;           // camera-pass samples per pixel, per batch
    std::uint32_t seed = 1;
    int maxBounces = 64;         // surface interactions a path may have (bias beyond: reported)
    int bvhWidth = 0;            // 0 = the device's default layout
    std::uint32_t poolSize = 0;  // path slots; 0 = automatic
    bool progress = false;       // progress line on stderr
    std::vector<Roi> rois;       // regions whose mean luminance is tracked batch by batch
};

struct RenderResult {
    Image image;                         // mean of the batches: radiance, cd/m^2 (RGB)
    std::vector<double> stdErrLuminance; // per pixel: standard error of the luminance (cd/m^2)
    std::uint64_t paths = 0, pathsPerBatch = 0;
    int batches = 0;
    std::uint64_t extensionRays = 0, shadowRays = 0, cameraRays = 0;
    std::uint64_t badContributions = 0, overflows = 0, maxBounceCuts = 0, cameraGlassCuts = 0;
    double renderSeconds = 0.0;       // the counted batches
    double calibrationSeconds = 0.0;  // --time only: the uncounted first batch
    double bvhSeconds = 0.0, kernelBuildSeconds = 0.0;
    int bvhWidth = 0;
    std::uint32_t poolSize = 0;
    EmissionSetup emission;
    EmissionMethod method = EmissionMethod::Uniform;
    // portal strategy: the portal nodes, triangles, plane groups, flux through them, precompute
    std::vector<std::string> portalNodes;
    std::size_t portalTriangles = 0, portalGroups = 0;
    double portalSunFlux_lm = 0.0, portalSkyFlux_lm = 0.0, portalPrecomputeSeconds = 0.0;
    std::map<std::string, ocl::KernelStats::Entry> kernels;
    // roiBatchMeans[k][b]: mean luminance of settings.rois[k] in batch b. Batches are independent,
    // so their spread gives the ROI mean's standard error (pixels within a batch are not).
    std::vector<std::vector<double>> roiBatchMeans;
    double roiMean(std::size_t k) const;
    double roiMeanStdErr(std::size_t k) const;
};

class Renderer {
public:
    Renderer(ocl::Context& ctx, const Scene& scene, const std::optional<Goniogram>& sky,
             const CameraSpec& camera, int width, int height, const RenderSettings& settings);
    ~Renderer();
    RenderResult render();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fen
