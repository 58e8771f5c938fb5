// false_color.cpp — the colour map, scales, and the false-colour pictures with their legend
// (false_color.h).
#include "io/false_color.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/bitmap_font.h"
#include "io/output_files.h"
#include "util/error.h"

namespace fen {

namespace {

// Viridis-like control points at t = 0, 1/8, ..., 1 (sRGB); interpolated linearly in between.
constexpr Rgb8 kMap[] = {{68, 1, 84},    {71, 45, 123},  {59, 82, 139},  {44, 114, 142}, {33, 145, 140},
                         {40, 174, 128}, {94, 201, 98},  {173, 220, 48}, {253, 231, 37}};
constexpr int kMapPoints = sizeof(kMap) / sizeof(kMap[0]);

constexpr Rgb8 kBackground{255, 255, 255};
constexpr Rgb8 kInk{20, 20, 20};
constexpr int kFontScale = 2;
constexpr int kLineHeight = kGlyphRows * kFontScale + 4;
constexpr int kCapHeight = kGlyphAscent * kFontScale;
constexpr int kMargin = 16;
constexpr int kLegendGap = 24;  // between the picture and the colour bar
constexpr int kBarWidth = 24;
constexpr int kTickLength = 6;
constexpr int kMinPictureSide = 300;  // images smaller than this are enlarged
constexpr double kPlanSide = 800.0;   // a plan's longer side, in pixels
constexpr int kMaxPictureSide = 8192;  // a plan's picture, at most
constexpr int kMaxImageSide = 16384;   // an image, at most (fenestra renders at most 16384)
constexpr std::size_t kMaxLineBytes = 120;

double percentile(std::vector<double> v, double p)
{
    const std::size_t n = v.size();
    std::size_t k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(n)));
    k = std::clamp<std::size_t>(k, 1, n) - 1;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

// The smallest {1, 1.5, 2, 2.5, 3, 4, 5, 6, 8} x 10^k at or above x > 0.
double roundStepAtLeast(double x)
{
    static const double mantissas[] = {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0};
    const double decade = std::pow(10.0, std::floor(std::log10(x)));
    for (const double m : mantissas)
        if (m * decade >= x * (1.0 - 1e-12))
            return m * decade;
    return 10.0 * decade;
}

// The picture with its title, label and legend around it (false_color.h, "Layout").
Raster compose(const Raster& picture, const FalseColorScale& scale, const std::string& label)
{
    // Title and label lines, each cut to kMaxLineBytes so that no text can make the picture huge.
    std::vector<std::string> header;
    for (const std::string* line : {&scale.title, &label})
        if (!line->empty())
            header.push_back(line->size() <= kMaxLineBytes ? *line : line->substr(0, kMaxLineBytes) + "...");
    const int pictureX = kMargin;
    const int pictureY = kMargin + static_cast<int>(header.size()) * kLineHeight + (header.empty() ? 0 : 6);

    const int barX = pictureX + picture.width + kLegendGap;
    const int barTop = pictureY + (scale.unit.empty() ? 0 : kLineHeight) + kCapHeight / 2 + 2;
    const int room = picture.height - (barTop - pictureY) - kCapHeight / 2;
    const int stepPixels = std::clamp(room / scale.steps, 22, 60);
    const int barHeight = stepPixels * scale.steps;

    const std::vector<double> ticks = scaleTicks(scale);
    std::vector<std::string> labels;
    // The labels' column, wide enough for the unit too (drawn from barX, above the bar).
    int labelWidth = textWidth(scale.unit, kFontScale) - kBarWidth - kTickLength - 4;
    for (const double t : ticks) {
        labels.push_back(compactNumber(t, scale.log ? 2 : 3));
        labelWidth = std::max(labelWidth, textWidth(labels.back(), kFontScale));
    }
    const int labelX = barX + kBarWidth + kTickLength + 4;

    int width = labelX + labelWidth + kMargin;
    for (const auto& line : header)
        width = std::max(width, 2 * kMargin + textWidth(line, kFontScale));
    const int height = std::max(pictureY + picture.height, barTop + barHeight + kCapHeight / 2 + 2) + kMargin;

    Raster out(width, height, kBackground);
    for (std::size_t i = 0; i < header.size(); ++i)
        drawText(out, kMargin, kMargin + static_cast<int>(i) * kLineHeight, header[i], kInk, kFontScale);
    for (int y = 0; y < picture.height; ++y)
        for (int x = 0; x < picture.width; ++x)
            out.set(pictureX + x, pictureY + y, picture.get(x, y));

    if (!scale.unit.empty())
        drawText(out, barX, pictureY, scale.unit, kInk, kFontScale);
    for (int r = 0; r <= barHeight; ++r)
        out.fillRect(barX, barTop + r, barX + kBarWidth, barTop + r + 1,
                     colorMap(1.0 - static_cast<double>(r) / barHeight));
    // a frame around the bar, one pixel outside it
    out.fillRect(barX - 1, barTop - 1, barX + kBarWidth + 1, barTop, kInk);
    out.fillRect(barX - 1, barTop + barHeight + 1, barX + kBarWidth + 1, barTop + barHeight + 2, kInk);
    out.fillRect(barX - 1, barTop - 1, barX, barTop + barHeight + 2, kInk);
    out.fillRect(barX + kBarWidth, barTop - 1, barX + kBarWidth + 1, barTop + barHeight + 2, kInk);
    for (int i = 0; i <= scale.steps; ++i) {
        const int y = barTop + barHeight - i * stepPixels;
        out.fillRect(barX + kBarWidth, y, barX + kBarWidth + kTickLength, y + 1, kInk);
        drawText(out, labelX, y - kCapHeight / 2, labels[static_cast<std::size_t>(i)], kInk, kFontScale);
    }
    return out;
}

std::string encode(const Raster& r) { return encodePng(r.width, r.height, 3, r.rgb); }

}  // namespace

