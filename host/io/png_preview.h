// png_preview.h — an 8-bit sRGB preview of a linear image, for looking at, never for measuring.
//
// Exposure: the ROI's mean luminance is mapped to 0.18 (mid-grey) unless `exposure` is given
// (multiplier on linear values); then Reinhard's x / (1 + x) on luminance keeps highlights
// (sunlit patches are 10-100x the room) and the sRGB transfer curve encodes.
#pragma once

#include <string>

#include "io/image.h"

namespace fen {

// Returns the exposure multiplier used.
double writePngPreview(const std::string& path, const Image& image, double meanLuminance,
                       double exposure = 0.0);

}  // namespace fen
