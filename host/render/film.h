// film.h — where a render's light lands (DESIGN.md §2, §5): the device's 128-bit fixed-point pixel
// accumulators and the camera pass's image, and on the host the batch images folded into a
// running mean, each pixel's standard error and the regions' batch means.
//
// Fixed point (kernels/lib/accumulate.h): a pixel channel holds round(value * scale) as two
// 64-bit words, scale = 2^kPixelFixedPointBits per reference luminance (the brightest plausible
// diffuse luminance of the scene): contributions down to 1e-12 of it keep 1e-6 relative precision,
// and 2^127 units hold any plausible sum. Integer sums do not depend on the order of the atomic
// adds, so an image is bit-identical whatever the scheduling.
// Batches are independent estimates (or, with a learning strategy, unbiased given everything
// before them), so the spread of a pixel's batch values gives its standard error. A batch may
// carry a weight w_b in proportion to its expected precision (a learning strategy's early
// batches are noisier): the image is sum w_b I_b / W, W = sum w_b, and with Var(I_b) = s^2 / w_b
// (each pixel's own s^2, the same relative precisions everywhere) s^2 is estimated by
// sum w_b (I_b - mean)^2 / (B - 1), so the mean's standard error is sqrt(s^2 / W). Equal weights
// give the plain mean and the plain batch-spread estimate.
#pragma once

#include <cstdint>
#include <vector>

#include "cl/context.h"
#include "io/image.h"
#include "render/image_stats.h"

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
    cl::Buffer& cameraImage() { return camera_; }

    // Zeroes the accumulators (enqueued).
    void clear();
    // The batch's image, rgb per pixel: accumulators / (scale x paths) + the camera pass.
    std::vector<double> read(std::uint64_t paths);

private:
    ocl::Context& ctx_;
    int width_, height_;
    float fixedScale_;
    cl::Buffer accum_, camera_;
};

class StateReader;
class StateWriter;

// Batch images in; mean image, per-pixel standard error of luminance and ROI batch means out.
class BatchStatistics {
public:
    BatchStatistics(int width, int height, std::vector<Roi> rois);
    void add(const std::vector<double>& rgb, double weight = 1.0);
    int batches() const { return batches_; }
    Image mean() const;
    std::vector<double> stdErrLuminance() const;
    // roiBatchMeans()[k][b]: mean luminance of ROI k in batch b; weights()[b]: batch b's weight.
    const std::vector<std::vector<double>>& roiBatchMeans() const { return roiMeans_; }
    const std::vector<double>& weights() const { return weights_; }
    // The sums so far, exactly (render/checkpoint.h); load() requires the same image and ROIs.
    void save(StateWriter& w) const;
    void load(StateReader& r);

private:
    int width_, height_;
    std::vector<Roi> rois_;
    std::vector<double> sum_, sumY2_;  // weighted
    std::vector<std::vector<double>> roiMeans_;
    std::vector<double> weights_;
    double weight_ = 0.0;
    int batches_ = 0;
};

}  // namespace fen
