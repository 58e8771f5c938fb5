// renderer.h — a render from start to finish (DESIGN.md §2, §4, §5): the scene on the device, the
// emission strategy (emission/strategy.h), the film (render/film.h), the stages in either kernel
// form (render/path_loop.h), and the batch loop.
//
// Paths are rendered in B equal batches; each batch's pixels are accumulated in 128-bit fixed
// point (bit-identical for a given seed and device) and folded into a running mean and sum of
// squares, so every pixel carries its own standard error without a reference. Inside a batch the
// strategy may ask for passes (passLimit): the paths run in pieces, and after each the strategy
// reads its statistics and may change its density -- the hook after every pass, which a learning
// strategy uses. The camera pass adds the sky seen directly once per batch. With a time budget, a
// short calibration (not counted in the image, but a learning strategy learns from it) sizes the
// batches so that about B of them fill the time, and one smaller last batch takes the time the
// last whole one leaves (render/last_batch.h), weighed by its share of a batch's paths. In a team
// (settings.team) every member runs this same loop on its share of each pass's paths; the device
// sums are added over the members after every pass (team/shared_sums.h), the root alone runs the
// camera pass and hands out its image, and every decision that depends on a clock or a signal is
// the root's or everyone's, so all members take the same steps and hold the same state
// (DESIGN.md §9).
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cl/context.h"
#include "emission/strategy.h"
#include "emission/strategy_registry.h"
#include "io/image.h"
#include "render/camera_sampler.h"
#include "render/image_stats.h"
#include "render/path_loop.h"
#include "sensor/sensor_set.h"
#include "sensor/sensor_stats.h"
#include "scene/scene.h"
#include "sky/goniogram.h"
#include "team/shared_sums.h"
#include "team/team.h"

