// raster.h — an 8-bit RGB picture to draw on (false-colour pictures, their legends and text),
// row 0 at the top, 3 bytes per pixel, row-major: the layout io/output_files.h's encodePng takes.
//
// Every drawing call clips to the picture: a rectangle or a pixel outside it draws nothing there,
// never out of bounds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace fen {

struct Rgb8 {
    unsigned char r = 0, g = 0, b = 0;
    bool operator==(const Rgb8& o) const { return r == o.r && g == o.g && b == o.b; }
    bool operator!=(const Rgb8& o) const { return !(*this == o); }
};

struct Raster {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;  // 3 bytes per pixel

    Raster() = default;
    Raster(int w, int h, Rgb8 fill) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3)
    {
        fillRect(0, 0, w, h, fill);
    }
    void set(int x, int y, Rgb8 c)
    {
        if (x < 0 || y < 0 || x >= width || y >= height)
            return;
        unsigned char* p = rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x);
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
    }
    Rgb8 get(int x, int y) const
    {
        const unsigned char* p = rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x);
        return {p[0], p[1], p[2]};
    }
    // Pixels x0 <= x < x1, y0 <= y < y1.
    void fillRect(int x0, int y0, int x1, int y1, Rgb8 c)
    {
        x0 = std::max(x0, 0);
        y0 = std::max(y0, 0);
        x1 = std::min(x1, width);
        y1 = std::min(y1, height);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                set(x, y, c);
    }
};

}  // namespace fen
