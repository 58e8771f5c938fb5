// weather_file.cpp — an EPW read for its daylight (weather_file.h).
#include "io/weather_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace fen {

namespace {

constexpr int kDaysIn[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};

std::vector<std::string> splitFields(const std::string& line)
{
    std::vector<std::string> out(1);
    for (const char c : line) {
        if (c == ',')
            out.emplace_back();
        else if (c != '\r')
            out.back() += c;
    }
    return out;
}

class Reader {
public:
    Reader(const std::string& path, int line, const std::vector<std::string>& fields)
        : path_(path), line_(line), fields_(fields)
    {
    }
    [[noreturn]] void fail(const char* field, std::size_t index, const std::string& why) const
    {
        const std::string text = index < fields_.size() ? fields_[index] : std::string();
        throw Error(cat(printable(path_), ":", line_, ": ", field, " '", printable(text, 40), "': ", why));
    }
    double number(std::size_t index, const char* field) const
    {
        if (index >= fields_.size())
            fail(field, index, cat("missing (the line has ", fields_.size(), " fields)"));
        const std::string& t = fields_[index];
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(t.c_str(), &end);
        std::size_t rest = static_cast<std::size_t>(end - t.c_str());
        while (rest < t.size() && t[rest] == ' ')
            ++rest;
        if (t.empty() || end == t.c_str() || rest != t.size() || errno == ERANGE || !std::isfinite(v))
            fail(field, index, "not a number");
        return v;
    }
    int integer(std::size_t index, const char* field, int lo, int hi) const
    {
        const double v = number(index, field);
        if (v != std::floor(v) || v < lo || v > hi)
            fail(field, index, cat("must be an integer ", lo, "..", hi));
        return static_cast<int>(v);
    }
    // An irradiance: >= 0 W/m^2, or missing (9999).
    std::optional<double> irradiance(std::size_t index, const char* field) const
    {
        const double v = number(index, field);
        if (v >= 9999.0)
            return std::nullopt;
        if (v < 0.0) {
            if (v > -1.0)  // "-0.00" and rounding below zero in converted files
                return 0.0;
            fail(field, index, "negative");
        }
        return v;
    }
    // An illuminance: >= 0 lux, or missing (999999).
    std::optional<double> illuminance(std::size_t index, const char* field) const
    {
        const double v = number(index, field);
        if (v >= 999999.0)
            return std::nullopt;
        if (v < 0.0)
            fail(field, index, "negative");
        return v;
    }

private:
    const std::string& path_;
    int line_;
    const std::vector<std::string>& fields_;
};

}  // namespace

int dayOfYear(int month, int day)
{
    int d = day;
    for (int m = 1; m < month && m <= 12; ++m)
        d += kDaysIn[m - 1];
    return d;
}

const WeatherRecord& WeatherFile::at(int month, int day, int hour, const std::string& what) const
{
    for (const WeatherRecord& r : records)
        if (r.month == month && r.day == day && r.hour == hour)
            return r;
    throw Error(cat(what, ": ", printable(path), " has no record for month ", month, ", day ", day, ", hour ", hour));
}

WeatherFile readWeatherFile(const std::string& path)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error(cat(printable(path), ": ", std::filesystem::exists(path, ec) ? "not a regular file" : "cannot open the weather file",
                        " (a weather file is an EPW file)"));
    if (std::filesystem::file_size(path, ec) > (std::uintmax_t{256} << 20))
        throw Error(cat(printable(path), ": larger than 256 MiB: not an EPW weather file"));
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw Error(cat(printable(path), ": cannot open the weather file"));
    std::ostringstream text;
    text << file.rdbuf();
    return readWeatherText(text.str(), path);
}

WeatherFile readWeatherText(const std::string& text, const std::string& path)
{
    std::istringstream in(text);
    WeatherFile w;
    w.path = path;
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
        ++n;
        if (line.size() > 4096)
            throw Error(cat(printable(path), ":", n, ": a line longer than 4096 bytes: not an EPW file"));
        const std::vector<std::string> f = splitFields(line);
        const Reader r(path, n, f);
        if (n == 1) {
            if (f[0] != "LOCATION")
                throw Error(cat(printable(path), ":1: expected the LOCATION line of an EPW weather file"));
            w.place = cat(f.size() > 1 ? printable(f[1], 60) : "", f.size() > 3 ? ", " + printable(f[3], 60) : "");
            w.latitudeDeg = r.number(6, "latitude");
            w.longitudeDeg = r.number(7, "longitude");
            w.timeZoneHours = r.number(8, "time zone");
            if (std::abs(w.latitudeDeg) > 90.0)
                r.fail("latitude", 6, "must be in -90..90 degrees");
            if (std::abs(w.longitudeDeg) > 180.0)
                r.fail("longitude", 7, "must be in -180..180 degrees");
            if (std::abs(w.timeZoneHours) > 14.0)
                r.fail("time zone", 8, "must be in -14..14 hours");
            continue;
        }
        if (n <= 8 || line.empty() || line == "\r")
            continue;  // the other header lines say nothing fenestra uses
        if (w.records.size() >= 527040)  // a record a minute for a leap year: more is no weather file
            throw Error(cat(printable(path), ":", n, ": more than 527040 records: not an EPW weather file"));
        WeatherRecord rec;
        rec.line = n;
        rec.year = r.integer(0, "year", -9999, 9999);
        rec.month = r.integer(1, "month", 1, 12);
        rec.day = r.integer(2, "day", 1, rec.month == 2 ? 29 : kDaysIn[rec.month - 1]);
        rec.hour = r.integer(3, "hour", 1, 24);
        const double dew = r.number(7, "dew point temperature");
        if (dew < 99.0 && (dew < -90.0 || dew > 70.0))
            r.fail("dew point temperature", 7, "must be in -90..70 deg C (99.9: missing)");
        if (dew < 99.0)
            rec.dewPoint_C = dew;
        rec.globalHorizontal_W_m2 = r.irradiance(13, "global horizontal irradiance");
        rec.directNormal_W_m2 = r.irradiance(14, "direct normal irradiance");
        rec.diffuseHorizontal_W_m2 = r.irradiance(15, "diffuse horizontal irradiance");
        rec.globalHorizontal_lux = r.illuminance(16, "global horizontal illuminance");
        rec.directNormal_lux = r.illuminance(17, "direct normal illuminance");
        rec.diffuseHorizontal_lux = r.illuminance(18, "diffuse horizontal illuminance");
        w.records.push_back(rec);
    }
    if (n == 0)
        throw Error(cat(printable(path), ": empty: not an EPW weather file"));
    if (w.records.empty())
        throw Error(cat(printable(path), ": no hourly records after the 8 header lines"));
    return w;
}

}  // namespace fen
