// false_color_test.cpp — false-colour pictures (io/false_color.h) and their font
// (io/bitmap_font.h): the map rises in luminance and clamps, scales fitted to known data, compact
// labels, and pictures decoded back from their PNG bytes: each cell's pixels are the map's colour
// for its value, neighbours tile, no data is dark grey, the legend stands beside the picture.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "io/bitmap_font.h"
#include "io/false_color.h"
#include "util/error.h"

namespace fen {
namespace {

double srgbToLinear(unsigned char c)
{
    const double s = c / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

double relativeLuminance(Rgb8 c)
{
    return 0.2126 * srgbToLinear(c.r) + 0.7152 * srgbToLinear(c.g) + 0.0722 * srgbToLinear(c.b);
}

Raster decodePng(const std::string& png)
{
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()), static_cast<int>(png.size()), &w,
                              &h, &channels, 3),
        stbi_image_free);
    EXPECT_NE(pixels, nullptr) << "not a PNG";
    Raster r;
    if (!pixels)
        return r;
    r.width = w;
    r.height = h;
    r.rgb.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * h * 3);
    return r;
}

// The block of colour c whose top-left pixel is the leftmost (then topmost) pixel of that colour:
// x, y, width (run along its top row), height (run down its left column). Empty if c is absent.
struct Block {
    int x = -1, y = -1, width = 0, height = 0;
};
Block leftmostBlock(const Raster& r, Rgb8 c)
{
    Block b;
    for (int x = 0; x < r.width && b.x < 0; ++x)
        for (int y = 0; y < r.height; ++y)
            if (r.get(x, y) == c) {
                b.x = x;
                b.y = y;
                break;
            }
    if (b.x < 0)
        return b;
    while (b.x + b.width < r.width && r.get(b.x + b.width, b.y) == c)
        ++b.width;
    while (b.y + b.height < r.height && r.get(b.x, b.y + b.height) == c)
        ++b.height;
    return b;
}

bool blockIsUniform(const Raster& r, const Block& b, Rgb8 c)
{
    for (int y = b.y; y < b.y + b.height; ++y)
        for (int x = b.x; x < b.x + b.width; ++x)
            if (r.get(x, y) != c)
                return false;
    return true;
}

int countColour(const Raster& r, Rgb8 c, int x0, int y0, int x1, int y1)
{
    int n = 0;
    for (int y = std::max(y0, 0); y < std::min(y1, r.height); ++y)
        for (int x = std::max(x0, 0); x < std::min(x1, r.width); ++x)
            n += r.get(x, y) == c;
    return n;
}

bool isInk(Rgb8 c) { return c.r < 60 && c.g < 60 && c.b < 60 && c != kNoDataColor; }

TEST(FalseColor, MapRisesInLuminanceAndClamps)
{
    // Strictly brighter from each hundredth of the scale to the next (a legend has at most 100
    // steps); in between, only the rounding to 8 bits (< 0.0005 in luminance) may reverse it.
    for (int i = 0; i < 100; ++i)
        EXPECT_LT(relativeLuminance(colorMap(i / 100.0)), relativeLuminance(colorMap((i + 1) / 100.0))) << i;
    double brightest = -1.0;
    for (int i = 0; i <= 10000; ++i) {
        const double y = relativeLuminance(colorMap(i / 10000.0));
        EXPECT_GT(y, brightest - 5e-4) << "t = " << i / 10000.0;
        brightest = std::max(brightest, y);
    }
    EXPECT_GT(relativeLuminance(colorMap(1.0)), 20.0 * relativeLuminance(colorMap(0.0)));

    EXPECT_EQ(colorMap(-3.0), colorMap(0.0));
    EXPECT_EQ(colorMap(7.0), colorMap(1.0));
    FalseColorScale s;
    s.min = 100.0;
    s.max = 500.0;
    EXPECT_EQ(falseColor(-20.0, s), colorMap(0.0));
    EXPECT_EQ(falseColor(1e9, s), colorMap(1.0));
    EXPECT_EQ(falseColor(INFINITY, s), colorMap(1.0));
    EXPECT_EQ(falseColor(300.0, s), colorMap(0.5));
    EXPECT_DOUBLE_EQ(scalePosition(200.0, s), 0.25);
    s.log = true;
    s.min = 1.0;
    s.max = 1e4;
    EXPECT_DOUBLE_EQ(scalePosition(100.0, s), 0.5);
    EXPECT_EQ(falseColor(0.0, s), colorMap(0.0));
    EXPECT_EQ(falseColor(0.01, s), colorMap(0.0));
    // no data: a colour the map never takes
    EXPECT_EQ(falseColor(NAN, s), kNoDataColor);
    for (int i = 0; i <= 1000; ++i)
        EXPECT_NE(colorMap(i / 1000.0), kNoDataColor);
}

