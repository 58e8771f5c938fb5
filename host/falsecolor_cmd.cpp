// falsecolor_cmd.cpp — `fenestra falsecolor`: an EXR's luminance, or a sensor file's planes
// (illuminance or daylight factor), in false colour on a labelled scale (docs/false_color.md).
//
// Options are checked before the input is read; every failure is a one-line fen::Error naming
// the option or the file (and the line). One scale serves every picture of a run, fitted to all
// the values unless --min/--max fix its ends, so that a colour means one value in all of them.
// Pictures of a sensor file: the first plane (in file order) is OUT.png, every other
// OUT-<sensor>.png, or OUT-<sensor>-<k>.png for the k-th plane of a sensor with several; in
// <sensor> every byte but A-Z a-z 0-9 . _ - becomes _. All are written as a set
// (io/output_files.h): on failure none is.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "io/exr_io.h"
#include "io/false_color.h"
#include "io/output_files.h"
#include "io/path_checks.h"
#include "io/sensor_csv.h"
#include "io/sensor_pictures.h"
#include "util/error.h"

namespace fen {

namespace {

constexpr int kDefaultSteps = 8;

bool endsWith(const std::string& s, const std::string& suffix)
{
    if (s.size() < suffix.size())
        return false;
    for (std::size_t i = 0; i < suffix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i])
            return false;
    return true;
}

std::string baseName(const std::string& path)
{
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The scale: fitted to `values`, then the ends given on the command line. With only --min, a
// linear top is fitted to the values above it (in round steps from it), a log top is the fitted
// one, or a decade above --min where that is not above it; with only --max, the bottom is the
// fitted one (a log one a decade below --max where that is not below it). Without --steps, a log
// scale of d whole decades has d x round(8 / d) steps (at least d), so that every decade is a label.
FalseColorScale chooseScale(const std::vector<double>& values, const FalseColorOptions& o, bool log,
                            const std::string& unit)
{
    const int steps = o.steps.value_or(kDefaultSteps);
    FalseColorScale s = autoScale(values, log, unit, steps);
    if (o.min && o.max) {
        s.min = *o.min;
        s.max = *o.max;
    } else if (o.min) {
        s.min = *o.min;
        if (log) {
            if (!(s.max > s.min))
                s.max = 10.0 * s.min;
        } else {
            std::vector<double> above;
            for (const double v : values)
                above.push_back(v - s.min);
            s.max = s.min + autoScale(above, false, unit, steps).max;
        }
    } else if (o.max) {
        s.max = *o.max;
        if (!(s.min < s.max)) {
            if (!log)
                throw Error(cat("--max ", *o.max, ": must be above the scale's bottom, ", s.min, "; give --min too"));
            s.min = s.max / 10.0;
        }
    }
    if (log && !o.steps && s.min > 0.0 && s.max > s.min) {
        const double decades = std::log10(s.max / s.min);
        const long whole = std::lround(decades);
        if (whole >= 1 && std::fabs(decades - whole) < 1e-9)
            s.steps = static_cast<int>(std::min<long>(whole * std::max(1L, std::lround(8.0 / whole)), kMaxScaleSteps));
    }
    checkScale(s);
    return s;
}

void checkOptions(const FalseColorOptions& o, bool sensorFile)
{
    if (o.steps && (*o.steps < 1 || *o.steps > kMaxScaleSteps))
        throw Error(cat("--steps ", *o.steps, ": must be in 1..", kMaxScaleSteps));
    if (o.min && !std::isfinite(*o.min))
        throw Error(cat("--min ", *o.min, ": must be a finite number"));
    if (o.max && !std::isfinite(*o.max))
        throw Error(cat("--max ", *o.max, ": must be a finite number"));
    if (o.min && o.max && !(*o.min < *o.max))
        throw Error(cat("--min ", *o.min, " must be below --max ", *o.max));
    const bool log = o.log || (!o.linear && !sensorFile);
    if (log && o.min && !(*o.min > 0.0))
        throw Error(cat("--min ", *o.min, ": a logarithmic scale (", o.log ? "--log" : "the default for an image",
                        ") needs a positive minimum; give --linear for a linear one"));
    if (log && o.max && !(*o.max > 0.0))
        throw Error(cat("--max ", *o.max, ": a logarithmic scale (", o.log ? "--log" : "the default for an image",
                        ") needs a positive maximum"));
    if (o.quantity && !sensorFile)
        throw Error(cat("--quantity ", printable(*o.quantity, 40), ": only for a .csv sensor file; an image is luminance"));
    if (o.quantity && *o.quantity != "illuminance" && *o.quantity != "df")
        throw Error(cat("--quantity '", printable(*o.quantity, 40), "': must be illuminance or df"));
}

std::string scaleText(const FalseColorScale& s)
{
    return cat(compactNumber(s.min), "..", compactNumber(s.max), " ", s.unit, s.log ? " (log)" : " (linear)");
}

void writeAll(const std::vector<std::pair<std::string, std::string>>& files, const FalseColorOptions& o)
{
    checkOutputPath(o.out, "--out");
    OutputFiles out;
    for (const auto& [path, bytes] : files) {
        refuseOverwritingInputs(path, "--out", {{"the input", o.input}});
        out.add(path, bytes);
    }
    out.commit();
}

int runImage(const FalseColorOptions& o)
{
    const Image image = readExr(o.input);
    std::vector<double> y(image.pixels());
    for (std::size_t i = 0; i < y.size(); ++i)
        y[i] = image.luminance(i);
    FalseColorScale scale = chooseScale(y, o, !o.linear, "cd/m²");
    scale.title = o.title ? *o.title : cat("luminance, ", baseName(o.input));
    writeAll({{o.out, falseColorImagePng(y, image.width, image.height, scale)}}, o);
    std::printf("%s: luminance of %s, %d x %d, scale %s\n", o.out.c_str(), o.input.c_str(), image.width,
                image.height, scaleText(scale).c_str());
    return 0;
}

int runSensors(const FalseColorOptions& o)
{
    const SensorFile file = readSensorCsv(o.input);
    const bool df = o.quantity && *o.quantity == "df";
    if (df && !file.hasDaylightFactor)
        throw Error(cat(printable(o.input), ": --quantity df needs the columns daylight_factor_pct and "
                                            "daylight_factor_std_err_pct, which this sensor file does not have"));
    const auto valueOf = [df](const SensorRow& r) { return df ? r.daylightFactor : r.illuminance; };
    std::vector<double> values;
    for (const SensorRow& r : file.rows)
        values.push_back(valueOf(r));
    FalseColorScale scale = chooseScale(values, o, o.log, df ? "% DF" : "lux");

    std::vector<std::pair<std::string, std::string>> files;
    std::vector<std::string> summaries;
    for (SensorPicture& p : sensorPictures(file, df, scale, o.out, o.title)) {
        files.emplace_back(p.path, std::move(p.png));
        summaries.push_back(p.summary);
    }
    writeAll(files, o);
    for (const auto& s : summaries)
        std::printf("%s\n", s.c_str());
    std::printf("scale %s\n", scaleText(scale).c_str());
    return 0;
}

}  // namespace

void addFalseColorOptions(CLI::App& sub, FalseColorOptions& o)
{
    sub.add_option("input", o.input, "fenestra image (.exr: luminance) or sensor file (.csv: illuminance, DF)")
        ->required();
    sub.add_option("--out", o.out, "Output OUT.png (a sensor file's further planes: OUT-<sensor>.png)")->required();
    auto* log = sub.add_flag("--log", o.log, "Logarithmic scale (default for an image)");
    auto* linear = sub.add_flag("--linear", o.linear, "Linear scale (default for a sensor file)");
    log->excludes(linear);
    sub.add_option("--min", o.min, "Value at the bottom of the scale (default: fitted to the data)");
    sub.add_option("--max", o.max, "Value at the top of the scale (default: fitted to the data)");
    sub.add_option("--steps", o.steps,
                   "Labelled steps of the legend, 1 to 100 (default 8; on a log scale, a multiple of its decades)");
    sub.add_option("--quantity", o.quantity, "Sensor file: illuminance (lux, default) or df (daylight factor, %)");
    sub.add_option("--title", o.title, "Title above the picture (default: the quantity and the file or sensor)");
}

int runFalseColor(const FalseColorOptions& o)
{
    const bool exr = endsWith(o.input, ".exr"), csv = endsWith(o.input, ".csv");
    if (!exr && !csv)
        throw Error(cat(printable(o.input), ": give a .exr image or a .csv sensor file"));
    checkOptions(o, csv);
    if (!endsWith(o.out, ".png"))
        throw Error(cat("--out '", printable(o.out), "': give a .png file name"));
    requireRegularFile(o.input, "the input");
    return exr ? runImage(o) : runSensors(o);
}

}  // namespace fen
