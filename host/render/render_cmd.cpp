// render_cmd.cpp — `fenestra render`: scene in, EXR + PNG preview + JSON statistics out
// (DESIGN.md §5). Every JSON key is documented in README.md ("Render output").
#include "render/render_cmd.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <memory>
#include <optional>
#include <filesystem>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "annual/annual_report.h"
#include "annual/sky_patches.h"
#include "cl/device.h"
#include "io/exr_io.h"
#include "io/image.h"
#include "io/json_text.h"
#include "io/output_files.h"
#include "io/path_checks.h"
#include "render/checkpoint.h"
#include "render/device_scene.h"
#include "io/png_preview.h"
#include "render/camera_setup.h"
#include "render/image_stats.h"
#include "render/memory_check.h"
#include "render/path_loop.h"
#include "render/renderer.h"
#include "scene/gltf_load.h"
#include "io/false_color.h"
#include "io/sensor_csv.h"
#include "io/sensor_pictures.h"
#include "sensor/sensor_options.h"
#include "sensor/sensor_report.h"
#include "sensor/sensor_smoothing.h"
#include "sky/sky_spec.h"
#include "sky/solar_position.h"
#include "render/device_team.h"
#include "team/team.h"
#include "util/error.h"
#include "util/stop_signals.h"

namespace fen {

namespace {


// The sun and the sky rendered (after the command line's changes), for the JSON.
nlohmann::json sunJson(const Sun& sun)
{
    if (!sun.present)
        return nullptr;
    double altitude = 0.0, azimuth = 0.0;
    altitudeAzimuthOf(-sun.travelDirection, &altitude, &azimuth);
    const glm::dvec3 e = sun.illuminanceRgb_lux;
    return {{"altitude_deg", altitude}, {"azimuth_deg", azimuth}, {"normal_illuminance_lux", luminance(e.r, e.g, e.b)}};
}

nlohmann::json skyJson(const SkySpec& spec, const std::optional<Goniogram>& sky)
{
    if (spec.type == SkySpec::Type::None || !sky)
        return nullptr;
    nlohmann::json j;
    switch (spec.type) {
    case SkySpec::Type::Uniform:
        j = {{"type", "uniform"}, {"luminance_cd_m2", spec.luminance_cd_m2}};
        break;
    case SkySpec::Type::Cie:
        j = {{"type", "cie"},
             {"cie_type", spec.cieType},
             {"zenith_luminance_cd_m2", spec.zenithLuminance_cd_m2},
             {"sun_altitude_deg", spec.sunAltitudeDeg},
             {"sun_azimuth_deg", spec.sunAzimuthDeg}};
        break;
    case SkySpec::Type::Perez:
        j = {{"type", "perez"},
             {"source", spec.where},
             {"clearness_epsilon", spec.perezEpsilon},
             {"brightness_delta", spec.perezDelta},
             {"diffuse_horizontal_lux", spec.diffuseHorizontal_lux},
             {"illuminance_from", spec.illuminanceFromFile ? "weather file" : "irradiance x Perez 1990 efficacy"},
             {"sun_altitude_deg", spec.sunAltitudeDeg},
             {"sun_azimuth_deg", spec.sunAzimuthDeg}};
        break;
    default:
        j = {{"type", "table"}};
    }
    // The sky's own, over its table (a ground's rows face down: they add nothing here).
    j["horizontal_illuminance_lux"] = sky->illuminance(glm::dvec3(0.0, 1.0, 0.0));
    j["ground_albedo"] = spec.groundAlbedo;
    j["ground_luminance_cd_m2"] = sky->groundLuminance();
    return j;
}

}  // namespace

int runRender(const RenderOptions& opt, const RenderHooks& hooks)
{
    const auto t0 = std::chrono::steady_clock::now();
    const bool noImage = opt.sensors.noImage;
    const bool namesExr = opt.outPath.size() >= 5 && opt.outPath.substr(opt.outPath.size() - 4) == ".exr";
    if (!namesExr && !noImage)
        throw Error(cat("--out '", printable(opt.outPath), "' must name an .exr file"));
    if (opt.outPath.empty() || opt.outPath.back() == '/')
        throw Error(cat("--out '", printable(opt.outPath), "' must name a file"));
    // PATH of PATH.exr: every output is PATH.something (with --no-image, --out may be PATH itself).
    const std::string base = namesExr ? opt.outPath.substr(0, opt.outPath.size() - 4) : opt.outPath;
    const auto outputPath = [&](const std::string& ext) { return base + ext; };
    const EmissionSettings emission = opt.emission.settings();
    const std::string checkpointPath = opt.checkpointPath.value_or(""), resumePath = opt.resumePath.value_or("");
    const std::string referencePath = opt.referencePath.value_or("");
    // Every output's folder is created and proved writable, and no output is a folder, before a
    // long render rather than after it.
    const std::string pngPath = outputPath(".png");
    const std::string jsonPath = outputPath(".json");
    const std::string noisePath = outputPath(".noise.exr");
    const std::string errorPath = outputPath(".error.png");
    const std::string sensorCsvPath = outputPath(".sensors.csv");
    const std::string falsePath = outputPath(".falsecolor.png");
    // The outputs whose names --out alone decides (the sensors' pictures are named once they are known).
    const std::vector<std::string> namedOutputs{opt.outPath, pngPath, jsonPath, noisePath, errorPath, sensorCsvPath, falsePath};
    for (const std::string& p : namedOutputs)
        checkOutputPath(p, "--out");
    if (!checkpointPath.empty()) {
        checkOutputPath(checkpointPath, "--checkpoint");
        requireCheckpointTarget(checkpointPath, "--checkpoint");
    }
    // Files read are regular files (a FIFO would block the read for ever).
    if (!resumePath.empty())
        requireRegularFile(resumePath, "--resume");
    if (!referencePath.empty())
        requireRegularFile(referencePath, "--reference");

    Scene scene = loadGltf(opt.scenePath);
    // No output may overwrite an input: the scene and the files it reads, the reference, and the
    // checkpoint resumed from (except by the checkpoint itself: continuing one in place).
    // (what, path) of every file the render reads but the checkpoint it resumes; "" when not given.
    std::vector<std::pair<std::string, std::string>> inputs;
    for (std::size_t i = 0; i < scene.files.size(); ++i)
        inputs.emplace_back(i == 0 ? "the scene" : "a file the scene reads", scene.files[i]);
    inputs.emplace_back("the --reference image", referencePath);
    for (const std::string& f : opt.sensors.pointsFiles)
        inputs.emplace_back("a --sensor-points file", f);
    if (opt.skySun.weather)
        inputs.emplace_back("the --weather file", *opt.skySun.weather);
    if (opt.annual.weather)
        inputs.emplace_back("the --annual weather file", *opt.annual.weather);
    const std::pair<std::string, std::string> resumed{"the checkpoint to resume (--resume)", resumePath};
    for (const std::string& out : namedOutputs) {
        refuseOverwritingInputs(out, "--out", inputs);
        refuseOverwritingInputs(out, "--out", {resumed});
    }
    if (!checkpointPath.empty())
        refuseOverwritingInputs(checkpointPath, "--checkpoint", inputs);
    const SkySunReport skySun = applySkySunOptions(opt.skySun, &scene);
    // An annual study (DESIGN.md §8): its hours' skies from the weather file, read now so that a bad
    // file fails before the render; the render itself is under a sky of 1 cd/m^2 everywhere, the
    // ground too, and no sun, each path tagged with the patch it left the sky by.
    std::optional<WeatherFile> annualWeather;
    std::optional<AnnualSkies> annualSkyVectors;
    if (opt.annual.weather) {
        annualWeather = readWeatherFile(*opt.annual.weather);
        scene.sun.present = false;
        scene.sky = SkySpec{};
        scene.sky.type = SkySpec::Type::Uniform;
        scene.sky.where = "--annual";
        scene.sky.luminance_cd_m2 = 1.0;
    }
    for (const auto& w : scene.warnings)
        std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
    for (const auto& w : skySun.warnings)
        std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
    // The sensors: the scene's marked nodes, the work plane, the points files (DESIGN.md §8).
    const SensorSet sensors = buildSensors(opt.sensors, scene);
    scene.bounds.grow(sensorBounds(sensors));  // light is emitted where every sensor sees it
    if (sensors.empty() && (noImage || opt.sensors.smoothing_m))
        throw Error(cat(noImage ? "--no-image renders sensors alone" : "--sensor-smoothing smooths sensors", ", and ",
                        printable(scene.source),
                        " has none: give --sensor-points FILE or --work-plane NODE, or mark a node extras.sensor"));
    // A false-colour plan per sensor plane (io/sensor_pictures.h): PATH.sensors.png for the first,
    // PATH.sensors-NAME.png for the others; named now, from the cells alone, so that the set of
    // outputs is claimed before rendering.
    const std::string sensorPngPath = outputPath(".sensors.png");
    std::vector<std::string> sensorPngPaths;
    if (!sensors.empty()) {
        const SensorStatistics zero(sensors.cells.size());
        sensorPngPaths = sensorPicturePaths(sensorRows(sensors, zero, std::nullopt, sensorCsvPath), sensorPngPath);
    }
    for (const std::string& p : sensorPngPaths)
        checkOutputPath(p, "--out");
    std::optional<AnnualPaths> annualOut;
    if (opt.annual.weather) {
        annualOut = annualPaths(base, sensors);
        std::vector<std::string> names{annualOut->csv, annualOut->matrix, annualOut->directMatrix};
        names.insert(names.end(), annualOut->pngs.begin(), annualOut->pngs.end());
        for (const std::string& p : names) {
            checkOutputPath(p, "--out");
            refuseOverwritingInputs(p, "--out", inputs);
        }
    }
    // One render at a time writes this set; what a killed one left is finished or removed first.
    std::vector<std::string> outputSet{opt.outPath, noisePath, pngPath, errorPath, sensorCsvPath, falsePath};
    outputSet.insert(outputSet.end(), sensorPngPaths.begin(), sensorPngPaths.end());
    if (annualOut) {
        outputSet.insert(outputSet.end(), {annualOut->csv, annualOut->matrix, annualOut->directMatrix});
        outputSet.insert(outputSet.end(), annualOut->pngs.begin(), annualOut->pngs.end());
    }
    outputSet.push_back(jsonPath);
    if (!checkpointPath.empty())
        outputSet.push_back(checkpointPath);
    // In a team (mpirun) the root alone writes, warns and shows progress; the others trace.
    Team& team = hooks.team ? *hooks.team : processTeam();
    std::optional<OutputSetLock> outputLock;
    if (team.root())
        outputLock.emplace(outputSet);
    if (outputLock && !outputLock->recovered().empty())
        std::fprintf(stderr, "fenestra: warning: %s: %s\n", printable(opt.outPath).c_str(), outputLock->recovered().c_str());

    // No image: no camera is needed, and a one-pixel film that nothing reaches stands in.
    CameraSpec noCamera;
    noCamera.yfovRad = 1.0;
    noCamera.nodeName = "none";
    const CameraSpec& camera = noImage ? noCamera : findCamera(scene, opt.camera);
    std::optional<Goniogram> sky = buildSky(scene);
    if (opt.annual.weather)
        sky = sky->withGround(1.0, "--annual");
    int width = 1, height = 1;
    if (!noImage)
        resolveImageSize(camera, opt.width.value_or(0), opt.height.value_or(0), &width, &height);
    const Roi roi = parseRoi(opt.roi.value_or(""), width, height);
    // Named regions: a work plane, a wall -- each reported like the ROI (regions.NAME in the JSON).
    std::vector<std::pair<std::string, Roi>> regions;
    for (const std::string& spec : opt.regions) {
        const std::size_t eq = spec.find('=');
        const std::string name = spec.substr(0, eq == std::string::npos ? 0 : eq);
        if (eq == std::string::npos || name.empty() || name.size() > 64)
            throw Error(cat("--region '", printable(spec, 80), "': expected NAME=x0,y0,x1,y1"));
        for (const auto& [other, _] : regions)
            if (other == name)
                throw Error(cat("--region ", printable(name, 64), ": given twice"));
        regions.emplace_back(name, parseRoi(spec.substr(eq + 1), width, height, "--region " + printable(name, 64)));
    }
    std::optional<Image> reference;
    if (!referencePath.empty()) {
        reference = readExr(referencePath);
        if (reference->width != width || reference->height != height)
            throw Error(cat(referencePath, ": reference is ", reference->width, " x ",
                            reference->height, ", the render ", width, " x ", height));
    }
    if (!scene.sun.present && scene.sky.type == SkySpec::Type::None && team.root())
        std::fprintf(stderr, "fenestra: warning: %s has neither a sun nor a sky: the image is black\n",
                     scene.source.c_str());

    // The device, or with `--device all` or a list several, each a member of the render's team.
    std::vector<std::unique_ptr<ocl::Context>> ownContexts;
    if (!hooks.context)
        for (const ocl::DeviceInfo& d : ocl::selectDevices(opt.device, team.localRank()))
            ownContexts.push_back(std::make_unique<ocl::Context>(d));
    if (ownContexts.size() > 1 && team.size() > 1)
        throw Error(cat("--device '", opt.device, "': under mpirun each rank takes one device (",
                        ownContexts.size(), " named); start a rank per device instead"));
    ocl::Context& ctx = hooks.context ? *hooks.context : *ownContexts.front();
    std::vector<ocl::Context*> contexts{&ctx};
    for (std::size_t k = 1; k < ownContexts.size(); ++k)
        contexts.push_back(ownContexts[k].get());
    if (hooks.onInputs) {
        std::vector<std::string> read;
        for (const auto& input : inputs)
            if (!input.second.empty())
                read.push_back(input.second);
        if (!resumePath.empty())
            read.push_back(resumePath);
        hooks.onInputs(read, jsonPath);
    }
    // What the film and the path pool will take, against what each device and the host have; in a
    // team also the film's copy and differences (team/shared_sums.h), on the device and the host.
    const bool sharing = team.size() > 1 || contexts.size() > 1;
    for (const ocl::Context* c : contexts) {
        MemoryNeeds m = renderMemoryNeeds(width, height,
                                          opt.poolSize ? static_cast<std::uint64_t>(*opt.poolSize)
                                                       : defaultPoolSlots(c->info()));
        if (sharing) {
            const std::uint64_t film = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * 48;
            m.deviceBytes += 2 * film;
            m.hostBytes += film;
        }
        checkMemoryNeeds(m, c->info());
    }
    if (opt.annual.weather) {
        // The daylight coefficients: two cells x patches matrices of 128-bit sums on the device
        // (one buffer with the cells'); on the host each batch's read-back (16 bytes an entry of
        // those two) as three matrices (all, direct, indirect: 8 bytes an entry each), and their
        // weighted sums, mean and standard error (8 bytes each).
        const std::uint64_t entries = 2ull * sensors.cells.size() * skyPatchCount(opt.annual.settings.mf);
        MemoryNeeds m;
        m.deviceBytes = m.largestBufferBytes = (entries + sensors.cells.size()) * 16;
        m.hostBytes = entries * 16 + entries / 2 * 3 * (8 + 4 * 8);
        checkMemoryNeeds(m, ctx.info(), cat("--annual: the daylight coefficients of ", sensors.cells.size(), " cells x ",
                                            skyPatchCount(opt.annual.settings.mf), " sky patches"),
                         "use a smaller --sky-patches, or fewer sensor cells");
        annualSkyVectors = annualSkies(*annualWeather, opt.annual.settings);  // then the year's skies
    }
    RenderSettings settings;
    settings.emission = emission;
    settings.paths = static_cast<std::uint64_t>(opt.paths.value_or(0));
    settings.timeSeconds = opt.timeSeconds.value_or(0.0);
    settings.batches = opt.batchesValue();
    settings.cameraSpp = opt.cameraSpp.value_or(settings.cameraSpp);
    if (opt.cameraPass)
        settings.cameraPass = parseCameraPassMode(*opt.cameraPass);
    settings.seed = opt.seedValue();
    settings.maxBounces = opt.maxBouncesValue();
    settings.bvhWidth = opt.bvhWidth;
    settings.poolSize = static_cast<std::uint32_t>(opt.poolSize.value_or(0));
    if (opt.kernels)
        settings.kernels = parseKernelMode(*opt.kernels);
    settings.rouletteDepth = opt.rouletteDepth;  // not given: the renderer takes the method's
    settings.splitMax = opt.split.value_or(settings.splitMax);
    settings.splitWeight = opt.splitWeight.value_or(settings.splitWeight);
    settings.progress = team.root() && opt.progress.value_or(isatty(STDERR_FILENO) != 0);
    settings.team = &team;
    settings.rois = {roi};
    settings.sensors = &sensors;
    settings.noImage = noImage;
    settings.skyPatchMF = opt.annual.weather ? opt.annual.settings.mf : 0;
    const bool openingWalks = emission.method == EmissionMethod::Adaptive && emission.adaptive.openingsShare > 0.0;
    if (openingWalks && settings.skyPatchMF > 0)
        throw Error("--adaptive-openings-share: does not apply to an --annual study (the light a walk brings in has "
                    "no sky patch of its own)");
    if (openingWalks && noImage)
        throw Error("--adaptive-openings-share: needs an image (the walks start on the panes the opening aim learns "
                    "from what reaches the camera), and --no-image renders none");
    if (annualSkyVectors && opt.annual.settings.learnForYear)
        settings.skyPatchWeights = annualPatchWeights(*annualSkyVectors, opt.annual.settings.mf);
    for (const auto& reg : regions)
        settings.rois.push_back(reg.second);
    settings.checkpointPath = checkpointPath;
    settings.resumePath = resumePath;
    settings.checkpointSeconds = opt.checkpointSeconds;
    settings.checkpointBatches = opt.checkpointBatches;
    // The sun apart from the sky traces the render's scene again after it (annual/direct_sun.h):
    // a cache of this render's own keeps the device scene for it, where the caller keeps none.
    DeviceSceneCache ownSceneCache;
    const bool exactSun = opt.annual.weather && opt.annual.settings.exactSun;
    settings.sceneCache = hooks.sceneCache ? hooks.sceneCache : exactSun ? &ownSceneCache : nullptr;
    // Error against time, batch by batch (what `scripts/compare.py` charts): the ROI's mean, the
    // noise estimate, and with a reference the RMSE and the mean's bias.
    nlohmann::json progress = nlohmann::json::array();
    const double referenceMean = reference ? roiStats(*reference, {}, nullptr, roi).meanLuminance_cd_m2 : 0.0;
    settings.onBatch = [&](const BatchProgress& p) {
        const Image img = p.stats->mean();
        const RoiStats s = roiStats(img, p.stats->stdErrLuminance(), reference ? &*reference : nullptr, roi);
        nlohmann::json e = {{"batches", p.batches},
                            {"paths", p.paths},
                            {"seconds", p.seconds},
                            {"mean_luminance_cd_m2", s.meanLuminance_cd_m2}};
        if (p.batches >= 2)
            e["noise_std_err_cd_m2"] = s.noiseStdErr_cd_m2;
        if (s.rmse_cd_m2) {
            e["rmse_cd_m2"] = *s.rmse_cd_m2;
            e["bias_cd_m2"] = s.meanLuminance_cd_m2 - referenceMean;
        }
        progress.push_back(e);
    };
    settings.carry = &progress;  // a resumed render's records start with those before it
    const StopSignals signals;  // Ctrl-C asks for a graceful stop (util/stop_signals.h)
    settings.stop = StopSignals::flag();
    // Warned once the settings are known to be valid, so that an error stays one line.
    const auto warnPaths = [&] {
        if (settings.paths > 0 && settings.paths % static_cast<std::uint64_t>(settings.batches) != 0 && team.root())
            std::fprintf(stderr, "fenestra: warning: --paths %llu is not a multiple of the %d batches: %llu paths "
                         "are traced (batches of %llu)\n",
                         static_cast<unsigned long long>(settings.paths), settings.batches,
                         static_cast<unsigned long long>(settings.paths / settings.batches * settings.batches),
                         static_cast<unsigned long long>(settings.paths / settings.batches));
    };
    RenderResult r;
    if (contexts.size() == 1) {
        Renderer renderer(ctx, scene, sky, camera, width, height, settings);
        warnPaths();
        r = renderer.render();
    } else {
        r = renderOnDevices(contexts, scene, sky, camera, width, height, settings);
        warnPaths();
    }
    if (&team == &processTeam())
        markLastCollectiveDone();
    if (!team.root())  // the root writes the outputs, and reports a failed checkpoint
        return r.interrupted ? 130 : 0;

    for (float v : r.image.rgb)
        if (!std::isfinite(v))
            throw Error("internal error: the image holds a non-finite value");
    const RoiStats st = roiStats(r.image, r.stdErrLuminance, reference ? &*reference : nullptr, roi);

    // Each pixel's standard error of luminance (from its batches), grey: the error without a reference.
    Image noise(width, height);
    for (std::size_t p = 0; p < noise.pixels(); ++p)
        noise.rgb[3 * p] = noise.rgb[3 * p + 1] = noise.rgb[3 * p + 2] = static_cast<float>(r.stdErrLuminance[p]);
    const Preview preview = pngPreview(r.image, st.meanLuminance_cd_m2, opt.exposure.value_or(0.0));
    const double exposure = preview.exposure;
    OutputFiles outputs;
    if (!noImage) {
        outputs.add(opt.outPath, encodeExr(r.image));
        outputs.add(noisePath, encodeExr(noise));
        outputs.add(pngPath, preview.png);
    }
    if (reference)
        outputs.add(errorPath, errorPng(r.image, *reference, referenceMean));
    // Sensors: cells as CSV, summaries in the JSON; a daylight-factor study divides by the sky's
    // unobstructed horizontal illuminance (DESIGN.md §8).
    std::optional<DaylightFactorSpec> df;
    if (opt.sensors.daylightFactor && sky)
        df = DaylightFactorSpec{sky->illuminance(glm::dvec3(0.0, 1.0, 0.0)), opt.sensors.dfThresholdValue()};
    nlohmann::json sensorJson = nullptr;
    if (r.sensors) {
        for (double v : r.sensors->mean())
            if (!std::isfinite(v))
                throw Error("internal error: a sensor cell holds a non-finite value");
        // --sensor-smoothing: every batch's cells through the same local linear fit, so each
        // reported cell keeps its batch spread (sensor/sensor_smoothing.h)
        std::optional<SensorStatistics> smoothed;
        if (opt.sensors.smoothing_m) {
            const SensorSmoother smoother(sensors, *opt.sensors.smoothing_m, &scene);
            smoothed = r.sensors->mapped([&](const std::vector<double>& v) { return smoother.apply(v); });
        }
        const SensorStatistics& shown = smoothed ? *smoothed : *r.sensors;
        const SensorFile file = sensorRows(sensors, shown, df, sensorCsvPath);
        outputs.add(sensorCsvPath, sensorCsv(file));
        sensorJson = sensorSummary(sensors, shown, df);
        // the plans: the daylight factor in a DF study, else the illuminance, on one linear scale
        std::vector<double> values;
        for (const SensorRow& row : file.rows)
            values.push_back(df ? row.daylightFactor : row.illuminance);
        for (SensorPicture& pic : sensorPictures(file, df.has_value(), autoScale(values, false, df ? "% DF" : "lux"),
                                                 sensorPngPath))
            outputs.add(pic.path, std::move(pic.png));
    }
    nlohmann::json annualJson = nullptr;
    std::vector<std::string> annualLines;
    if (annualOut && r.daylightCoefficients) {
        std::optional<DirectSun> directSun;
        std::shared_ptr<const DeviceScene> sunScene;
        if (exactSun) {
            bool reused = false;
            sunScene = settings.sceneCache->get(ctx, scene, r.bvhWidth, &reused);
            directSun.emplace(ctx, *sunScene, sensors, annualSkyVectors->sunDirection, annualSkyVectors->sunNormal_lux,
                              opt.annual.settings.sunPoints, settings.seed);
        }
        annualJson = writeAnnual(sensors, *r.daylightCoefficients, *annualWeather, *annualSkyVectors,
                                 opt.annual.settings, directSun ? &*directSun : nullptr, *annualOut, outputs,
                                 &annualLines);
        if (directSun) {  // its launches join the render's in the JSON's kernels
            const auto& e = ctx.stats().entries();
            if (const auto k = e.find("direct_sun"); k != e.end())
                r.kernels["direct_sun"] = k->second;
        }
    }
    if (opt.sensors.falseColor) {
        // the image's luminance in false colour, on a log scale of whole decades
        std::vector<double> y(r.image.pixels());
        for (std::size_t i = 0; i < y.size(); ++i)
            y[i] = r.image.luminance(i);
        FalseColorScale scale = autoScale(y, true, "cd/m²");
        scale.title = "luminance";
        outputs.add(falsePath, falseColorImagePng(y, width, height, scale));
    }
    const double totalSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    nlohmann::json j;
    j["scene"] = scene.source;
    j["camera"] = camera.nodeName.empty() ? camera.cameraName : camera.nodeName;
    j["sun"] = sunJson(scene.sun);
    j["sky"] = skyJson(scene.sky, sky);
    std::string deviceLabels;
    for (const ocl::Context* c : contexts)
        deviceLabels += (deviceLabels.empty() ? "" : " + ") + c->info().label();
    j["device"] = deviceLabels;
    j["method"] = methodName(r.method);
    j["width"] = width;
    j["height"] = height;
    j["seed"] = opt.seedValue();
    j["max_bounces"] = opt.maxBouncesValue();
    j["roulette_depth"] = r.rouletteDepth;
    j["split_max"] = settings.splitMax;
    j["split_weight"] = settings.splitWeight;
    j["kernel_mode"] = kernelModeName(r.kernelMode);
    j["bvh_layout"] = cat("bvh", r.bvhWidth);
    j["paths"] = r.paths;
    j["interrupted"] = r.interrupted;
    j["checkpoint"] = {{"written", r.checkpoints},
                       {"path", checkpointPath.empty() ? nlohmann::json(nullptr) : nlohmann::json(checkpointPath)},
                       {"resumed_from", resumePath.empty() ? nlohmann::json(nullptr) : nlohmann::json(resumePath)},
                       {"resumed_batches", r.resumedBatches}};
    j["batches"] = r.batches;
    j["paths_per_batch"] = r.pathsPerBatch;
    j["last_batch_paths"] = r.lastBatchPaths;
    j["camera_samples_per_pixel"] = r.cameraSamplesPerPixel;
    j["camera_pass"] = r.cameraPass;
    if (!r.team.is_null())
        j["team"] = r.team;
    const BatchCounts& n = r.counts;
    const std::uint64_t lightRays = n.extensionRays + n.shadowRays;
    j["rays"] = {{"extension", n.extensionRays},
                 {"shadow", n.shadowRays},
                 {"camera", n.cameraRays},
                 {"total", lightRays + n.cameraRays}};
    j["seconds"] = {{"total", totalSeconds},
                    {"render", r.renderSeconds},
                    {"calibration", r.calibrationSeconds},
                    {"bvh_build", r.bvhSeconds},  // 0 when an earlier job of a batch built it (bvh_reused)
                    {"kernel_build", r.kernelBuildSeconds}};
    j["bvh_reused"] = r.bvhReused;
    j["rays_per_second"] = r.renderSeconds > 0.0 ? lightRays / r.renderSeconds : 0.0;
    j["paths_per_second"] = r.renderSeconds > 0.0 ? r.paths / r.renderSeconds : 0.0;
    j["roi"] = {roi.x0, roi.y0, roi.x1, roi.y1};
    j["mean_luminance_cd_m2"] = st.meanLuminance_cd_m2;
    j["rms_luminance_cd_m2"] = st.rmsLuminance_cd_m2;
    // One batch (an interrupted render) has no spread to estimate the noise from.
    j["noise_std_err_cd_m2"] = r.batches >= 2 ? nlohmann::json(st.noiseStdErr_cd_m2) : nlohmann::json(nullptr);
    j["noise_top1_share"] = r.batches >= 2 ? nlohmann::json(st.noiseTop1Share) : nlohmann::json(nullptr);
    // The ROI mean's own standard error: batches are independent, so the spread of their ROI
    // means measures it directly (pixels within a batch are correlated through shared paths).
    j["mean_std_err_cd_m2"] = r.roiMeanStdErr(0);
    if (st.rmse_cd_m2) {
        j["reference"] = referencePath;
        j["rmse_cd_m2"] = *st.rmse_cd_m2;
        j["rel_mse"] = *st.relMse;
        j["bias_cd_m2"] = st.meanLuminance_cd_m2 - referenceMean;
        j["reference_mean_luminance_cd_m2"] = referenceMean;
    }
    nlohmann::json regionsJson = nlohmann::json::object();
    for (std::size_t k = 0; k < regions.size(); ++k) {
        const Roi& g = regions[k].second;
        const RoiStats s = roiStats(r.image, r.stdErrLuminance, reference ? &*reference : nullptr, g);
        nlohmann::json e = {{"roi", {g.x0, g.y0, g.x1, g.y1}},
                            {"mean_luminance_cd_m2", s.meanLuminance_cd_m2},
                            {"mean_std_err_cd_m2", r.roiMeanStdErr(k + 1)},
                            {"noise_std_err_cd_m2", r.batches >= 2 ? nlohmann::json(s.noiseStdErr_cd_m2)
                                                                   : nlohmann::json(nullptr)}};
        if (s.rmse_cd_m2) {
            const double refMean = roiStats(*reference, {}, nullptr, g).meanLuminance_cd_m2;
            e["rmse_cd_m2"] = *s.rmse_cd_m2;
            e["bias_cd_m2"] = s.meanLuminance_cd_m2 - refMean;
            e["reference_mean_luminance_cd_m2"] = refMean;
        }
        regionsJson[regions[k].first] = e;
    }
    j["regions"] = regionsJson;
    j["sensors"] = sensorJson;
    j["annual"] = annualJson;
    j["sensor_smoothing_m"] = opt.sensors.smoothing_m ? nlohmann::json(*opt.sensors.smoothing_m) : nlohmann::json(nullptr);
    j["emission"] = r.emission;
    j["progress"] = progress;
    j["counters"] = {{"bad_contributions", n.badContributions},
                     {"fixed_point_overflows", n.overflows},
                     {"stats_overflows", n.statsOverflows},
                     {"max_bounce_cuts", n.maxBounceCuts},
                     // the flux the cuts removed, over the flux emitted: the bias of the cap
                     {"max_bounce_flux_share", r.maxBounceFluxShare()},
                     {"max_bounce_flux_lm", r.paths > 0 ? n.cutFlux / static_cast<double>(r.paths) : 0.0},
                     {"camera_glass_cuts", n.cameraGlassCuts},
                     // the scatters at diffuse vertices, and those whose direction the guide drew
                     {"diffuse_vertices", n.diffuseVertices},
                     {"guided_vertices", n.guidedVertices},
                     {"guided_vertex_share", n.diffuseVertices ? static_cast<double>(n.guidedVertices) /
                                                                     static_cast<double>(n.diffuseVertices)
                                                               : 0.0},
                     // branches made by splitting (--split, weight windows); paths the windows culled
                     {"split_branches", n.splitBranches},
                     {"window_culls", n.windowCulls},
                     // paths that started on the aimed panes, and the rays their walks outside traced
                     // (--adaptive-openings-share; not in the extension rays)
                     {"opening_walks", n.openingWalks},
                     {"opening_walk_rays", n.openingWalkRays}};
    for (const auto& [name, e] : r.kernels)
        j["kernels"][name] = {{"launches", e.launches}, {"device_seconds", e.deviceSeconds}};
    j["png_exposure"] = exposure;
    j["image"] = !noImage;
    j["outputs"] = {{"json", jsonPath}};
    if (!noImage) {
        j["outputs"]["exr"] = opt.outPath;
        j["outputs"]["png"] = pngPath;
        j["outputs"]["noise_exr"] = noisePath;
    }
    if (r.sensors) {
        j["outputs"]["sensors_csv"] = sensorCsvPath;
        j["outputs"]["sensors_png"] = sensorPngPaths;
    }
    if (opt.sensors.falseColor)
        j["outputs"]["falsecolor_png"] = falsePath;
    if (annualJson.is_object())
        j["outputs"]["annual"] = annualJson["outputs"];
    if (reference)
        j["outputs"]["error_png"] = errorPath;
    // Names are bytes: what is not UTF-8 is written as \xNN (util/utf8.h), so this cannot fail now.
    outputs.add(jsonPath, dumpUtf8(std::move(j), 2) + "\n");  // last: it names the others
    outputs.commit();

    if (noImage)
        std::printf("%s: sensors only, %llu paths in %d batches, %.1f s (%.2f Mrays/s)\n", base.c_str(),
                    static_cast<unsigned long long>(r.paths), r.batches, r.renderSeconds,
                    r.renderSeconds > 0.0 ? lightRays / r.renderSeconds * 1e-6 : 0.0);
    else
        std::printf("%s: %d x %d, %llu paths in %d batches, %.1f s (%.2f Mrays/s)\n", opt.outPath.c_str(),
                    width, height, static_cast<unsigned long long>(r.paths), r.batches, r.renderSeconds,
                    r.renderSeconds > 0.0 ? lightRays / r.renderSeconds * 1e-6 : 0.0);
    if (!noImage) {
        std::printf("ROI [%d,%d)-[%d,%d): mean luminance %.4g cd/m2 (+- %.2g), RMS %.4g, noise %.3g",
                    roi.x0, roi.y0, roi.x1, roi.y1, st.meanLuminance_cd_m2,
                    r.roiMeanStdErr(0), st.rmsLuminance_cd_m2, st.noiseStdErr_cd_m2);
        if (st.rmse_cd_m2)
            std::printf(", RMSE %.4g, relMSE %.4g", *st.rmse_cd_m2, *st.relMse);
        std::printf("\n");
    }
    for (const auto& [name, e] : sensorJson.is_object() ? sensorJson.items() : nlohmann::json::object().items()) {
        std::printf("sensor %s: %zu cells, mean %.4g lux (+- %.2g), min %.4g, max %.4g, uniformity %.3g",
                    name.c_str(), e["cells"].get<std::size_t>(), e["mean_lux"].get<double>(),
                    e["mean_lux_std_err"].is_null() ? 0.0 : e["mean_lux_std_err"].get<double>(),
                    e["min_lux"].get<double>(), e["max_lux"].get<double>(), e["uniformity"].get<double>());
        if (e.contains("daylight_factor")) {
            const auto& d = e["daylight_factor"];
            std::printf("; DF mean %.3g %% (+- %.2g), %.0f %% of the area at or above %g %%", d["mean_pct"].get<double>(),
                        d["mean_pct_std_err"].is_null() ? 0.0 : d["mean_pct_std_err"].get<double>(),
                        100.0 * d["area_share_above"].get<double>(), d["threshold_pct"].get<double>());
        }
        std::printf("\n");
    }
    for (const std::string& line : annualLines)
        std::printf("%s\n", line.c_str());
    // Every file written besides the EXR, in one line.
    std::vector<std::string> wrote;
    if (!noImage)
        wrote = {pngPath, noisePath};
    if (reference)
        wrote.push_back(errorPath);
    if (opt.sensors.falseColor)
        wrote.push_back(falsePath);
    if (r.sensors) {
        wrote.push_back(sensorCsvPath);
        wrote.insert(wrote.end(), sensorPngPaths.begin(), sensorPngPaths.end());
    }
    if (annualJson.is_object()) {
        wrote.insert(wrote.end(), {annualOut->csv, annualOut->matrix, annualOut->directMatrix});
        wrote.insert(wrote.end(), annualOut->pngs.begin(), annualOut->pngs.end());
    }
    wrote.push_back(jsonPath);
    std::string list;
    for (std::size_t i = 0; i < wrote.size(); ++i)
        list += (i == 0 ? "" : i + 1 == wrote.size() ? " and " : ", ") + wrote[i];
    std::printf("%s %s\n", noImage ? "wrote" : "also wrote", list.c_str());
    // What the strategy wants the user to know (e.g. portal emission's measured blind spot).
    for (const std::string& w : r.emissionWarnings)
        std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
    if (n.badContributions || n.overflows)
        std::fprintf(stderr,
                     "fenestra: warning: %llu non-finite contributions and %llu fixed-point "
                     "overflows were dropped\n",
                     static_cast<unsigned long long>(n.badContributions),
                     static_cast<unsigned long long>(n.overflows));
    if (!r.checkpointError.empty())
        throw Error(cat(r.checkpointError, " (the render stopped there; its outputs hold the ", r.batches,
                        " batches finished)"));
    if (r.interrupted) {
        // The files are complete and valid for the paths traced; the status says they are fewer
        // than asked for (the shell's convention for a Ctrl-C).
        std::fprintf(stderr, "fenestra: interrupted: the outputs hold the %d batches finished (%llu paths)\n",
                     r.batches, static_cast<unsigned long long>(r.paths));
        return 130;
    }
    return 0;
}

}  // namespace fen
