// png_preview.cpp — tone mapping and the error map, encoded as PNG (png_preview.h).
#include "io/png_preview.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/output_files.h"

namespace fen {

namespace {

unsigned char encodeSrgb(double v)
{
    v = std::clamp(v, 0.0, 1.0);
    const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(255.0 * s));
}

}  // namespace

Preview pngPreview(const Image& image, double meanLuminance, double exposure)
{
    if (!(exposure > 0.0))
        exposure = meanLuminance > 0.0 ? 0.18 / meanLuminance : 1.0;
    std::vector<unsigned char> out(image.pixels() * 3);
    for (std::size_t i = 0; i < image.pixels(); ++i) {
        const double y = image.luminance(i) * exposure;
        const double scale = y > 0.0 ? (y / (1.0 + y)) / y : 0.0;
        for (int c = 0; c < 3; ++c)
            out[3 * i + c] = encodeSrgb(image.rgb[3 * i + c] * exposure * scale);
    }
    return {encodePng(image.width, image.height, 3, out), exposure};
}

std::string errorPng(const Image& image, const Image& reference, double scale)
{
    std::vector<unsigned char> out(image.pixels());
    const double s = scale > 0.0 ? scale : 1.0;
    for (std::size_t i = 0; i < image.pixels(); ++i) {
        const double e = std::fabs(image.luminance(i) - reference.luminance(i)) / s;
        const double g = e > 0.0 ? 1.0 + std::log10(e) / 3.0 : 0.0;
        out[i] = static_cast<unsigned char>(std::lround(255.0 * std::clamp(g, 0.0, 1.0)));
    }
    return encodePng(image.width, image.height, 1, out);
}

}  // namespace fen