FalseColorScale autoScale(const std::vector<double>& values, bool log, std::string unit, int steps)
{
    FalseColorScale s;
    s.log = log;
    s.steps = steps;
    s.unit = std::move(unit);
    std::vector<double> use;
    for (const double v : values)
        if (std::isfinite(v) && (!log || v > 0.0))
            use.push_back(v);
    if (log) {
        if (use.empty()) {
            s.min = 1.0;
            s.max = 10.0;
            return s;
        }
        const double lo = std::floor(std::log10(percentile(use, 0.01)) + 1e-9);
        double hi = std::ceil(std::log10(percentile(use, 0.99)) - 1e-9);
        hi = std::max(hi, lo + 1.0);
        s.min = std::pow(10.0, lo);
        s.max = std::pow(10.0, hi);
        return s;
    }
    double top = use.empty() ? 0.0 : percentile(use, 0.99);
    if (!(top > 0.0))
        top = 1.0;
    s.min = 0.0;
    s.max = roundStepAtLeast(top / std::max(steps, 1)) * std::max(steps, 1);
    return s;
}

void checkScale(const FalseColorScale& s)
{
    if (!std::isfinite(s.min) || !std::isfinite(s.max) || !(s.min < s.max))
        throw Error(cat("false-colour scale ", s.min, " .. ", s.max, ": the minimum must be below the maximum"));
    if (s.log && !(s.min > 0.0))
        throw Error(cat("false-colour scale ", s.min, " .. ", s.max, ": a logarithmic scale needs a positive minimum"));
    if (s.steps < 1 || s.steps > kMaxScaleSteps)
        throw Error(cat("false-colour scale: ", s.steps, " steps, must be 1 to ", kMaxScaleSteps));
}

double scalePosition(double value, const FalseColorScale& s)
{
    if (std::isnan(value))
        return value;
    double t;
    if (s.log)
        t = value > 0.0 ? std::log(value / s.min) / std::log(s.max / s.min) : 0.0;
    else
        t = (value - s.min) / (s.max - s.min);
    return std::clamp(t, 0.0, 1.0);
}

