// image.h — an RGB float image, row 0 at the top (DESIGN.md §6), linear Rec.709 primaries;
// luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (DESIGN.md §1).
#pragma once

#include <vector>

namespace fen {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 floats per pixel, row-major

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.0f) {}
    std::size_t pixels() const { return static_cast<std::size_t>(width) * height; }
    float* at(int x, int y) { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
    const float* at(int x, int y) const
    {
        return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x);
    }
    double luminance(std::size_t pixel) const
    {
        const float* p = rgb.data() + 3 * pixel;
        return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    }
};

inline double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

}  // namespace fen