TEST(FalseColor, AutoScaleLinearRoundsAboveThe99thPercentile)
{
    std::vector<double> v;
    for (int i = 1; i <= 470; ++i)
        v.push_back(i);
    v.push_back(NAN);
    v.push_back(INFINITY);
    FalseColorScale s = autoScale(v, false, "lux");
    EXPECT_FALSE(s.log);
    EXPECT_EQ(s.unit, "lux");
    EXPECT_EQ(s.steps, 8);
    EXPECT_EQ(s.min, 0.0);
    EXPECT_DOUBLE_EQ(s.max, 480.0);  // p99 = 466; 466 / 8 = 58.25 -> steps of 60
    EXPECT_DOUBLE_EQ(autoScale(v, false, "lux", 5).max, 500.0);  // 93.2 -> 100

    // a few bright outliers (the sun patch) do not set the scale
    std::vector<double> room(1000, 100.0);
    for (int i = 0; i < 5; ++i)
        room.push_back(1e6);
    EXPECT_DOUBLE_EQ(autoScale(room, false, "lux").max, 120.0);  // 100 / 8 = 12.5 -> 15

    EXPECT_DOUBLE_EQ(autoScale({}, false, "lux").max, 1.2);  // nothing to fit: 0 .. about 1
    EXPECT_DOUBLE_EQ(autoScale({0.0, 0.0}, false, "lux").max, 1.2);
}

TEST(FalseColor, AutoScaleLogSpansWholeDecades)
{
    std::vector<double> v;
    for (int i = 0; i <= 100; ++i)
        v.push_back(3.0 * std::pow(4000.0 / 3.0, i / 100.0));  // 3 .. 4000
    v.push_back(0.0);
    v.push_back(-5.0);
    v.push_back(NAN);
    FalseColorScale s = autoScale(v, true, "cd/m²");
    EXPECT_TRUE(s.log);
    EXPECT_DOUBLE_EQ(s.min, 1.0);
    EXPECT_DOUBLE_EQ(s.max, 1e4);
    s = autoScale(std::vector<double>(10, 50.0), true, "cd/m²");
    EXPECT_DOUBLE_EQ(s.min, 10.0);
    EXPECT_DOUBLE_EQ(s.max, 100.0);
    s = autoScale(std::vector<double>(10, 100.0), true, "cd/m²");  // a decade exactly: one decade
    EXPECT_DOUBLE_EQ(s.min, 100.0);
    EXPECT_DOUBLE_EQ(s.max, 1000.0);
    s = autoScale({0.0, -1.0}, true, "cd/m²");
    EXPECT_DOUBLE_EQ(s.min, 1.0);
    EXPECT_DOUBLE_EQ(s.max, 10.0);
}

TEST(FalseColor, TicksAndCompactLabels)
{
    FalseColorScale s;
    s.min = 0.0;
    s.max = 480.0;
    const std::vector<double> linear = scaleTicks(s);
    ASSERT_EQ(linear.size(), 9u);
    for (int i = 0; i <= 8; ++i)
        EXPECT_DOUBLE_EQ(linear[static_cast<std::size_t>(i)], 60.0 * i);
    s.log = true;
    s.min = 1.0;
    s.max = 1e4;
    s.steps = 4;
    const std::vector<double> log = scaleTicks(s);
    ASSERT_EQ(log.size(), 5u);
    for (int i = 0; i <= 4; ++i)
        EXPECT_NEAR(log[static_cast<std::size_t>(i)], std::pow(10.0, i), 1e-9 * std::pow(10.0, i));

    EXPECT_EQ(compactNumber(0.5), "0.5");
    EXPECT_EQ(compactNumber(12), "12");
    EXPECT_EQ(compactNumber(350), "350");
    EXPECT_EQ(compactNumber(1200), "1.2k");
    EXPECT_EQ(compactNumber(15000), "15k");
    EXPECT_EQ(compactNumber(62.5), "62.5");
    EXPECT_EQ(compactNumber(0.15 * 8), "1.2");
    EXPECT_EQ(compactNumber(999.7), "1k");
    EXPECT_EQ(compactNumber(1234567), "1.23M");
    EXPECT_EQ(compactNumber(2.5e9), "2.5G");
    EXPECT_EQ(compactNumber(0), "0");
    EXPECT_EQ(compactNumber(-3), "-3");
    EXPECT_EQ(compactNumber(3162.28, 2), "3.2k");
    EXPECT_EQ(compactNumber(0.0125), "0.0125");
}