Rgb8 colorMap(double t)
{
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
    const double x = t * (kMapPoints - 1);
    const int i = std::min(static_cast<int>(x), kMapPoints - 2);
    const double f = x - i;
    const auto mix = [f](unsigned char a, unsigned char b) {
        return static_cast<unsigned char>(std::lround(a + (static_cast<double>(b) - a) * f));
    };
    const Rgb8 a = kMap[i], b = kMap[i + 1];
    return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

Rgb8 falseColor(double value, const FalseColorScale& scale)
{
    return std::isnan(value) ? kNoDataColor : colorMap(scalePosition(value, scale));
}

std::vector<double> scaleTicks(const FalseColorScale& s)
{
    std::vector<double> ticks;
    for (int i = 0; i <= s.steps; ++i) {
        const double f = static_cast<double>(i) / s.steps;
        ticks.push_back(i == s.steps ? s.max
                        : s.log      ? s.min * std::pow(s.max / s.min, f)
                                     : s.min + (s.max - s.min) * f);
    }
    return ticks;
}

std::string compactNumber(double value, int significant)
{
    if (std::isnan(value))
        return "nan";
    if (std::isinf(value))
        return value > 0 ? "inf" : "-inf";
    if (value == 0.0)
        return "0";
    significant = std::clamp(significant, 1, 15);
    const std::string sign = value < 0.0 ? "-" : "";
    double a = std::fabs(value);
    // round to the significant digits first, so that 999.7 becomes 1k, not 1000
    const double e = std::floor(std::log10(a));
    const double unit = std::pow(10.0, e - significant + 1);
    a = std::round(a / unit) * unit;
    char buf[64];
    if (a < 1e-4) {
        std::snprintf(buf, sizeof buf, "%.*g", significant, a);
        return sign + buf;
    }
    const char* suffix = "";
    if (a >= 1e9) {
        a /= 1e9;
        suffix = "G";
    } else if (a >= 1e6) {
        a /= 1e6;
        suffix = "M";
    } else if (a >= 1e3) {
        a /= 1e3;
        suffix = "k";
    }
    const int decimals = std::max(0, significant - 1 - static_cast<int>(std::floor(std::log10(a) + 1e-9)));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, a);
    std::string s = buf;
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0')
            s.pop_back();
        if (s.back() == '.')
            s.pop_back();
    }
    return sign + s + suffix;
}

std::string falseColorImagePng(const std::vector<double>& values, int width, int height,
                               const FalseColorScale& scale)
{
    checkScale(scale);
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide ||
        values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw Error(cat("false-colour image: ", width, " x ", height, " pixels with ", values.size(),
                        " values (at most ", kMaxImageSide, " pixels a side)"));
    const int longer = std::max(width, height);
    const int k = longer >= kMinPictureSide ? 1 : (kMinPictureSide + longer - 1) / longer;
    Raster picture(width * k, height * k, kBackground);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            picture.fillRect(x * k, y * k, (x + 1) * k, (y + 1) * k,
                             falseColor(values[static_cast<std::size_t>(y) * width + x], scale));
    return encode(compose(picture, scale, ""));
}

std::string falseColorPlanPng(const std::vector<PlanCell>& cells, const FalseColorScale& scale,
                              const std::string& label)
{
    checkScale(scale);
    if (cells.empty())
        throw Error("false-colour plan: no cells");
    double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY, smallest = INFINITY;
    for (const PlanCell& c : cells) {
        if (!std::isfinite(c.u_m) || !std::isfinite(c.v_m) || !std::isfinite(c.size_m) || !(c.size_m > 0.0))
            throw Error(cat("false-colour plan: a cell at (", c.u_m, ", ", c.v_m, ") of size ", c.size_m,
                            " m: positions must be finite and sizes positive"));
        u0 = std::min(u0, c.u_m - c.size_m / 2);
        u1 = std::max(u1, c.u_m + c.size_m / 2);
        v0 = std::min(v0, c.v_m - c.size_m / 2);
        v1 = std::max(v1, c.v_m + c.size_m / 2);
        smallest = std::min(smallest, c.size_m);
    }
    double perMetre = kPlanSide / std::max(u1 - u0, v1 - v0);
    perMetre = std::max(perMetre, 2.0 / smallest);
    const double w = std::round((u1 - u0) * perMetre), h = std::round((v1 - v0) * perMetre);
    if (!(w <= kMaxPictureSide && h <= kMaxPictureSide))
        throw Error(cat("false-colour plan: ", w, " x ", h, " pixels needed to draw its smallest cell (",
                        smallest, " m) 2 pixels across over ", u1 - u0, " x ", v1 - v0,
                        " m; at most ", kMaxPictureSide, " pixels across"));
    Raster picture(std::max(1, static_cast<int>(w)), std::max(1, static_cast<int>(h)), kBackground);
    for (const PlanCell& c : cells) {
        const auto edge = [perMetre](double x) { return static_cast<int>(std::lround(x * perMetre)); };
        const int x0 = edge(c.u_m - c.size_m / 2 - u0), x1 = edge(c.u_m + c.size_m / 2 - u0);
        const int y0 = edge(c.v_m - c.size_m / 2 - v0), y1 = edge(c.v_m + c.size_m / 2 - v0);
        picture.fillRect(x0, y0, std::max(x1, x0 + 1), std::max(y1, y0 + 1), falseColor(c.value, scale));
    }
    return encode(compose(picture, scale, label));
}

}  // namespace fen
