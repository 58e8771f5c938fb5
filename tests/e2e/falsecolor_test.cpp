// falsecolor_test.cpp — `fenestra falsecolor` as a user runs it: a sensor file written here gives
// one PNG per plane named by the documented rule, with the mean and uniformity reported; a tiny
// EXR gives its luminance on a log scale; bad input is one line naming the file (and line) or
// option, status 1, or 2 for a usage error, and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include <stb/stb_image.h>

#include "e2e/cli_run.h"
#include "io/exr_io.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

using test::CliRun;
using test::expectError;
using test::run;

const std::string kHeader = "sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux";
const std::string kDfColumns = ",daylight_factor_pct,daylight_factor_std_err_pct";

std::string write(const std::string& path, const std::string& bytes)
{
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// A desk of 3 x 2 cells of 0.5 m (100 .. 600 lux, DF 1 .. 6 %), two cells on the south wall and
// one on the west wall (one sensor, "wall": two planes).
std::string sensorFile(const std::string& dir, bool daylightFactor)
{
    std::string text = kHeader + (daylightFactor ? kDfColumns : "") + "\n";
    const auto row = [&](const std::string& sensor, int cell, double x, double y, double z, const char* normal,
                         double lux) {
        text += cat(sensor, ",", cell, ",", x, ",", y, ",", z, ",", normal, ",0.25,", lux, ",", lux / 100);
        if (daylightFactor)
            text += cat(",", lux / 100, ",0.01");
        text += "\n";
    };
    int cell = 0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i, ++cell)
            row("desk", cell, 0.25 + 0.5 * i, 0.8, -1.0 + 0.5 * j, "0,1,0", 100.0 * (cell + 1));
    row("wall", 0, 0.25, 1.0, 2.0, "0,0,1", 50);
    row("wall", 1, 0.75, 1.0, 2.0, "0,0,1", 70);
    row("wall", 2, -1.0, 1.0, 1.0, "-1,0,0", 20);
    return write(dir + (daylightFactor ? "/df.csv" : "/lux.csv"), text);
}

struct Png {
    int width = 0, height = 0;
};
Png readPng(const std::string& path)
{
    Png p;
    int channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(path.c_str(), &p.width, &p.height, &channels, 3),
                                                           stbi_image_free);
    EXPECT_NE(pixels, nullptr) << path << " is not a PNG";
    return p;
}

TEST(CliFalseColor, SensorPlanesOnePngEach)
{
    const std::string dir = test::tempDir("cli-falsecolor");
    const std::string csv = sensorFile(dir, true);
    const CliRun r = run("falsecolor " + csv + " --out " + dir + "/new/plan.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    // the first plane is OUT.png, the others OUT-<sensor>-<k>.png (the sensor has two planes)
    for (const char* f : {"/new/plan.png", "/new/plan-wall-1.png", "/new/plan-wall-2.png"}) {
        const Png p = readPng(dir + f);
        EXPECT_GT(p.width, p.height) << f;  // the legend beside the picture
        EXPECT_GT(p.width, 600) << f;
    }
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir + "/new"), {}), 3);
    // the desk: equal areas, mean 350 lux, min/mean 100 / 350
    EXPECT_NE(r.out.find("plan.png: illuminance of desk, 6 cells, mean 350 lux  min/mean 0.29"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("plan-wall-1.png: illuminance of wall (facing south), 2 cells, mean 60 lux  min/mean 0.83"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("plan-wall-2.png: illuminance of wall (facing west), 1 cell, mean 20 lux  min/mean 1.00"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("scale 0..640 lux (linear)"), std::string::npos) << r.out;  // 600 / 8 = 75 -> steps of 80

    // the daylight factor, a scale given, a title; the files are replaced
    const CliRun d = run("falsecolor " + csv + " --out " + dir + "/new/plan.png --quantity df --max 10 --steps 5 "
                         "--title 'DF, level 1'");
    ASSERT_EQ(d.status, 0) << d.err;
    EXPECT_NE(d.out.find("plan.png: daylight factor of desk, 6 cells, mean 3.5 %  min/mean 0.29"), std::string::npos)
        << d.out;
    EXPECT_NE(d.out.find("scale 0..10 % DF (linear)"), std::string::npos) << d.out;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir + "/new"), {}), 3);

    // --log: whole decades around the data
    const CliRun l = run("falsecolor " + csv + " --out " + dir + "/log.png --log");
    ASSERT_EQ(l.status, 0) << l.err;
    EXPECT_NE(l.out.find("scale 10..1k lux (log)"), std::string::npos) << l.out;
}