TEST(FalseColor, BadScalesAndSizesAreErrors)
{
    FalseColorScale s;
    s.min = 5.0;
    s.max = 5.0;
    EXPECT_THROW(checkScale(s), Error);
    s.max = 10.0;
    EXPECT_NO_THROW(checkScale(s));
    s.min = 0.0;
    s.log = true;
    EXPECT_THROW(checkScale(s), Error);
    s.log = false;
    s.steps = 0;
    EXPECT_THROW(checkScale(s), Error);
    s.steps = 8;
    EXPECT_THROW(falseColorImagePng({1.0, 2.0, 3.0}, 2, 2, s), Error);
    EXPECT_THROW(falseColorPlanPng({}, s), Error);
    EXPECT_THROW(falseColorPlanPng({{0.0, 0.0, 0.0, 1.0}}, s), Error);  // a cell of size 0
    // 2 px for a 1 mm cell over 100 m: too many pixels, said, not attempted
    EXPECT_THROW(falseColorPlanPng({{0.0, 0.0, 0.001, 1.0}, {100.0, 0.0, 0.001, 1.0}}, s), Error);
}

TEST(FalseColor, PlanCellsAreTheirValuesColourWithALegendBeside)
{
    FalseColorScale s;
    s.min = 0.0;
    s.max = 300.0;
    s.steps = 3;
    s.unit = "lux";
    s.title = "illuminance, desk";
    // two 1 m cells side by side, a third (no data) below the first
    const std::vector<PlanCell> cells = {{0.5, 0.5, 1.0, 40.0}, {1.5, 0.5, 1.0, 290.0}, {0.5, 1.5, 1.0, NAN}};
    const Raster png = decodePng(falseColorPlanPng(cells, s, "mean 165 lux  min/mean 0.24"));
    ASSERT_GT(png.width, 0);

    const Block a = leftmostBlock(png, falseColor(40.0, s));
    const Block b = leftmostBlock(png, falseColor(290.0, s));
    const Block none = leftmostBlock(png, kNoDataColor);
    // 2 m across -> 800 px: 400 px a metre
    EXPECT_EQ(a.width, 400);
    EXPECT_EQ(a.height, 400);
    EXPECT_TRUE(blockIsUniform(png, a, falseColor(40.0, s)));
    EXPECT_EQ(b.x, a.x + 400);  // neighbours tile: no gap, no overlap
    EXPECT_EQ(b.y, a.y);
    EXPECT_EQ(b.width, 400);
    EXPECT_EQ(b.height, 400);
    EXPECT_EQ(none.x, a.x);
    EXPECT_EQ(none.y, a.y + 400);
    EXPECT_EQ(none.width, 400);
    EXPECT_EQ(none.height, 400);
    EXPECT_EQ(countColour(png, kNoDataColor, 0, 0, png.width, png.height), 400 * 400);
    // where no cell is: background
    EXPECT_EQ(png.get(b.x + 200, b.y + 600), (Rgb8{255, 255, 255}));

    // the title and label above, text (ink) only there and in the legend
    EXPECT_GT(countColour(png, Rgb8{20, 20, 20}, 0, 0, png.width, a.y), 200);
    // the legend: right of the plan, the bar with both ends of the map, the labels in ink
    const int right = b.x + b.width;
    EXPECT_GE(png.width, right + 60);
    EXPECT_GT(countColour(png, colorMap(1.0), right, 0, png.width, png.height), 10);
    EXPECT_GT(countColour(png, colorMap(0.0), right, 0, png.width, png.height), 10);
    int ink = 0;
    for (int y = a.y; y < png.height; ++y)
        for (int x = right; x < png.width; ++x)
            ink += isInk(png.get(x, y));
    EXPECT_GT(ink, 300);
}

