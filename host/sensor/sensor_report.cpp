// sensor_report.cpp — sensor CSV and JSON summaries (sensor_report.h).
#include "sensor/sensor_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace fen {

namespace {

std::string num(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.7g", v);
    return b;
}

// The cells of sensor s with their areas.
struct Members {
    std::vector<std::size_t> cells;
    std::vector<double> area;
    double totalArea = 0.0;
};

Members membersOf(const SensorSet& set, std::uint32_t s)
{
    Members m;
    for (std::size_t c = 0; c < set.cells.size(); ++c)
        if (set.cells[c].sensor == s) {
            m.cells.push_back(c);
            const double a = set.cells[c].side_m * set.cells[c].side_m;
            m.area.push_back(a);
            m.totalArea += a;
        }
    return m;
}

// into[key] = f(cell means), into[key_std_err] = its jackknife standard error (null: one batch).
void estimate(const SensorStatistics& stats, const std::function<double(const std::vector<double>&)>& f,
              const char* key, nlohmann::json& into)
{
    const SensorStatistics::Estimate e = stats.jackknife(f);
    into[key] = e.value;
    into[std::string(key) + "_std_err"] = stats.batches() >= 2 ? nlohmann::json(e.stdErr) : nlohmann::json(nullptr);
}

}  // namespace

SensorFile sensorRows(const SensorSet& set, const SensorStatistics& stats, const std::optional<DaylightFactorSpec>& df,
                      const std::string& path)
{
    const std::vector<double> mean = stats.mean(), se = stats.stdErr();
    SensorFile file;
    file.path = path;
    file.hasDaylightFactor = df.has_value();
    std::vector<std::size_t> index(set.sensors.size(), 0);
    for (std::size_t c = 0; c < set.cells.size(); ++c) {
        const SensorCell& cell = set.cells[c];
        SensorRow r;
        r.sensor = set.sensors[cell.sensor].name;
        r.cell = std::to_string(index[cell.sensor]++);
        r.x = cell.position.x, r.y = cell.position.y, r.z = cell.position.z;
        r.nx = cell.normal.x, r.ny = cell.normal.y, r.nz = cell.normal.z;
        r.area = cell.side_m * cell.side_m;
        r.illuminance = mean[c];
        r.illuminanceStdErr = se[c];
        if (df) {
            r.daylightFactor = 100.0 * mean[c] / df->outside_lux;
            r.daylightFactorStdErr = 100.0 * se[c] / df->outside_lux;
        }
        r.line = static_cast<int>(c + 2);  // the header is line 1
        file.rows.push_back(std::move(r));
    }
    return file;
}

std::string sensorCsvPlace(const SensorRow& r)
{
    // Names are quoted when they hold a comma or a quote (RFC 4180).
    std::string name = r.sensor;
    if (name.find_first_of(",\"\n\r") != std::string::npos) {
        std::string q = "\"";
        for (char ch : name)
            q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
        name = q + "\"";
    }
    std::string out = name + "," + r.cell;
    for (double v : {r.x, r.y, r.z, r.nx, r.ny, r.nz, r.area})
        out += "," + num(v);
    return out;
}

std::string sensorCsv(const SensorFile& file)
{
    std::string out = "sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux";
    if (file.hasDaylightFactor)
        out += ",daylight_factor_pct,daylight_factor_std_err_pct";
    out += "\n";
    for (const SensorRow& r : file.rows) {
        out += sensorCsvPlace(r);
        for (double v : {r.illuminance, r.illuminanceStdErr})
            out += "," + num(v);
        if (file.hasDaylightFactor)
            out += "," + num(r.daylightFactor) + "," + num(r.daylightFactorStdErr);
        out += "\n";
    }
    return out;
}

nlohmann::json sensorSummary(const SensorSet& set, const SensorStatistics& stats,
                             const std::optional<DaylightFactorSpec>& df)
{
    nlohmann::json all = nlohmann::json::object();
    for (std::uint32_t s = 0; s < set.sensors.size(); ++s) {
        const Members m = membersOf(set, s);
        const auto meanOf = [&](const std::vector<double>& E) {
            double sum = 0.0;
            for (std::size_t i = 0; i < m.cells.size(); ++i)
                sum += m.area[i] * E[m.cells[i]];
            return sum / m.totalArea;
        };
        const auto minOf = [&](const std::vector<double>& E) {
            double v = INFINITY;
            for (std::size_t c : m.cells)
                v = std::min(v, E[c]);
            return v;
        };
        const auto maxOf = [&](const std::vector<double>& E) {
            double v = 0.0;
            for (std::size_t c : m.cells)
                v = std::max(v, E[c]);
            return v;
        };
        nlohmann::json j = {{"kind", set.sensors[s].kind},
                            {"source", set.sensors[s].source},
                            {"cells", m.cells.size()},
                            {"area_m2", m.totalArea}};
        estimate(stats, meanOf, "mean_lux", j);
        estimate(stats, minOf, "min_lux", j);
        estimate(stats, maxOf, "max_lux", j);
        estimate(stats, [&](const std::vector<double>& E) {
            const double mean = meanOf(E);
            return mean > 0.0 ? minOf(E) / mean : 0.0;
        }, "uniformity", j);
        if (df) {
            const double k = 100.0 / df->outside_lux;
            nlohmann::json d = {{"outside_lux", df->outside_lux}, {"threshold_pct", df->threshold_pct}};
            estimate(stats, [&](const std::vector<double>& E) { return k * meanOf(E); }, "mean_pct", d);
            estimate(stats, [&](const std::vector<double>& E) { return k * minOf(E); }, "min_pct", d);
            estimate(stats, [&](const std::vector<double>& E) { return k * maxOf(E); }, "max_pct", d);
            estimate(stats, [&](const std::vector<double>& E) {
                double a = 0.0;
                for (std::size_t i = 0; i < m.cells.size(); ++i)
                    if (k * E[m.cells[i]] >= df->threshold_pct)
                        a += m.area[i];
                return a / m.totalArea;
            }, "area_share_above", d);
            j["daylight_factor"] = d;
        }
        all[set.sensors[s].name] = j;
    }
    return all;
}

}  // namespace fen
