// image_stats.h — the figures a render reports for a region of interest (DESIGN.md §5; the
// paper's tables): mean luminance, RMS of pixel luminances around it, the batch-noise estimate,
// and, against a reference image, RMSE and relative MSE.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/image.h"

namespace fen {

// Pixels x0 <= x < x1, y0 <= y < y1 (DESIGN.md §6).
struct Roi {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    std::size_t pixels() const { return static_cast<std::size_t>(x1 - x0) * (y1 - y0); }
};

// "x0,y0,x1,y1", or the whole image when spec is empty. Errors name `option`.
Roi parseRoi(const std::string& spec, int width, int height, const std::string& option = "--roi");

struct RoiStats {
    std::size_t pixels = 0;
    double meanLuminance_cd_m2 = 0.0;
    double rmsLuminance_cd_m2 = 0.0;    // sqrt(mean((Y - mean)^2)) over the ROI's pixels
    // sqrt of the mean over the ROI of each pixel's squared standard error: mean(SE^2) estimates
    // the mean per-pixel variance without bias, so this estimates the RMSE against the true image.
    // (A plain mean of SE fails where contributions are sparse: a pixel hit in one batch of 16
    // gets SE about equal to its value, whatever the method -- measured on the inner room.)
    double noiseStdErr_cd_m2 = 0.0;
    // The share of sum(SE^2) that the noisiest 1 % of the ROI's pixels hold (at least one pixel):
    // about 0.01 for noise spread evenly, near 1 when a few fireflies -- single paths of large
    // weight -- make up the noise (measured on the house: docs/results/house.md).
    double noiseTop1Share = 0.0;
    std::optional<double> rmse_cd_m2;   // vs reference: sqrt(mean((Y - Yref)^2))
    std::optional<double> relMse;       // vs reference: mean((Y - Yref)^2 / (Yref^2 + 0.01))
};

// stdErr: per-pixel standard error of the luminance (may be empty); reference may be null.
RoiStats roiStats(const Image& image, const std::vector<double>& stdErr, const Image* reference,
                  const Roi& roi);

}  // namespace fen