TEST(FalseColor, ImagePixelsAreBlocksAndNoDataIsDarkGrey)
{
    FalseColorScale s;
    s.log = true;
    s.min = 1.0;
    s.max = 1e4;
    s.steps = 4;
    s.unit = "cd/m²";
    const std::vector<double> y = {NAN, 1.0, 10.0, 100.0, 1000.0, 1e5};  // 3 x 2
    const Raster png = decodePng(falseColorImagePng(y, 3, 2, s));
    const Block none = leftmostBlock(png, kNoDataColor);
    EXPECT_EQ(none.width, 100);  // 3 px across: enlarged 100 times, to 300
    EXPECT_EQ(none.height, 100);
    EXPECT_EQ(countColour(png, kNoDataColor, 0, 0, png.width, png.height), 100 * 100);
    // row 1: 100, 1000 and 1e5 (clamped to the top)
    const Rgb8 mid = falseColor(100.0, s), top = colorMap(1.0);
    EXPECT_EQ(mid, colorMap(0.5));
    EXPECT_EQ(png.get(none.x + 50, none.y + 150), mid);
    EXPECT_EQ(png.get(none.x + 150, none.y + 150), falseColor(1000.0, s));
    EXPECT_EQ(png.get(none.x + 250, none.y + 150), top);
    EXPECT_EQ(png.get(none.x + 250, none.y + 50), falseColor(10.0, s));
    EXPECT_GE(png.width, none.x + 300 + 60);  // the legend beside
    // a larger image is drawn 1:1
    const Raster big = decodePng(falseColorImagePng(std::vector<double>(400 * 10, 50.0), 400, 10, s));
    const Block all = leftmostBlock(big, falseColor(50.0, s));
    EXPECT_EQ(all.width, 400);
    EXPECT_EQ(all.height, 10);
}

TEST(BitmapFont, EveryRequiredCharacterHasItsOwnGlyph)
{
    std::u32string required = U"0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.,-+%/:()=\u00b2 ";
    std::set<std::vector<bool>> shapes;
    for (const char32_t c : required) {
        EXPECT_TRUE(hasGlyph(c)) << static_cast<unsigned>(c);
        std::vector<bool> shape;
        for (int row = 0; row < kGlyphRows; ++row)
            for (int column = 0; column < kGlyphColumns; ++column)
                shape.push_back(glyphPixel(c, column, row));
        const bool blank = std::find(shape.begin(), shape.end(), true) == shape.end();
        EXPECT_EQ(blank, c == U' ') << static_cast<unsigned>(c);
        EXPECT_TRUE(shapes.insert(shape).second) << "two characters look alike: " << static_cast<unsigned>(c);
    }
    EXPECT_FALSE(hasGlyph(U'\u20ac'));
    EXPECT_TRUE(glyphPixel(U'\u20ac', 0, 0));  // drawn as a box
    EXPECT_EQ(textWidth("", 2), 0);
    EXPECT_EQ(textWidth("ab", 2), 22);
    EXPECT_EQ(textWidth("cd/m\xc2\xb2", 1), 29);  // ² is one character
    EXPECT_EQ(textWidth("\xff\xc2", 1), 11);      // malformed bytes: one box each

    Raster r(40, 20, {255, 255, 255});
    drawText(r, 1, 1, "1", {0, 0, 0}, 2);
    int set = 0;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 40; ++x)
            set += r.get(x, y) == Rgb8{0, 0, 0};
    int pixels = 0;
    for (int row = 0; row < kGlyphRows; ++row)
        for (int column = 0; column < kGlyphColumns; ++column)
            pixels += glyphPixel(U'1', column, row);
    EXPECT_EQ(set, 4 * pixels);  // each glyph pixel a 2 x 2 square
    drawText(r, 35, 15, "clipped at the edge", {0, 0, 0}, 3);  // never out of bounds
}

}  // namespace
}  // namespace fen
