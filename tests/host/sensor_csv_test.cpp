// sensor_csv_test.cpp — reading sensor files (io/sensor_csv.h) and laying their cells out on
// planes (io/sensor_planes.h): the columns as written, quoting, CR LF, no data; one-line errors
// naming the file and line; planes by sensor and normal, and their picture coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "io/sensor_csv.h"
#include "io/sensor_planes.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

const std::string kHeader = "sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux";
const std::string kDfHeader = kHeader + ",daylight_factor_pct,daylight_factor_std_err_pct";

std::string writeFile(const std::string& name, const std::string& text)
{
    static const std::string dir = test::tempDir("sensor-csv");
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// The message of the fen::Error that reading `text` throws ("" if none).
std::string errorOf(const std::string& name, const std::string& text)
{
    try {
        readSensorCsv(writeFile(name, text));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SensorCsv, ReadsTheColumnsAsWritten)
{
    const std::string path = writeFile("df.csv", kDfHeader + "\r\n" +
                                                     "desk,0,1.5,0.8,-2,0,2,0,0.25,312.5,4.1,2.4,0.05\r\n"
                                                     "\r\n"
                                                     "\"desk, east\",c1, 2 ,0.8,-2,0,1,0,0.25,nan,nan,nan,nan\r\n");
    const SensorFile f = readSensorCsv(path);
    EXPECT_TRUE(f.hasDaylightFactor);
    ASSERT_EQ(f.rows.size(), 2u);
    const SensorRow& a = f.rows[0];
    EXPECT_EQ(a.sensor, "desk");
    EXPECT_EQ(a.cell, "0");
    EXPECT_DOUBLE_EQ(a.x, 1.5);
    EXPECT_DOUBLE_EQ(a.y, 0.8);
    EXPECT_DOUBLE_EQ(a.z, -2.0);
    EXPECT_DOUBLE_EQ(a.ny, 1.0);  // normalised
    EXPECT_DOUBLE_EQ(a.area, 0.25);
    EXPECT_DOUBLE_EQ(a.illuminance, 312.5);
    EXPECT_DOUBLE_EQ(a.illuminanceStdErr, 4.1);
    EXPECT_DOUBLE_EQ(a.daylightFactor, 2.4);
    EXPECT_DOUBLE_EQ(a.daylightFactorStdErr, 0.05);
    EXPECT_EQ(a.line, 2);
    const SensorRow& b = f.rows[1];
    EXPECT_EQ(b.sensor, "desk, east");
    EXPECT_DOUBLE_EQ(b.x, 2.0);
    EXPECT_TRUE(std::isnan(b.illuminance));
    EXPECT_EQ(b.line, 4);

    const SensorFile plain = readSensorCsv(writeFile("plain.csv", kHeader + "\nfloor,0,0,0,0,0,1,0,1,100,1\n"));
    EXPECT_FALSE(plain.hasDaylightFactor);
    ASSERT_EQ(plain.rows.size(), 1u);
}

TEST(SensorCsv, ErrorsNameTheFileAndTheLine)
{
    std::string e = errorOf("badnum.csv", kHeader + "\nfloor,0,0,0,0,0,1,0,1,100,1\nfloor,1,abc,0,0,0,1,0,1,100,1\n");
    EXPECT_NE(e.find("badnum.csv:3: x_m 'abc' is not a number"), std::string::npos) << e;
    e = errorOf("fields.csv", kHeader + "\nfloor,0,0,0,0,0,1,0,1,100\n");
    EXPECT_NE(e.find("fields.csv:2: 10 fields, the header has 11"), std::string::npos) << e;
    e = errorOf("header.csv", "x,y,z\n1,2,3\n");
    EXPECT_NE(e.find("header.csv:1: not a fenestra sensor file"), std::string::npos) << e;
    e = errorOf("empty.csv", "");
    EXPECT_NE(e.find("empty.csv:1: not a fenestra sensor file"), std::string::npos) << e;
    e = errorOf("norows.csv", kHeader + "\n");
    EXPECT_NE(e.find("norows.csv: no sensor cells"), std::string::npos) << e;
    e = errorOf("area.csv", kHeader + "\nfloor,0,0,0,0,0,1,0,0,100,1\n");
    EXPECT_NE(e.find("area.csv:2: area_m2 0 must be positive"), std::string::npos) << e;
    e = errorOf("normal.csv", kHeader + "\nfloor,0,0,0,0,0,0,0,1,100,1\n");
    EXPECT_NE(e.find("normal.csv:2: the normal (0, 0, 0) is not a direction"), std::string::npos) << e;
    e = errorOf("inf.csv", kHeader + "\nfloor,0,0,0,0,0,1,0,1,inf,1\n");
    EXPECT_NE(e.find("inf.csv:2: illuminance_lux 'inf'"), std::string::npos) << e;
    e = errorOf("quote.csv", kHeader + "\n\"floor,0,0,0,0,0,1,0,1,100,1\n");
    EXPECT_NE(e.find("quote.csv:2: a quoted field is not closed"), std::string::npos) << e;
    e = errorOf("noname.csv", kHeader + "\n,0,0,0,0,0,1,0,1,100,1\n");
    EXPECT_NE(e.find("noname.csv:2: the sensor name is empty"), std::string::npos) << e;
    try {
        readSensorCsv("/no/such/sensors.csv");
        ADD_FAILURE() << "no error";
    } catch (const Error& ex) {
        EXPECT_NE(std::string(ex.what()).find("/no/such/sensors.csv: cannot open"), std::string::npos) << ex.what();
    }
    // what the file holds is quoted printable: the message stays one line
    e = errorOf("ctl.csv", "a\x01\rb\n");
    EXPECT_NE(e.find("a\\x01\\x0db"), std::string::npos) << e;
}

std::string row(const std::string& sensor, double x, double y, double z, double nx, double ny, double nz, double lux)
{
    return cat(sensor, ",c,", x, ",", y, ",", z, ",", nx, ",", ny, ",", nz, ",0.25,", lux, ",1\n");
}

TEST(SensorPlanes, OnePlanePerSensorAndNormalInPictureCoordinates)
{
    const double tilt = std::sin(2.0 * std::acos(-1.0) / 180.0);  // 2°: still the desk's plane
    const std::string text = kHeader + "\n" + row("desk", 1.0, 0.8, -3.0, 0, 1, 0, 100) +
                             row("wall", 2.0, 1.5, 4.0, 0, 0, 1, 50) +   // faces south
                             row("desk", 2.0, 0.8, -2.0, tilt, 1, 0, 200) +
                             row("wall", -1.0, 1.2, 3.0, -1, 0, 0, 60) +  // faces west
                             row("wall", 3.0, 0.5, 4.0, 0, 0, 1, 70);
    const SensorFile f = readSensorCsv(writeFile("planes.csv", text));
    const std::vector<SensorPlane> planes = sensorPlanes(f);
    ASSERT_EQ(planes.size(), 3u);

    const SensorPlane& desk = planes[0];
    EXPECT_EQ(desk.sensor, "desk");
    EXPECT_TRUE(desk.horizontal);
    EXPECT_EQ(facing(desk), "up");
    EXPECT_EQ(desk.count, 1);
    ASSERT_EQ(desk.rows, (std::vector<std::size_t>{0, 2}));
    EXPECT_DOUBLE_EQ(desk.u[0], 1.0);  // plan: u = x (east right), v = z (north up)
    EXPECT_DOUBLE_EQ(desk.v[0], -3.0);
    EXPECT_DOUBLE_EQ(desk.u[1], 2.0);
    EXPECT_DOUBLE_EQ(desk.v[1], -2.0);

    const SensorPlane& south = planes[1];
    EXPECT_EQ(south.sensor, "wall");
    EXPECT_FALSE(south.horizontal);
    EXPECT_EQ(facing(south), "south");
    EXPECT_EQ(south.index, 1);
    EXPECT_EQ(south.count, 2);
    ASSERT_EQ(south.rows, (std::vector<std::size_t>{1, 4}));
    // seen from the south: east (+x) to the right, up (+y) up
    EXPECT_NEAR(south.u[0], 2.0, 1e-12);
    EXPECT_NEAR(south.v[0], -1.5, 1e-12);
    EXPECT_NEAR(south.u[1], 3.0, 1e-12);
    EXPECT_NEAR(south.v[1], -0.5, 1e-12);

    const SensorPlane& west = planes[2];
    EXPECT_EQ(facing(west), "west");
    EXPECT_EQ(west.index, 2);
    EXPECT_EQ(west.count, 2);
    // seen from the west, looking east: south (+z) to the right
    EXPECT_NEAR(west.u[0], 3.0, 1e-12);
    EXPECT_NEAR(west.v[0], -1.2, 1e-12);
}

}  // namespace
}  // namespace fen
