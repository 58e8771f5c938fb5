// camera_sampler.h — how many camera-pass samples each pixel gets per batch (DESIGN.md §6.1).
//
// The camera pass (kernels/camera_pass.cl) traces what the pinhole sees of the sky directly. With
// one sample per pixel per batch, a pixel that straddles a window's edge or a mullion (half sky at
// thousands of cd/m^2, half frame at none) keeps the noise of a dozen samples however long the light
// tracer runs, and such pixels held most of a daylit room's image error (docs/results/guiding.md).
// Balanced mode gives each pixel samples in proportion to its own per-sample standard deviation,
// with the total chosen so that the camera pass's share of the batch's error equals its share of
// the batch's rays -- the optimum of error x time when both parts' errors fall as 1/effort:
//   minimise  sum_p V_p / n_p + V_L T_L / (T - c sum_p n_p)   =>   n_p = sigma_p sqrt(T_L / (c V_L))
// with sigma_p^2 the per-sample variance of pixel p's camera luminance, c the camera rays per
// sample, T_L the light tracer's rays per batch and V_L its image variance per batch (summed over
// the pixels). Rays stand for time: counted, so the counts (and so the image) are a function of the
// seed and settings alone, never of the machine's load.
// Estimates: sigma_p from a pilot before the first batch (camera samples of their own, never in the
// image): kPilotSamples per pixel, then kPilotRefineSamples more for every pixel next to one whose
// samples varied -- an edge is a line, and a pixel on it whose first samples all agreed (a pixel
// 80 % sky does so with probability 0.8^8 = 0.17) would otherwise keep its one sample a batch;
// after both, 0.8^32 = 0.0008; V_L from consecutive batches' light-traced images,
// E[(L_b - L_{b-1})^2] = s^2 (1/w_b + 1/w_{b-1}) per pixel (film.h: Var(L_b) = s^2 / w_b); c from
// the pilot's rays per sample. The first two batches, before V_L is known, take the floor.
// Unbiased, with the camera part weighed by its samples: the film (film.h) averages each pixel's
// camera samples over all batches, sum_b n_b m_b / sum_b n_b. That is unbiased only if the counts
// do not depend on the samples they weigh, which is why the counts come from the pilot and the
// light tracer alone and never from the counted camera samples (which would make a batch that
// happened to vary ask for more samples later, and so weigh less than its share).
// Invariants: every pixel gets at least `floor` samples a batch (no pixel left to chance); at most
// kMaxPerPixel; the camera pass never traces more rays than the light tracer did in the last batch.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fen {

class StateReader;
class StateWriter;

enum class CameraPassMode { Fixed, Balanced };
CameraPassMode parseCameraPassMode(const std::string& s);  // fixed | balanced
std::string cameraPassModeName(CameraPassMode m);

class CameraSampler {
public:
    static constexpr std::uint32_t kMaxPerPixel = 4096;
    // The pilot's samples per pixel: a sky sliver of an eighth of a pixel is seen with probability
    // 1 - (7/8)^8 = 0.66; 8 camera rays a pixel once cost about half a batch's camera pass at 16.
    static constexpr std::uint32_t kPilotSamples = 8;
    static constexpr std::uint32_t kPilotRefineSamples = 24;

    CameraSampler(std::size_t pixels, std::uint32_t floor, CameraPassMode mode);

    CameraPassMode mode() const { return mode_; }
    // Samples per pixel for the next camera pass (the pilot's while it is needed).
    const std::vector<std::uint32_t>& counts() const { return counts_; }
    std::uint64_t samplesPerBatch() const;

    // Balanced and not yet piloted: the next camera pass should be a pilot pass (counts() are its;
    // `pilotPass()` its number, 0 or 1, for its random numbers).
    bool needsPilot() const { return pilotPass_ < 2; }
    int pilotPass() const { return pilotPass_; }
    // A pilot pass's output (4 floats a pixel: rgb mean, luminance's squared deviations) and rays,
    // for an image `width` pixels wide (the neighbours of a pixel).
    void addPilot(const std::vector<float>& camera, std::uint64_t cameraRays, std::size_t width);

    // After a counted batch of weight `weight` (film.h): `lightLuminance` the light-traced part of
    // its image (cd/m^2 per pixel), `lightRays` its extension and shadow rays, `pathsShare` its
    // paths over a full batch's (below 1 for a render by time's last batch, render/last_batch.h).
    // Counts the batch's samples and sets the next batch's counts, planned for a full batch (fixed
    // mode: only counts; the rest is not read).
    void afterBatch(const std::vector<double>& lightLuminance, double weight, std::uint64_t lightRays,
                    double pathsShare = 1.0);

    // What it did, for the JSON: samples in all, the most a pixel gets in the next batch, pixels
    // above the floor, and the camera pass's predicted share of the next batch's image variance (0 when not
    // known yet; balanced mode only, since only its pilot measures the pixels' variance).
    std::uint64_t samplesTotal() const { return samplesTotal_; }
    std::uint32_t maxCount() const;
    std::uint64_t pixelsAboveFloor() const;
    double errorShare() const { return errorShare_; }

    void save(StateWriter& w) const;
    void load(StateReader& r);

private:
    void allocate(double weight, std::uint64_t lightRays);
    std::size_t pixels_;
    std::uint32_t floor_;
    CameraPassMode mode_;
    std::vector<std::uint32_t> counts_;
    std::vector<double> sigma_;          // per pixel: the pilot's standard deviation of a sample (cd/m^2)
    double raysPerSample_ = 1.0;         // the pilot's
    int pilotPass_ = 2;                  // the next pilot pass; 2: done (or none needed)
    std::vector<double> pilotN_, pilotY1_, pilotY2_, pilotM2_;  // the pilot's sums per pixel
    std::vector<double> lastLight_;      // the last batch's light-traced luminance
    double lastWeight_ = 0.0;
    double lightVarSum_ = 0.0;           // sum over batch pairs of the s^2 estimates (all pixels)
    std::uint64_t pairs_ = 0;
    std::uint64_t samplesTotal_ = 0;
    double errorShare_ = 0.0;
};

}  // namespace fen
