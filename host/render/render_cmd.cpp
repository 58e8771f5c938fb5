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

int runRender(const RenderOptions& opt)
{
    const auto t0 = std::chrono::steady_clock::now();
    if (opt.outPath.size() < 5 || opt.outPath.substr(opt.outPath.size() - 4) != ".exr")
        throw Error(cat("--out '", opt.outPath, "' must name an .exr file"));
    const EmissionMethod method = parseEmissionMethod(opt.method);
    const PortalOverlap overlap = parsePortalOverlap(opt.portalOverlap);
    if (method != EmissionMethod::Portal && !opt.portals.empty())
        throw Error("--portals applies to --method portal");
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
    settings.method = method;
    settings.portals = opt.portals;
    settings.overlap = overlap;
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
    const std::uint64_t lightRays = r.extensionRays + r.shadowRays;
    j["rays"] = {{"extension", r.extensionRays},
                 {"shadow", r.shadowRays},
                 {"camera", r.cameraRays},
                 {"total", lightRays + r.cameraRays}};
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
    if (method == EmissionMethod::Portal)
        j["emission"] = {{"portal_nodes", r.portalNodes},
                         {"portal_triangles", r.portalTriangles},
                         {"portal_plane_groups", r.portalGroups},
                         {"portal_overlap", opt.portalOverlap},
                         {"sun_flux_lm", r.portalSunFlux_lm},
                         {"sky_flux_lm", r.portalSkyFlux_lm},
                         {"precompute_seconds", r.portalPrecomputeSeconds}};
    else
        j["emission"] = {{"sun_flux_lm", r.emission.sunFlux},
                         {"sky_flux_lm", r.emission.skyFlux},
                         {"p_sun", r.emission.pSun},
                         {"disk_radius_m", r.emission.sphereRadius_m}};
    j["counters"] = {{"bad_contributions", r.badContributions},
                     {"fixed_point_overflows", r.overflows},
                     {"max_bounce_cuts", r.maxBounceCuts},
                     {"camera_glass_cuts", r.cameraGlassCuts}};
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
    if (r.badContributions || r.overflows)
        std::fprintf(stderr,
                     "fenestra: warning: %llu non-finite contributions and %llu fixed-point "
                     "overflows were dropped\n",
                     static_cast<unsigned long long>(r.badContributions),
                     static_cast<unsigned long long>(r.overflows));
    return 0;
}

}  // namespace fen
