// false_color.h — false-colour pictures on a labelled scale, as Radiance's `falsecolor` draws
// them: a luminance image, or sensor cells on a plane (illuminance, daylight factor), each value
// a colour of one map, with the scale beside it as a colour bar and numbers. For reading values
// off a picture, never for measuring (the numbers are in the EXR and the sensor file).
//
// The map: viridis-like (dark purple, blue, green, yellow), a few control points interpolated in
// sRGB; its luminance rises from one end to the other (strictly from each hundredth of the scale
// to the next; within a hundredth only the rounding to 8 bits, under 0.0005, can reverse it), so
// the order of values survives a grey print and colour-blind eyes. Values below `min` take the first colour, above
// `max` the last; NaN (no data) is dark grey, a colour the map never takes. Linear scales place
// a value at (v - min) / (max - min), logarithmic ones at log(v / min) / log(max / min).
// Layout: the title and the label on top, the picture below them at its top-left, the legend to
// its right: the unit, then the colour bar (max at the top) with `steps` + 1 labelled ticks. Text
// is io/bitmap_font.h's at twice its size, a title or label cut after 120 bytes; the background
// is white. Encoded as 8-bit RGB PNG (io/output_files.h's encodePng).
#pragma once

#include <string>
#include <vector>

#include "io/raster.h"

namespace fen {

struct FalseColorScale {
    double min = 0.0, max = 1.0;  // values at the ends of the scale (min > 0 when log)
    bool log = false;             // logarithmic (decades) or linear
    int steps = 8;                // labelled bands/ticks in the legend: steps + 1 labels
    std::string unit;             // e.g. "cd/m²", "lux", "% DF" -- written in the legend
    std::string title;            // optional, e.g. "illuminance, work plane"
};

// The colour of no data (NaN).
constexpr Rgb8 kNoDataColor{64, 64, 64};
constexpr int kMaxScaleSteps = 100;

// A scale fitted to the finite values, with `steps` steps and no title.
// Linear: 0 .. the smallest steps x {1, 1.5, 2, 2.5, 3, 4, 5, 6, 8} x 10^k at or above the 99th
// percentile (1 when that is not positive), so that every tick is a round number.
// Log: whole decades, from the one at or below the 1st percentile of the positive values to the
// one at or above their 99th; at least one decade; 1 .. 10 when no value is positive.
FalseColorScale autoScale(const std::vector<double>& values, bool log, std::string unit, int steps = 8);

// Throws fen::Error unless min < max, both finite, min > 0 when log, and 1 <= steps <= kMaxScaleSteps.
void checkScale(const FalseColorScale& scale);
// Where `value` lies on the scale, 0 (min) to 1 (max), clamped; NaN for NaN.
double scalePosition(double value, const FalseColorScale& scale);
// The map's colour at position t (clamped to [0, 1]).
Rgb8 colorMap(double t);
// The colour of `value` on the scale: colorMap(scalePosition(...)), kNoDataColor for NaN.
Rgb8 falseColor(double value, const FalseColorScale& scale);
// The steps + 1 tick values from min to max (evenly spaced, or in equal ratios when log).
std::vector<double> scaleTicks(const FalseColorScale& scale);
// A number in at most `significant` significant digits, trailing zeros dropped, thousands as k,
// millions as M, billions as G: 0.5, 12, 350, 1.2k, 15k, 2.5M.
std::string compactNumber(double value, int significant = 3);

// An image (row-major, width x height, row 0 at the top; NaN = no data, drawn dark grey) in false
// colour with a legend bar beside it; returns the encoded PNG file's bytes. An image under 300
// pixels on its longer side is enlarged by a whole factor (each pixel a square block) to at
// least 300. Throws fen::Error for a bad scale, or a size that is not width x height values or
// exceeds 16384 pixels a side.
std::string falseColorImagePng(const std::vector<double>& values, int width, int height,
                               const FalseColorScale& scale);

// Sensor cells on a plane: each a square of side `size_m` centred at (u_m, v_m) in plane
// coordinates (u to the right, v downwards in the picture), rasterised at a resolution that gives
// the picture about 800 px on its longer side, or more where that leaves a cell under 2 px
// across (at most 8192 px: beyond, fen::Error); white where there is no cell; legend beside it;
// optional `label` text above (e.g. "mean 312 lux  min/mean 0.21"). A cell's pixels are those
// whose centres it covers, edges rounded to whole pixels, so that neighbours tile without gaps;
// where cells overlap, the later one is drawn on top.
struct PlanCell {
    double u_m, v_m, size_m, value;
};
std::string falseColorPlanPng(const std::vector<PlanCell>& cells, const FalseColorScale& scale,
                              const std::string& label = "");

}  // namespace fen
