// sensor_csv.h — reading a fenestra sensor file: one CSV row per sensor cell, the illuminance on
// it, and optionally its daylight factor.
//
// The first line is exactly the header
//   sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux
// optionally followed by ,daylight_factor_pct,daylight_factor_std_err_pct; every other non-empty
// line has as many fields. A field may be double-quoted ("a, b"; "" inside for a quote); spaces
// around a field are ignored; CR LF line ends are read as LF. Positions, normals and areas must be
// finite numbers, the normal not zero (it is normalised), the area positive; the values
// (illuminance, daylight factor and their errors) are numbers, `nan` meaning no data.
// Errors are fen::Error naming the file, and the line for what is wrong on one (`plan.csv:7: ...`).
#pragma once

#include <string>
#include <vector>

namespace fen {

struct SensorRow {
    std::string sensor, cell;
    double x = 0, y = 0, z = 0;     // the cell's centre, metres
    double nx = 0, ny = 0, nz = 1;  // its unit normal
    double area = 0;                // m²
    double illuminance = 0, illuminanceStdErr = 0;          // lux
    double daylightFactor = 0, daylightFactorStdErr = 0;    // % (when the file has them)
    int line = 0;                                           // where it is in the file, from 1
};

struct SensorFile {
    std::string path;
    bool hasDaylightFactor = false;
    std::vector<SensorRow> rows;  // in file order; at least one
};

SensorFile readSensorCsv(const std::string& path);

}  // namespace fen