namespace fen {

class DeviceSceneCache;

class BatchStatistics;

// After every counted batch: the statistics so far, for a progress record (error against time).
struct BatchProgress {
    int batches = 0;                // batches done
    std::uint64_t paths = 0;        // paths in them
    double seconds = 0.0;           // since the render started, calibration included
    const BatchStatistics* stats = nullptr;
};

struct RenderSettings {
    EmissionSettings emission;
    std::uint64_t paths = 0;     // total light paths; 0 = use timeSeconds
    double timeSeconds = 0.0;
    int batches = 16;            // independent batches (>= 2): the noise estimate's sample size
    int cameraSpp = 1;           // camera-pass samples per pixel, per batch: the floor when balanced
    // How the camera pass spends its samples (render/camera_sampler.h): balanced, in proportion to
    // each pixel's own noise, or a fixed cameraSpp everywhere.
    CameraPassMode cameraPass = CameraPassMode::Balanced;
    std::uint32_t seed = 1;
    int maxBounces = 1024;       // guards against endless paths; roulette ends them (cut flux: reported)
    int bvhWidth = 0;            // 0 = the device's default layout
    std::uint32_t poolSize = 0;  // path slots; 0 = automatic
    std::optional<KernelMode> kernels;  // unset: defaultKernelMode(device is a GPU)
    // Russian roulette from this surface interaction on (lib/shade_path.h); unset: the emission
    // method's default, the most efficient across the measured scenes (defaultRouletteDepth(),
    // emission/strategy_registry.h; docs/results/termination.md).
    std::optional<int> rouletteDepth;
    // Splitting at the first diffuse vertex (lib/shade_path.h): a path of weight Y >= 2 w, w =
    // splitWeight times the emitted flux per path, goes on as min(floor(Y / w), splitMax) branches.
    // splitMax 1: never.
    int splitMax = 1;
    double splitWeight = 1.0;
    bool progress = false;       // progress line on stderr
    std::vector<Roi> rois;       // regions whose mean luminance is tracked batch by batch
    // Sensor grids (sensor/sensor_set.h; DESIGN.md §8): every path segment adds its flux to the
    // cells it crosses. Null or empty: none.
    const SensorSet* sensors = nullptr;
    // No image: the camera sees nothing and connects to nothing (a render for its sensors alone);
    // the film is one black pixel.
    bool noImage = false;
    // Daylight coefficients (annual/sky_patches.h; DESIGN.md §8): > 0, every path is tagged with
    // the Reinhart patch (this MF) it left the sky by, and the sensors also sum by patch. The sky
    // should then have a known luminance everywhere (the annual study's: 1 cd/m^2, ground too).
    int skyPatchMF = 0;
    // With skyPatchMF: each patch's luminance in the sky the coefficients are for (an annual
    // study's mean sky), which weighs what a learning strategy learns from the sensors (lib/sensor.h);
    // empty: the unit sky's (all 1).
    std::vector<double> skyPatchWeights;
    std::function<void(const BatchProgress&)> onBatch;  // optional
    // Set (by a signal handler) to stop: the batch in flight finishes and the render ends with the
    // batches done -- at least one, so the image is valid.
    const std::atomic<bool>* stop = nullptr;
    // Checkpoints (render/checkpoint.h): written to checkpointPath after a batch when
    // checkpointSeconds have passed since the last (or checkpointBatches batches, when > 0), and
    // when stopped; resumePath continues one. `carry`: the caller's own state, kept in the
    // checkpoint and restored on resume (the progress records).
    std::string checkpointPath, resumePath;
    double checkpointSeconds = 600.0;
    int checkpointBatches = 0;
    nlohmann::json* carry = nullptr;
    // Renders of one process (`fenestra batch`): the device scene (BVH, materials, textures) of the
    // same geometry on the same context is built once (render/device_scene.h).
    DeviceSceneCache* sceneCache = nullptr;
    // The members this render's paths are shared with (team/team.h: MPI ranks), each tracing its
    // share of every pass on its own device; the image is the one a single process gives, bit for
    // bit. Null: this process alone.
    Team* team = nullptr;
};

struct RenderResult {
    Image image;                         // mean of the batches: radiance, cd/m^2 (RGB)
    std::vector<double> stdErrLuminance; // per pixel: standard error of the luminance (cd/m^2)
    std::uint64_t paths = 0, pathsPerBatch = 0;
    std::uint64_t lastBatchPaths = 0;  // pathsPerBatch, or fewer: a render by time's last batch (last_batch.h)
    int batches = 0;
    BatchCounts counts;                  // rays and counters of the counted batches
    bool interrupted = false;         // stopped by settings.stop before its paths or time were done
    std::string checkpointError;      // a checkpoint could not be written: the render stopped there
    int resumedBatches = 0;           // batches that came from the checkpoint resumed
    int checkpoints = 0;              // checkpoints written
    double renderSeconds = 0.0;       // the counted batches
    double calibrationSeconds = 0.0;  // --time only: the uncounted first batches
    double bvhSeconds = 0.0, kernelBuildSeconds = 0.0;
    bool bvhReused = false;           // the device scene came from settings.sceneCache (bvhSeconds 0)
    int bvhWidth = 0;
    std::uint32_t poolSize = 0;
    KernelMode kernelMode = KernelMode::Wavefront;
    int rouletteDepth = 0;            // the depth rendered with (the method's, when not set)
    EmissionMethod method = EmissionMethod::Uniform;
    nlohmann::json emission;          // the strategy's report
    std::vector<std::string> emissionWarnings;  // the strategy's (EmissionStrategy::warnings)
    double emittedFluxPerPath = 0.0;  // lm (EmissionStrategy::emittedFluxPerPath)
    std::map<std::string, ocl::KernelStats::Entry> kernels;
    // roiBatchMeans[k][b]: mean luminance of settings.rois[k]'s light-traced part in batch b (plus
    // roiCamera[k]: roiMean). Batches are independent,
    // so their (weighted) spread gives the ROI mean's standard error (pixels within a batch are
    // not).
    std::vector<std::vector<double>> roiBatchMeans;
    // film.h BatchStatistics: 1 each unless the strategy learns (a last batch by time: its share)
    std::vector<double> batchWeights;
    // Per ROI, the camera pass's part apart from the batches' (film.h): its mean and that mean's
    // variance. roiBatchMeans are of the light-traced part.
    std::vector<std::pair<double, double>> roiCamera;
    std::optional<SensorStatistics> sensors;  // with sensors: each cell's illuminance over the batches
    // With skyPatchMF: the three daylight-coefficient matrices (DeviceSensors::readMatrices: all
    // light, direct, indirect) over the batches, as one vector of 3 x cells x patches.
    std::optional<SensorStatistics> daylightCoefficients;
    // The camera pass: its mode, samples, the share of the render's device time it took and its
    // predicted share of the image's variance (render_cmd.cpp writes it as JSON camera_pass).
    nlohmann::json cameraPass;
    // The team's part (render_cmd.cpp writes it as JSON team): members, their shares of the
    // paths, and the reductions' count, bytes and seconds; null for one process.
    nlohmann::json team;
    double cameraSamplesPerPixel = 0.0;  // mean over the pixels, all counted batches
    double roiMean(std::size_t k) const;
    double roiMeanStdErr(std::size_t k) const;
    // The flux the --max-bounces cap removed over the flux emitted: the relative bias of the cap
    // (0 when nothing was cut).
    double maxBounceFluxShare() const;
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
