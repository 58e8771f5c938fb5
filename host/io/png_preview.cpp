// png_preview.cpp — tone mapping and PNG encoding (png_preview.h), via stb_image_write.
#include "io/png_preview.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <stb/stb_image_write.h>

#include "util/error.h"

namespace fen {

namespace {

unsigned char encodeSrgb(double v)
{
    v = std::clamp(v, 0.0, 1.0);
    const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(255.0 * s));
}

}  // namespace

double writePngPreview(const std::string& path, const Image& image, double meanLuminance,
                       double exposure)
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
    if (!stbi_write_png(path.c_str(), image.width, image.height, 3, out.data(), image.width * 3))
        throw Error(cat(path, ": cannot write PNG"));
    return exposure;
}

}  // namespace fen
