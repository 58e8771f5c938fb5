// sensor_csv.cpp — parsing a sensor file's lines into rows (sensor_csv.h).
#include "io/sensor_csv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace fen {

namespace {

const char* kHeader = "sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux";
const char* kDaylightColumns = ",daylight_factor_pct,daylight_factor_std_err_pct";
const char* kColumns[] = {"sensor", "cell", "x_m", "y_m", "z_m", "nx", "ny", "nz", "area_m2",
                          "illuminance_lux", "std_err_lux", "daylight_factor_pct", "daylight_factor_std_err_pct"};

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos)
        return "";
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The fields of one line; throws (with `where`) on a quote left open or text after a closing one.
std::vector<std::string> splitFields(const std::string& line, const std::string& where)
{
    std::vector<std::string> fields;
    std::size_t i = 0;
    while (true) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
            ++i;
        std::string field;
        if (i < line.size() && line[i] == '"') {
            ++i;
            while (true) {
                if (i >= line.size())
                    throw Error(cat(where, ": a quoted field is not closed"));
                if (line[i] == '"') {
                    if (i + 1 < line.size() && line[i + 1] == '"') {
                        field += '"';
                        i += 2;
                        continue;
                    }
                    ++i;
                    break;
                }
                field += line[i++];
            }
            while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
                ++i;
            if (i < line.size() && line[i] != ',')
                throw Error(cat(where, ": text after a quoted field"));
        } else {
            const std::size_t end = line.find(',', i);
            field = trim(line.substr(i, end == std::string::npos ? std::string::npos : end - i));
            i = end == std::string::npos ? line.size() : end;
        }
        fields.push_back(field);
        if (i >= line.size())
            return fields;
        ++i;  // the comma
    }
}

double number(const std::vector<std::string>& fields, std::size_t column, const std::string& where)
{
    const std::string& text = fields[column];
    const char* start = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(start, &end);
    if (text.empty() || end != start + text.size())
        throw Error(cat(where, ": ", kColumns[column], " '", printable(text, 40), "' is not a number"));
    return v;
}

double finiteNumber(const std::vector<std::string>& fields, std::size_t column, const std::string& where)
{
    const double v = number(fields, column, where);
    if (!std::isfinite(v))
        throw Error(cat(where, ": ", kColumns[column], " '", printable(fields[column], 40), "' must be finite"));
    return v;
}

// A value: a number or nan (no data), never infinite.
double value(const std::vector<std::string>& fields, std::size_t column, const std::string& where)
{
    const double v = number(fields, column, where);
    if (std::isinf(v))
        throw Error(cat(where, ": ", kColumns[column], " '", printable(fields[column], 40),
                        "' must be a finite number, or nan for no data"));
    return v;
}

}  // namespace

namespace {
SensorFile parseSensorCsv(const std::string& text, const std::string& path);
}  // namespace

SensorFile readSensorCsv(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(cat(printable(path), ": cannot open the sensor file: ", std::strerror(errno)));
    std::stringstream buffer;
    buffer << in.rdbuf();
    if (in.bad())
        throw Error(cat(printable(path), ": cannot read the sensor file"));
    return parseSensorCsv(buffer.str(), path);
}

namespace {

// The file read as text; `path` names it in errors.
SensorFile parseSensorCsv(const std::string& text, const std::string& path)
{
    SensorFile file;
    file.path = path;
    std::size_t columns = 0;
    std::size_t pos = 0;
    int lineNumber = 0;
    while (pos < text.size() || lineNumber == 0) {
        const std::size_t end = text.find('\n', pos);
        std::string line = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        pos = end == std::string::npos ? text.size() : end + 1;
        ++lineNumber;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        const std::string where = cat(printable(path), ":", lineNumber);
        if (lineNumber == 1) {
            if (line.rfind("\xef\xbb\xbf", 0) == 0)  // a UTF-8 byte order mark
                line.erase(0, 3);
            line = trim(line);
            if (line == kHeader) {
                columns = 11;
            } else if (line == std::string(kHeader) + kDaylightColumns) {
                columns = 13;
                file.hasDaylightFactor = true;
            } else {
                throw Error(cat(where, ": not a fenestra sensor file: the first line must be '", kHeader,
                                "' (optionally with '", kDaylightColumns, "'), not '", printable(line, 120), "'"));
            }
            continue;
        }
        if (trim(line).empty())
            continue;
        const std::vector<std::string> f = splitFields(line, where);
        if (f.size() != columns)
            throw Error(cat(where, ": ", f.size(), " fields, the header has ", columns));
        SensorRow r;
        r.line = lineNumber;
        r.sensor = f[0];
        r.cell = f[1];
        if (r.sensor.empty())
            throw Error(cat(where, ": the sensor name is empty"));
        r.x = finiteNumber(f, 2, where);
        r.y = finiteNumber(f, 3, where);
        r.z = finiteNumber(f, 4, where);
        r.nx = finiteNumber(f, 5, where);
        r.ny = finiteNumber(f, 6, where);
        r.nz = finiteNumber(f, 7, where);
        const double n = std::sqrt(r.nx * r.nx + r.ny * r.ny + r.nz * r.nz);
        if (!(n > 1e-6) || !std::isfinite(n))
            throw Error(cat(where, ": the normal (", r.nx, ", ", r.ny, ", ", r.nz, ") is not a direction"));
        r.nx /= n;
        r.ny /= n;
        r.nz /= n;
        r.area = finiteNumber(f, 8, where);
        if (!(r.area > 0.0))
            throw Error(cat(where, ": area_m2 ", r.area, " must be positive"));
        r.illuminance = value(f, 9, where);
        r.illuminanceStdErr = value(f, 10, where);
        if (file.hasDaylightFactor) {
            r.daylightFactor = value(f, 11, where);
            r.daylightFactorStdErr = value(f, 12, where);
        }
        file.rows.push_back(std::move(r));
    }
    if (file.rows.empty())
        throw Error(cat(printable(path), ": no sensor cells (a header and no rows)"));
    return file;
}

}  // namespace

}  // namespace fen
