// render_cmd.cpp — `fenestra render`: scene in, EXR + PNG preview + JSON statistics out
// (DESIGN.md §5). Every JSON key is documented in README.md ("Render output").
#include "render/render_cmd.h"

#include <chrono>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cl/device.h"
#include "io/exr_io.h"
#include "io/png_preview.h"
#include "render/camera_setup.h"
#include "render/image_stats.h"
#include "emission/adaptive_strategy.h"
#include "render/renderer.h"
#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "util/error.h"

namespace fen {

namespace {

std::string withExtension(const std::string& exrPath, const std::string& ext)
{
    return exrPath.substr(0, exrPath.size() - 4) + ext;
}

// Creates the output's folder and proves it writable before a long render, not after it.
void prepareOutput(const std::string& exrPath)
{
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(exrPath).parent_path();
    std::error_code ec;
    if (!dir.empty())
        fs::create_directories(dir, ec);
    if (ec)
        throw Error(cat("--out ", exrPath, ": cannot create folder ", dir.string(), ": ", ec.message()));
    const std::string probe = exrPath + ".writable";
    {
        std::ofstream f(probe);
        if (!f)
            throw Error(cat("--out ", exrPath, ": cannot write there"));
    }
    fs::remove(probe, ec);
}

}  // namespace

EmissionSettings emissionSettings(const RenderOptions& opt)
{
    EmissionSettings e;
    e.method = parseEmissionMethod(opt.method);
    e.overlap = parsePortalOverlap(opt.portalOverlap);
    e.portals = opt.portals;
    AdaptiveOptions& a = e.adaptive;
    a.base = parseEmissionMethod(opt.base);
    const bool adaptive = e.method == EmissionMethod::Adaptive;
    const bool portalsUsed = e.method == EmissionMethod::Portal || (adaptive && a.base == EmissionMethod::Portal);
    if (!opt.portals.empty() && !portalsUsed)
        throw Error("--portals applies to --method portal and to --method adaptive --base portal");
    if (opt.base != "uniform" && !adaptive)
        throw Error("--base applies to --method adaptive");
    if (a.base == EmissionMethod::Adaptive)
        throw Error("--base 'adaptive': expected uniform or portal");
    const bool tuned = !opt.adaptiveEstimate.empty() || opt.adaptiveInitialSkyDepth >= 0 || opt.adaptiveMaxSkyDepth >= 0 || opt.adaptiveInitialDepth >= 0 || opt.adaptiveMaxDepth >= 0 ||
                       opt.adaptiveDefensive >= 0.0 || opt.adaptiveDiskShare >= 0.0 || opt.adaptiveSplit >= 0.0 ||
                       opt.adaptiveFirstPass > 0 || opt.adaptiveMaxCells > 0 || opt.adaptivePrior >= 0.0 ||
                       !opt.adaptiveWeights.empty();
    if (tuned && !adaptive)
        throw Error("the --adaptive-* options apply to --method adaptive");
    if (opt.adaptiveInitialSkyDepth >= 0)
        a.initialSkyDepth = opt.adaptiveInitialSkyDepth;
    if (opt.adaptiveMaxSkyDepth >= 0)
        a.maxSkyDepth = opt.adaptiveMaxSkyDepth;
    if (opt.adaptiveEstimate == "squares")
        a.estimate = GridEstimate::Squares;
    else if (!opt.adaptiveEstimate.empty() && opt.adaptiveEstimate != "pooled")
        throw Error(cat("--adaptive-estimate '", opt.adaptiveEstimate, "': expected pooled or squares"));
    if (opt.adaptiveInitialDepth >= 0)
        a.initialDepth = opt.adaptiveInitialDepth;
    if (opt.adaptiveMaxDepth >= 0)
        a.maxDepth = opt.adaptiveMaxDepth;
    if (opt.adaptiveDefensive >= 0.0)
        a.defensive = opt.adaptiveDefensive;
    if (opt.adaptiveDiskShare >= 0.0)
        a.diskShare = opt.adaptiveDiskShare;
    if (opt.adaptiveSplit >= 0.0)
        a.splitGain = opt.adaptiveSplit;
    if (opt.adaptiveFirstPass > 0)
        a.firstPass = opt.adaptiveFirstPass;
    if (opt.adaptiveMaxCells > 0)
        a.maxCells = opt.adaptiveMaxCells;
    if (opt.adaptivePrior >= 0.0)
        a.priorPaths = opt.adaptivePrior;
    if (opt.adaptiveWeights == "equal")
        a.weighBatches = false;
    else if (!opt.adaptiveWeights.empty() && opt.adaptiveWeights != "predicted")
        throw Error(cat("--adaptive-weights '", opt.adaptiveWeights, "': expected predicted or equal"));
    if (adaptive)
        validateAdaptiveOptions(a);
    return e;
}

int runRender(const RenderOptions& opt)
{
    const auto t0 = std::chrono::steady_clock::now();
    if (opt.outPath.size() < 5 || opt.outPath.substr(opt.outPath.size() - 4) != ".exr")
        throw Error(cat("--out '", opt.outPath, "' must name an .exr file"));
    const EmissionSettings emission = emissionSettings(opt);
    if (opt.paths > 0 && opt.timeSeconds > 0.0)
        throw Error("give either --paths or --time, not both");
    if (opt.timeSeconds < 0.0 || (opt.timeSeconds == 0.0 && opt.paths == 0))
        throw Error("--paths must be positive, or --time a positive number of seconds");
    prepareOutput(opt.outPath);

    const Scene scene = loadGltf(opt.scenePath);
    for (const auto& w : scene.warnings)
        std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
    const CameraSpec& camera = findCamera(scene, opt.camera);
    const std::optional<Goniogram> sky = buildSky(scene.sky);
    int width = 0, height = 0;
    resolveImageSize(camera, opt.width, opt.height, &width, &height);
    const Roi roi = parseRoi(opt.roi, width, height);
    std::optional<Image> reference;
    if (!opt.referencePath.empty()) {
        reference = readExr(opt.referencePath);
        if (reference->width != width || reference->height != height)
            throw Error(cat(opt.referencePath, ": reference is ", reference->width, " x ",
                            reference->height, ", the render ", width, " x ", height));
    }
    if (!scene.sun.present && scene.sky.type == SkySpec::Type::None)
        std::fprintf(stderr, "fenestra: warning: %s has neither a sun nor a sky: the image is black\n",
                     scene.source.c_str());

    ocl::Context ctx(ocl::selectDevice(opt.device));
    RenderSettings settings;
    settings.emission = emission;
    settings.paths = opt.paths;
    settings.timeSeconds = opt.timeSeconds;
    settings.batches = opt.batches;
    settings.cameraSpp = opt.cameraSpp;
    settings.seed = opt.seed;
    settings.maxBounces = opt.maxBounces;
    settings.bvhWidth = opt.bvhWidth;
    settings.poolSize = opt.poolSize;
    settings.progress = opt.progress < 0 ? isatty(STDERR_FILENO) != 0 : opt.progress > 0;
    settings.rois = {roi};
    Renderer renderer(ctx, scene, sky, camera, width, height, settings);
    const RenderResult r = renderer.render();

    for (float v : r.image.rgb)
        if (!std::isfinite(v))
            throw Error("internal error: the image holds a non-finite value");
    const RoiStats st = roiStats(r.image, r.stdErrLuminance, reference ? &*reference : nullptr, roi);

    const std::string pngPath = withExtension(opt.outPath, ".png");
    const std::string jsonPath = withExtension(opt.outPath, ".json");
    const std::string noisePath = withExtension(opt.outPath, ".noise.exr");
    writeExr(opt.outPath, r.image);
    // Each pixel's standard error of luminance (from its batches), grey: the error without a reference.
    Image noise(width, height);
    for (std::size_t p = 0; p < noise.pixels(); ++p)
        noise.rgb[3 * p] = noise.rgb[3 * p + 1] = noise.rgb[3 * p + 2] = static_cast<float>(r.stdErrLuminance[p]);
    writeExr(noisePath, noise);
    const double exposure = writePngPreview(pngPath, r.image, st.meanLuminance_cd_m2, opt.exposure);
    const double totalSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    nlohmann::json j;
    j["scene"] = scene.source;
    j["camera"] = camera.nodeName.empty() ? camera.cameraName : camera.nodeName;
    j["device"] = ctx.info().label();
    j["method"] = opt.method;
    j["width"] = width;
    j["height"] = height;
    j["seed"] = opt.seed;
    j["max_bounces"] = opt.maxBounces;
    j["bvh_layout"] = cat("bvh", r.bvhWidth);
    j["paths"] = r.paths;
    j["batches"] = r.batches;
    j["paths_per_batch"] = r.pathsPerBatch;
    j["camera_samples_per_pixel"] = static_cast<std::uint64_t>(r.batches) * opt.cameraSpp;
    const BatchCounts& n = r.counts;
    const std::uint64_t lightRays = n.extensionRays + n.shadowRays;
    j["rays"] = {{"extension", n.extensionRays},
                 {"shadow", n.shadowRays},
                 {"camera", n.cameraRays},
                 {"total", lightRays + n.cameraRays}};
    j["seconds"] = {{"total", totalSeconds},
                    {"render", r.renderSeconds},
                    {"calibration", r.calibrationSeconds},
                    {"bvh_build", r.bvhSeconds},
                    {"kernel_build", r.kernelBuildSeconds}};
    j["rays_per_second"] = r.renderSeconds > 0.0 ? lightRays / r.renderSeconds : 0.0;
    j["paths_per_second"] = r.renderSeconds > 0.0 ? r.paths / r.renderSeconds : 0.0;
    j["roi"] = {roi.x0, roi.y0, roi.x1, roi.y1};
    j["mean_luminance_cd_m2"] = st.meanLuminance_cd_m2;
    j["rms_luminance_cd_m2"] = st.rmsLuminance_cd_m2;
    j["noise_std_err_cd_m2"] = st.noiseStdErr_cd_m2;
    // The ROI mean's own standard error: batches are independent, so the spread of their ROI
    // means measures it directly (pixels within a batch are correlated through shared paths).
    j["mean_std_err_cd_m2"] = r.roiMeanStdErr(0);
    if (st.rmse_cd_m2) {
        j["reference"] = opt.referencePath;
        j["rmse_cd_m2"] = *st.rmse_cd_m2;
        j["rel_mse"] = *st.relMse;
    }
    j["emission"] = r.emission;
    j["counters"] = {{"bad_contributions", n.badContributions},
                     {"fixed_point_overflows", n.overflows},
                     {"stats_overflows", n.statsOverflows},
                     {"max_bounce_cuts", n.maxBounceCuts},
                     {"camera_glass_cuts", n.cameraGlassCuts}};
    for (const auto& [name, e] : r.kernels)
        j["kernels"][name] = {{"launches", e.launches}, {"device_seconds", e.deviceSeconds}};
    j["png_exposure"] = exposure;
    j["outputs"] = {{"exr", opt.outPath}, {"png", pngPath}, {"json", jsonPath}, {"noise_exr", noisePath}};
    {
        std::ofstream f(jsonPath);
        if (!f)
            throw Error(cat(jsonPath, ": cannot write"));
        f << j.dump(2) << "\n";
    }

    std::printf("%s: %d x %d, %llu paths in %d batches, %.1f s (%.2f Mrays/s)\n", opt.outPath.c_str(),
                width, height, static_cast<unsigned long long>(r.paths), r.batches, r.renderSeconds,
                r.renderSeconds > 0.0 ? lightRays / r.renderSeconds * 1e-6 : 0.0);
    std::printf("ROI [%d,%d)-[%d,%d): mean luminance %.4g cd/m2 (+- %.2g), RMS %.4g, noise %.3g",
                roi.x0, roi.y0, roi.x1, roi.y1, st.meanLuminance_cd_m2,
                r.roiMeanStdErr(0), st.rmsLuminance_cd_m2, st.noiseStdErr_cd_m2);
    if (st.rmse_cd_m2)
        std::printf(", RMSE %.4g, relMSE %.4g", *st.rmse_cd_m2, *st.relMse);
    std::printf("\nalso wrote %s, %s and %s\n", pngPath.c_str(), jsonPath.c_str(), noisePath.c_str());
    if (n.badContributions || n.overflows)
        std::fprintf(stderr,
                     "fenestra: warning: %llu non-finite contributions and %llu fixed-point "
                     "overflows were dropped\n",
                     static_cast<unsigned long long>(n.badContributions),
                     static_cast<unsigned long long>(n.overflows));
    return 0;
}

}  // namespace fen
