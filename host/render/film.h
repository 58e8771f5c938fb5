// film.h — where a render's light lands (DESIGN.md §2, §5): the device's 128-bit fixed-point pixel
// accumulators and the camera pass's image, and on the host the batch images folded into a
// running mean, each pixel's standard error and the regions' batch means.
//
// Fixed point (kernels/lib/accumulate.h): a pixel channel holds round(value * scale) as two
// 64-bit words, scale = 2^kPixelFixedPointBits per reference luminance (the brightest plausible
// diffuse luminance of the scene): contributions down to 1e-12 of it keep 1e-6 relative precision,
// and 2^127 units hold any plausible sum. Integer sums do not depend on the order of the atomic
// adds, so an image is bit-identical whatever the scheduling.
// The camera pass's part of a batch is kept apart (addCamera): each pixel's is the mean of all its
// camera samples over the batches, sum_b n_b m_b / sum_b n_b, since their counts n_b vary from
// batch to batch and pixel to pixel (render/camera_sampler.h: unbiased because the counts never
// depend on the samples they weigh), and its variance is that of the samples over their count.
// Batches are independent estimates (or, with a learning strategy, unbiased given everything
// before them), so the spread of a pixel's batch values gives its standard error. A batch may
// carry a weight w_b in proportion to its expected precision (a learning strategy's early
// batches are noisier): the image is sum w_b I_b / W, W = sum w_b, and with Var(I_b) = s^2 / w_b
// (each pixel's own s^2, the same relative precisions everywhere) s^2 is estimated by
// sum w_b (I_b - mean)^2 / (B - 1), so the mean's standard error is sqrt(s^2 / W). Equal weights
// give the plain mean and the plain batch-spread estimate.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "cl/context.h"
#include "io/image.h"
#include "render/image_stats.h"
#include "team/summed_buffer.h"

namespace fen {

class Film {
public:
    static constexpr int kPixelFixedPointBits = 40;
    static constexpr int kWordsPerPixel = 6;  // (low, high) for r, g, b

    Film(ocl::Context& ctx, int width, int height, double referenceLuminance_cd_m2);

    int width() const { return width_; }
    int height() const { return height_; }
    std::size_t pixels() const { return static_cast<std::size_t>(width_) * height_; }
    float fixedScale() const { return fixedScale_; }
    cl::Buffer& accumulators() { return accum_; }
    // The accumulators as a team sums them (team/shared_sums.h): per pixel, three 128-bit sums.
    SummedBuffer summed() const { return {&accum_, pixels(), {2, 2, 2}}; }
    // The camera pass's output, per pixel: rgb mean of its samples, w the sum of their luminances'
    // squared deviations (kernels/camera_pass.cl).
    cl::Buffer& cameraImage() { return camera_; }
    // The camera pass's samples per pixel (uint each; 1 until set): what it traces next batch.
    cl::Buffer& cameraSamples() { return cameraSamples_; }
    void setCameraSamples(const std::vector<std::uint32_t>& perPixel);

    // Zeroes the accumulators (enqueued).
    void clear();
    // The batch's image, rgb per pixel: accumulators / (scale x paths) + the camera pass; with
    // `camera`, the light-traced part alone, and the camera pass's output apart as it is on the
    // device (4 floats per pixel, above).
    std::vector<double> read(std::uint64_t paths, std::vector<float>* camera = nullptr);
    std::vector<float> readCamera();
    // Sets the camera pass's output (4 floats a pixel): a team's members take the root's.
    void writeCamera(const std::vector<float>& camera);

private:
    ocl::Context& ctx_;
    int width_, height_;
    float fixedScale_;
    cl::Buffer accum_, camera_, cameraSamples_;
};

class StateReader;
class StateWriter;

// Batch images in; mean image, per-pixel standard error of luminance and ROI batch means out.
class BatchStatistics {
public:
    BatchStatistics(int width, int height, std::vector<Roi> rois);
    // A batch's image (with addCamera: its light-traced part alone), of weight `weight`.
    void add(const std::vector<double>& rgb, double weight = 1.0);
    // The batch's camera pass: its output (Film::cameraImage, 4 floats a pixel) and its samples
    // per pixel.
    void addCamera(const std::vector<float>& camera, const std::vector<std::uint32_t>& counts);
    int batches() const { return batches_; }
    Image mean() const;
    std::vector<double> stdErrLuminance() const;
    // roiBatchMeans()[k][b]: mean luminance of ROI k in batch b; weights()[b]: batch b's weight.
    const std::vector<std::vector<double>>& roiBatchMeans() const { return roiMeans_; }
    const std::vector<double>& weights() const { return weights_; }
    // ROI k's camera-pass part: its mean luminance and that mean's variance (each pixel's samples
    // are independent of the others'); (0, 0) with no camera part kept apart.
    std::pair<double, double> roiCamera(std::size_t k) const;
    // The sums so far, exactly (render/checkpoint.h); load() requires the same image and ROIs.
    void save(StateWriter& w) const;
    void load(StateReader& r);

private:
    int width_, height_;
    std::vector<Roi> rois_;
    // the camera part's variance of one sample's luminance at pixel p (0 below two samples)
    double cameraSampleVar(std::size_t p) const;
    std::vector<double> sum_, sumY2_;  // weighted
    // the camera part, per pixel: sum n m (rgb), sum n, and for its luminance the within-batch
    // squared deviations, sum n m_Y, sum n m_Y^2
    std::vector<double> camSum_, camN_, camM2_, camY1_, camY2_;
    std::vector<std::vector<double>> roiMeans_;
    std::vector<double> weights_;
    double weight_ = 0.0;
    int batches_ = 0;
};

}  // namespace fen
