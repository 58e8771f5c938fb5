// sensor_report.h — what a render says about its sensors (DESIGN.md §8, docs/sensors.md): each
// cell's illuminance with its standard error as CSV, and each sensor's summary for the JSON --
// area-weighted mean, minimum, maximum and uniformity (min / mean), each with its jackknife
// standard error (sensor/sensor_stats.h) -- and, in a daylight-factor study, the same for the
// daylight factor DF = E / E_outside (%) and the share of the sensor's area with DF at or above
// the threshold, as consultants report them.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "io/sensor_csv.h"
#include "sensor/sensor_set.h"
#include "sensor/sensor_stats.h"

namespace fen {

struct DaylightFactorSpec {
    double outside_lux = 0.0;   // the unobstructed horizontal illuminance of the sky (closed form)
    double threshold_pct = 2.0;
};

// Each cell's row (io/sensor_csv.h: what the CSV holds and `fenestra falsecolor` reads back), in
// the set's cell order; `path` names the file they go to.
SensorFile sensorRows(const SensorSet& set, const SensorStatistics& stats, const std::optional<DaylightFactorSpec>& df,
                      const std::string& path);
// The rows as CSV. Columns: sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux
// and, with a DF study, daylight_factor_pct,daylight_factor_std_err_pct.
std::string sensorCsv(const SensorFile& file);
// A row's first nine fields, sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2 (no line end): the start of
// every per-cell CSV fenestra writes.
std::string sensorCsvPlace(const SensorRow& r);

// {"NAME": {...}, ...} in the order the sensors were given.
nlohmann::json sensorSummary(const SensorSet& set, const SensorStatistics& stats,
                             const std::optional<DaylightFactorSpec>& df);

}  // namespace fen
