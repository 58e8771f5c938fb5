// camera_setup.cpp — image size rule and DevCamera (camera_setup.h).
#include "render/camera_setup.h"

#include <cmath>

#include "util/error.h"
#include "util/float4.h"

namespace fen {

void resolveImageSize(const CameraSpec& cam, int width, int height, int* outWidth, int* outHeight)
{
    const int kMax = 16384;
    if (width < 0 || width > kMax)
        throw Error(cat("--width ", width, " must be in 1..", kMax));
    if (height < 0 || height > kMax)
        throw Error(cat("--height ", height, " must be in 1..", kMax));
    const double aspect = cam.aspectRatio > 0.0 ? cam.aspectRatio : 4.0 / 3.0;
    if (width == 0 && height == 0)
        width = 640;
    if (width == 0)
        width = std::max(1, static_cast<int>(std::lround(height * aspect)));
    if (height == 0)
        height = std::max(1, static_cast<int>(std::lround(width / aspect)));
    if (width > kMax || height > kMax)
        throw Error(cat("image size ", width, " x ", height, " exceeds ", kMax));
    *outWidth = width;
    *outHeight = height;
}

dev::DevCamera makeDevCamera(const CameraSpec& cam, int width, int height)
{
    dev::DevCamera c{};
    const double tanY = std::tan(0.5 * cam.yfovRad);
    const double tanX = tanY * width / height;
    const double pixelArea = (2.0 * tanX / width) * (2.0 * tanY / height);
    c.position = toFloat4(cam.position, 0.0);
    c.forward = toFloat4(cam.forward, tanX);
    c.right = toFloat4(cam.right, tanY);
    c.up = toFloat4(cam.up, pixelArea);
    c.width = static_cast<std::uint32_t>(width);
    c.height = static_cast<std::uint32_t>(height);
    return c;
}

}  // namespace fen
