// png_preview.h — an 8-bit sRGB preview of a linear image, for looking at, never for measuring.
//
// Exposure: the ROI's mean luminance is mapped to 0.18 (mid-grey) unless `exposure` is given
// (multiplier on linear values); then Reinhard's x / (1 + x) on luminance keeps highlights
// (sunlit patches are 10-100x the room) and the sRGB transfer curve encodes.
#pragma once

#include <string>
#include <vector>

#include "io/image.h"

namespace fen {

struct Preview {
    std::string png;        // the encoded file
    double exposure = 0.0;  // the multiplier used
};
Preview pngPreview(const Image& image, double meanLuminance, double exposure = 0.0);

// An error map against a reference, 8-bit grey PNG: e = |Y - Y_ref| / scale per pixel, written as
// 255 (1 + log10(e) / 3) clamped to [0, 255] -- black at e <= 10^-3, white at e >= 1. The scale is
// the reference's mean luminance over the region the caller chooses, so dark regions do not blow
// up. For looking at (scripts/compare.py colours it), never for measuring.
std::string errorPng(const Image& image, const Image& reference, double scale);

}  // namespace fen
