// camera_sampler.cpp — the camera pass's samples per pixel (camera_sampler.h).
#include "render/camera_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "io/image.h"
#include "io/state_io.h"
#include "render/pooled_variance.h"
#include "util/error.h"

namespace fen {

CameraPassMode parseCameraPassMode(const std::string& s)
{
    if (s == "fixed")
        return CameraPassMode::Fixed;
    if (s == "balanced")
        return CameraPassMode::Balanced;
    throw Error("--camera-pass '" + s + "': expected fixed or balanced");
}

std::string cameraPassModeName(CameraPassMode m)
{
    return m == CameraPassMode::Fixed ? "fixed" : "balanced";
}

CameraSampler::CameraSampler(std::size_t pixels, std::uint32_t floor, CameraPassMode mode)
    : pixels_(pixels), floor_(std::clamp<std::uint32_t>(floor, 1u, kMaxPerPixel)), mode_(mode),
      counts_(pixels, mode == CameraPassMode::Balanced ? kPilotSamples : floor_), sigma_(pixels, 0.0),
      pilotPass_(mode == CameraPassMode::Balanced && pixels > 0 ? 0 : 2)
{
}

std::uint64_t CameraSampler::samplesPerBatch() const
{
    return std::accumulate(counts_.begin(), counts_.end(), std::uint64_t{0});
}

std::uint32_t CameraSampler::maxCount() const
{
    return counts_.empty() ? 0u : *std::max_element(counts_.begin(), counts_.end());
}

namespace {

// Calls f(q) for each of pixel p's neighbours (up to 8) in an image `width` x `height`.
template <class F>
void forEachNeighbour(std::size_t p, std::size_t width, std::size_t height, F f)
{
    const std::size_t x = p % width, y = p / width;
    for (std::size_t yy = y > 0 ? y - 1 : 0; yy <= std::min(y + 1, height - 1); ++yy)
        for (std::size_t xx = x > 0 ? x - 1 : 0; xx <= std::min(x + 1, width - 1); ++xx)
            if (yy != y || xx != x)
                f(yy * width + xx);
}

}  // namespace

void CameraSampler::addPilot(const std::vector<float>& camera, std::uint64_t cameraRays, std::size_t width)
{
    if (camera.size() != 4 * pixels_ || pilotPass_ >= 2 || width == 0 || pixels_ % width != 0)
        throw std::logic_error("CameraSampler::addPilot: one value per pixel, while piloting");
    if (pilotPass_ == 0) {
        pilotN_.assign(pixels_, 0.0);
        pilotY1_ = pilotY2_ = pilotM2_ = pilotN_;
        const double samples = static_cast<double>(samplesPerBatch());
        raysPerSample_ = samples > 0.0 ? std::max(1.0, static_cast<double>(cameraRays) / samples) : 1.0;
    }
    double brightest = 0.0;
    for (std::size_t p = 0; p < pixels_; ++p) {
        const double n = counts_[p];
        const double m = luminance(camera[4 * p], camera[4 * p + 1], camera[4 * p + 2]);
        pilotN_[p] += n;
        pilotY1_[p] += n * m;
        pilotY2_[p] += n * m * m;
        pilotM2_[p] += std::max(0.0, static_cast<double>(camera[4 * p + 3]));
        sigma_[p] = std::sqrt(pooledSampleVariance(pilotN_[p], pilotY1_[p], pilotY2_[p], pilotM2_[p]));
        brightest = std::max(brightest, pilotY1_[p] / std::max(pilotN_[p], 1.0));
    }
    // What varies less than this across a pixel (a thousandth of the brightest pixel) is no edge:
    // a sky's own gradient is less.
    const double tau = 1e-3 * brightest;
    const std::size_t height = pixels_ / width;
    const auto mean = [this](std::size_t q) { return pilotY1_[q] / pilotN_[q]; };
    if (pilotPass_ == 0) {
        // The second pass: every pixel near an edge -- next to one whose samples varied, or whose
        // mean differs from its own, by more than tau. The second test finds an edge that runs
        // along pixel boundaries, whose pixels are nearly all one side and so rarely vary.
        bool any = false;
        for (std::size_t p = 0; p < pixels_; ++p) {
            bool near = false;
            forEachNeighbour(p, width, height, [&](std::size_t q) {
                near = near || sigma_[q] > tau || std::abs(mean(q) - mean(p)) > tau;
            });
            counts_[p] = near ? kPilotRefineSamples : 0u;
            any = any || near;
        }
        pilotPass_ = 1;
        if (any)
            return;
    }
    // A pixel next to an edge whose samples all agreed may still hold a sliver of it: 1 - (1 - p)^N
    // is small for a sliver p ~ 1/N. Its deviation is given the posterior mean of p (1 - p) under a
    // uniform prior on the sliver p after N agreeing samples, (N + 1) / ((N + 2)(N + 3)), times the
    // contrast to its neighbours' means squared: the pure sky next to a mullion then costs a few
    // samples a batch, and a pixel 99 % sky is not left at one.
    if (pilotPass_ == 1) {
        std::vector<double> prior(pixels_, 0.0);
        for (std::size_t p = 0; p < pixels_; ++p) {
            if (counts_[p] == 0 || sigma_[p] > tau)
                continue;  // not looked at again, or it varied: its own estimate stands
            double contrast = 0.0;
            forEachNeighbour(p, width, height,
                             [&](std::size_t q) { contrast = std::max(contrast, std::abs(mean(q) - mean(p))); });
            const double N = pilotN_[p];
            prior[p] = contrast * std::sqrt((N + 1.0) / ((N + 2.0) * (N + 3.0)));
        }
        for (std::size_t p = 0; p < pixels_; ++p)
            sigma_[p] = std::max(sigma_[p], prior[p]);
    }
    pilotPass_ = 2;
    pilotN_.clear();
    pilotY1_.clear();
    pilotY2_.clear();
    pilotM2_.clear();
    std::fill(counts_.begin(), counts_.end(), floor_);  // until the light tracer's variance is known
}

void CameraSampler::afterBatch(const std::vector<double>& lightLuminance, double weight, std::uint64_t lightRays,
                               double pathsShare)
{
    samplesTotal_ += samplesPerBatch();
    if (mode_ == CameraPassMode::Fixed)
        return;  // its counts never change
    if (lightLuminance.size() != pixels_)
        throw std::logic_error("CameraSampler::afterBatch: one value per pixel");
    if (!lastLight_.empty() && weight > 0.0 && lastWeight_ > 0.0) {
        double d2 = 0.0;
        for (std::size_t p = 0; p < pixels_; ++p) {
            const double d = lightLuminance[p] - lastLight_[p];
            d2 += d * d;
        }
        lightVarSum_ += d2 / (1.0 / weight + 1.0 / lastWeight_);
        ++pairs_;
    }
    lastLight_ = lightLuminance;
    lastWeight_ = weight;
    // the pair above with the batch's own weight; the plan for a full batch's (weights and rays
    // grow with the paths)
    const double share = pathsShare > 0.0 && pathsShare < 1.0 ? pathsShare : 1.0;
    allocate(weight / share, static_cast<std::uint64_t>(static_cast<double>(lightRays) / share));
}

void CameraSampler::allocate(double weight, std::uint64_t lightRays)
{
    if (pairs_ == 0 || !(weight > 0.0) || needsPilot())
        return;  // the light tracer's variance is not known yet: the floor stays
    const double lightVar = lightVarSum_ / static_cast<double>(pairs_) / weight;  // the next batch's, all pixels
    const double sigmaSum = std::accumulate(sigma_.begin(), sigma_.end(), 0.0);
    const double T = static_cast<double>(lightRays), c = raysPerSample_;
    // The optimum; with no light-tracing noise to balance against, as many as the caps allow.
    double k = lightVar > 0.0 ? std::sqrt(T / (c * lightVar)) : std::numeric_limits<double>::infinity();
    // The camera pass traces no more rays than the light tracer: a scene whose light never
    // reaches the camera must not turn into a sky renderer.
    const double spare = T / c - static_cast<double>(floor_) * static_cast<double>(pixels_);
    k = sigmaSum > 0.0 ? std::min(k, std::max(0.0, spare) / sigmaSum) : 0.0;
    for (std::size_t p = 0; p < pixels_; ++p) {
        const double n = std::min(std::round(k * sigma_[p]), static_cast<double>(kMaxPerPixel));
        counts_[p] = std::max(floor_, static_cast<std::uint32_t>(n));
    }
    double cameraVar = 0.0;
    for (std::size_t p = 0; p < pixels_; ++p)
        cameraVar += sigma_[p] * sigma_[p] / static_cast<double>(counts_[p]);
    errorShare_ = cameraVar + lightVar > 0.0 ? cameraVar / (cameraVar + lightVar) : 0.0;
}

std::uint64_t CameraSampler::pixelsAboveFloor() const
{
    return static_cast<std::uint64_t>(std::count_if(counts_.begin(), counts_.end(),
                                                    [&](std::uint32_t n) { return n > floor_; }));
}

void CameraSampler::save(StateWriter& w) const
{
    w.u64s("camera.counts", std::vector<std::uint64_t>(counts_.begin(), counts_.end()));
    w.f64s("camera.sigma", sigma_);
    w.f64("camera.rays_per_sample", raysPerSample_);
    if (needsPilot())
        throw std::logic_error("CameraSampler::save: in the middle of the pilot");
    w.f64s("camera.last_light", lastLight_);
    w.f64("camera.last_weight", lastWeight_);
    w.f64("camera.light_var_sum", lightVarSum_);
    w.u64("camera.pairs", pairs_);
    w.u64("camera.samples_total", samplesTotal_);
    w.f64("camera.error_share", errorShare_);
}

void CameraSampler::load(StateReader& r)
{
    const std::vector<std::uint64_t> counts = r.u64s("camera.counts", pixels_);
    if (counts.size() != pixels_)
        r.fail("camera.counts", "not one count per pixel");
    for (std::size_t p = 0; p < pixels_; ++p) {
        if (counts[p] < floor_ || counts[p] > kMaxPerPixel)
            r.fail("camera.counts", "a count outside the floor and 4096");
        counts_[p] = static_cast<std::uint32_t>(counts[p]);
    }
    sigma_ = r.f64s("camera.sigma", pixels_, true);
    for (const double v : sigma_)
        if (!(v >= 0.0) || !std::isfinite(v))
            r.fail("camera.sigma", "a negative or undefined deviation");
    raysPerSample_ = r.f64("camera.rays_per_sample");
    if (!(raysPerSample_ >= 1.0) || !std::isfinite(raysPerSample_))
        r.fail("camera.rays_per_sample", "below one or undefined");
    pilotPass_ = 2;
    lastLight_ = r.f64s("camera.last_light", pixels_);
    if (!lastLight_.empty() && lastLight_.size() != pixels_)
        r.fail("camera.last_light", "not one value per pixel");
    lastWeight_ = r.f64("camera.last_weight");
    lightVarSum_ = r.f64("camera.light_var_sum");
    if (!(lightVarSum_ >= 0.0) || !(lastWeight_ >= 0.0))
        r.fail("camera.light_var_sum", "negative or undefined");
    pairs_ = r.u64("camera.pairs");
    samplesTotal_ = r.u64("camera.samples_total");
    errorShare_ = r.f64("camera.error_share");
}

}  // namespace fen