TEST(CliFalseColor, ExrLuminanceOnALogScale)
{
    const std::string dir = test::tempDir("cli-falsecolor-exr");
    Image img(32, 16);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c)
                img.at(x, y)[c] = static_cast<float>(5.0 * std::pow(100.0, x / 31.0));  // grey: Y = 5 .. 500
    const std::string exr = write(dir + "/room.exr", encodeExr(img));
    const CliRun r = run("falsecolor " + exr + " --out " + dir + "/room.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("room.png: luminance of " + exr + ", 32 x 16, scale 1..1k cd/m² (log)"), std::string::npos)
        << r.out;
    const Png p = readPng(dir + "/room.png");
    EXPECT_GE(p.width, 320 + 60);  // enlarged 10 times, the legend beside

    const CliRun lin = run("falsecolor " + exr + " --out " + dir + "/lin.png --linear --min 0 --max 1000 --steps 4");
    ASSERT_EQ(lin.status, 0) << lin.err;
    EXPECT_NE(lin.out.find("scale 0..1k cd/m² (linear)"), std::string::npos) << lin.out;
}

TEST(CliFalseColor, BadInputIsOneLineNamingTheProblem)
{
    const std::string dir = test::tempDir("cli-falsecolor-bad");
    const std::string out = " --out " + dir + "/out/x.png";
    const std::string lux = sensorFile(dir, false);
    expectError(run("falsecolor /no/such/plan.csv" + out), 1, "/no/such/plan.csv");
    const std::string bad = write(dir + "/bad.csv", kHeader + "\nfloor,0,0,0,0,0,1,0,1,100,1\nfloor,1,0,0,0,0,1,0,1,lots,1\n");
    expectError(run("falsecolor " + bad + out), 1, "bad.csv:3: illuminance_lux 'lots' is not a number");
    const std::string noHeader = write(dir + "/nohead.csv", "floor,0,0,0,0,0,1,0,1,100,1\n");
    expectError(run("falsecolor " + noHeader + out), 1, "nohead.csv:1: not a fenestra sensor file");
    const std::string badExr = write(dir + "/bad.exr", "not an EXR file");
    expectError(run("falsecolor " + badExr + out), 1, "bad.exr");
    expectError(run("falsecolor " + dir + out), 1, "give a .exr image or a .csv sensor file");
    std::filesystem::create_directory(dir + "/folder.csv");
    expectError(run("falsecolor " + dir + "/folder.csv" + out), 1, "folder.csv: the input must be a regular file");
    expectError(run("falsecolor " + lux + out + " --quantity df"), 1, "lux.csv: --quantity df needs the columns");
    expectError(run("falsecolor " + lux + out + " --quantity lux"), 1, "--quantity 'lux'");
    expectError(run("falsecolor " + badExr + out + " --quantity df"), 1, "--quantity df: only for a .csv");
    expectError(run("falsecolor " + lux + out + " --min 500 --max 100"), 1, "--min 500 must be below --max 100");
    expectError(run("falsecolor " + lux + out + " --log --min 0"), 1, "--min 0: a logarithmic scale");
    expectError(run("falsecolor " + badExr + out + " --min -1"), 1, "--min -1: a logarithmic scale");
    expectError(run("falsecolor " + lux + out + " --steps 0"), 1, "--steps 0");
    expectError(run("falsecolor " + lux + " --out " + dir + "/x.jpg"), 1, "--out");
    // usage errors
    expectError(run("falsecolor " + lux + out + " --log --linear"), 2, "--l");
    expectError(run("falsecolor " + lux), 2, "--out");
    expectError(run("falsecolor " + lux + out + " --min abc"), 2, "--min");
    expectError(run("falsecolor " + lux + out + " --steps 2.5"), 2, "--steps");
    EXPECT_FALSE(std::filesystem::exists(dir + "/out/x.png"));
}

}  // namespace
}  // namespace fen
