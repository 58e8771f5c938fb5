// ground_test.cpp — the ground's glow below the horizon (DESIGN.md §1 "Sky", sky/sky_spec.h): the
// sky's table extended over the whole sphere integrates to the right illuminance facing up (the
// sky's alone) and facing down (pi L_g = rho_g E_h, E_h the sky's and the sun's horizontal
// illuminance); with the ground off the table is exactly what it was; the step at the horizon is
// the table's only new shape; bad albedos in the file and on the command line are one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "support/error_of.h"
#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "sky/sky_sun_options.h"
#include "sky/sky_tables.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

constexpr double kHalfPi = M_PI / 2;
const glm::dvec3 kUp(0, 1, 0), kDown(0, -1, 0);

using test::errorOf;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A scene with no geometry: only its sky and sun matter here.
Scene skyScene(SkySpec::Type type, double groundAlbedo, bool sun)
{
    Scene s;
    s.source = "test";
    s.sky.where = "test: extras.sky";
    s.sky.type = type;
    s.sky.groundAlbedo = groundAlbedo;
    if (type == SkySpec::Type::Uniform) {
        s.sky.luminance_cd_m2 = 1000.0;
    } else if (type == SkySpec::Type::Cie) {
        s.sky.cieType = 12;
        s.sky.zenithLuminance_cd_m2 = 4000.0;
        s.sky.sunAltitudeDeg = 30.0;
        s.sky.sunAzimuthDeg = 135.0;
    } else {
        s.sky.zenithDeg = {0, 10, 35, 60, 80, 90};
        s.sky.azimuthDeg = {0, 45, 100, 180, 270, 360};
        for (std::size_t i = 0; i < 6; ++i) {
            std::vector<double> row;
            for (std::size_t j = 0; j < 6; ++j)
                row.push_back(i == 0 ? 500.0 : 200.0 + 400.0 * ((i * 7 + (j % 5) * 3) % 5) + 100.0 * i);
            s.sky.table_cd_m2.push_back(row);
        }
    }
    if (sun) {
        s.sun.present = true;
        s.sun.travelDirection = -skyDirection((90.0 - 30.0) * M_PI / 180.0, 135.0 * M_PI / 180.0);
        s.sun.illuminanceRgb_lux = glm::dvec3(60000.0, 50000.0, 40000.0);  // Y = 51,866 lux
    }
    return s;
}

TEST(GroundGlow, TableIntegratesToTheHorizontalIlluminanceUpAndDown)
{
    for (SkySpec::Type type : {SkySpec::Type::Uniform, SkySpec::Type::Cie, SkySpec::Type::Table})
        for (bool sun : {false, true}) {
            SCOPED_TRACE(testing::Message() << "sky type " << static_cast<int>(type) << ", sun " << sun);
            const double rho = 0.3;
            const Scene s = skyScene(type, rho, sun);
            const auto g = buildSky(s);
            const auto alone = buildSky(skyScene(type, 0.0, sun));
            ASSERT_TRUE(g && alone);
            ASSERT_TRUE(g->hasGround());
            ASSERT_FALSE(alone->hasGround());
            // E_h: the sky's over its table (independently: pi L for the uniform sky) and the sun's
            // normal illuminance's luminance times sin(30 degrees).
            const double sky = alone->illuminance(kUp);
            if (type == SkySpec::Type::Uniform) {
                EXPECT_NEAR(sky, M_PI * 1000.0, 1e-9 * M_PI * 1000.0);
            }
            const double sunY = 0.2126 * 60000.0 + 0.7152 * 50000.0 + 0.0722 * 40000.0;
            const double Eh = sky + (sun ? sunY * 0.5 : 0.0);
            EXPECT_NEAR(groundHorizontalIlluminance(*alone, s.sun), Eh, 1e-9 * Eh);
            const double Lg = rho * Eh / M_PI;
            EXPECT_NEAR(g->groundLuminance(), Lg, 1e-12 * Lg);
            // Facing up: the sky alone (the ground's rows face down); facing down: pi L_g = rho E_h.
            EXPECT_NEAR(g->illuminance(kUp), sky, 1e-9 * sky);
            EXPECT_NEAR(g->illuminance(kDown), rho * Eh, 1e-9 * rho * Eh);
            EXPECT_NEAR(g->illuminance({0, -7, 0}), rho * Eh, 1e-9 * rho * Eh);  // any length
            // A vertical plane: half of each hemisphere's.
            for (const glm::dvec3 n : {glm::dvec3(1, 0, 0), glm::dvec3(0.3, 0, -1)}) {
                const double expect = alone->illuminance(n) + M_PI * Lg / 2;
                EXPECT_NEAR(g->illuminance(n), expect, 1e-6 * expect);
            }
            // A plane tilted 120 degrees from facing up, below the horizon: pi L_g (1 + cos 60) / 2
            // from the ground, and the sky's share it sees.
            const glm::dvec3 tilted(std::sin(2 * M_PI / 3), std::cos(2 * M_PI / 3), 0.0);
            EXPECT_NEAR(g->illuminance(tilted), alone->illuminance(tilted) + M_PI * Lg * 0.75,
                        1e-6 * (alone->illuminance(tilted) + M_PI * Lg));
            // ∫ g dw: the sky's and 2 pi L_g.
            EXPECT_NEAR(g->integral(), alone->integral() + 2 * M_PI * Lg, 1e-9 * g->integral());
            // Lookups: every direction below the horizon sees L_g, exactly the table's; the horizon
            // itself is sky.
            const double table = g->groundLuminance();
            for (double t : {kHalfPi + 1e-9, 1.8, 2.5, M_PI - 1e-9, M_PI})
                for (double p : {0.0, 1.0, 4.0})
                    EXPECT_EQ(g->eval(t, p), table) << t << " " << p;
            EXPECT_EQ(g->evalDirection({0.3, -1e-9, 0.2}), table);
            EXPECT_EQ(g->evalDirection(kDown), table);
            for (double p : {0.0, 1.0, 4.0}) {
                EXPECT_EQ(g->eval(kHalfPi, p), alone->eval(kHalfPi, p));
                EXPECT_EQ(g->eval(1.0, p), alone->eval(1.0, p));
            }
            EXPECT_EQ(alone->evalDirection(kDown), 0.0);
        }
}

TEST(GroundGlow, ASunBelowTheHorizonAddsNothing)
{
    Scene s = skyScene(SkySpec::Type::Uniform, 0.5, true);
    s.sun.travelDirection = glm::dvec3(0.0, 0.6, -0.8);  // towards the sun: 37 degrees below
    const auto g = buildSky(s);
    ASSERT_TRUE(g);
    EXPECT_NEAR(g->groundLuminance(), 0.5 * 1000.0, 1e-9 * 500.0);  // rho (pi L) / pi
}

TEST(GroundGlow, OffLeavesTheTableAsItWas)
{
    for (SkySpec::Type type : {SkySpec::Type::Uniform, SkySpec::Type::Cie, SkySpec::Type::Table}) {
        const Scene s = skyScene(type, 0.0, true);
        const auto g = buildSky(s);
        const auto old = buildSky(s.sky);  // the sky alone, as every render built it before grounds
        ASSERT_TRUE(g && old);
        EXPECT_FALSE(g->hasGround());
        EXPECT_EQ(g->groundLuminance(), 0.0);
        EXPECT_EQ(g->theta(), old->theta());
        EXPECT_EQ(g->phi(), old->phi());
        EXPECT_EQ(g->values(), old->values());
        EXPECT_EQ(g->theta().back(), kHalfPi);
        const SkyTables a = makeSkyTables(g), b = makeSkyTables(old);
        EXPECT_EQ(a.theta, b.theta);
        EXPECT_EQ(a.values, b.values);
        EXPECT_EQ(a.cellSin, b.cellSin);
        EXPECT_EQ(a.maxLuminance_cd_m2, b.maxLuminance_cd_m2);
    }
    // No sky: no ground either, whatever the albedo.
    EXPECT_FALSE(buildSky(skyScene(SkySpec::Type::None, 0.5, true)));
    // The sky alone refuses a ground (it would lose the sun's part silently).
    EXPECT_TRUE(contains(errorOf([] { buildSky(skyScene(SkySpec::Type::Uniform, 0.2, true).sky); }),
                         "test: extras.sky.ground_albedo"));
}

TEST(GroundGlow, TheHorizonStepIsTheTablesOnlyNewShape)
{
    const Scene s = skyScene(SkySpec::Type::Table, 0.4, true);
    const Goniogram g = *buildSky(s);
    const Goniogram alone = *buildSky(skyScene(SkySpec::Type::Table, 0.0, true));
    // The sky's rows, pi/2 again, and 90 rows of 1 degree down to pi, on the same phi nodes.
    ASSERT_EQ(g.thetaCount(), alone.thetaCount() + Goniogram::kGroundThetaSteps + 1);
    EXPECT_EQ(g.phi(), alone.phi());
    const std::size_t h = alone.thetaCount() - 1;
    EXPECT_EQ(g.theta()[h], kHalfPi);
    EXPECT_EQ(g.theta()[h + 1], kHalfPi);
    EXPECT_EQ(g.theta().back(), M_PI);
    for (std::size_t i = h + 1; i + 1 < g.thetaCount(); ++i)
        EXPECT_NEAR(g.theta()[i + 1] - g.theta()[i], M_PI / 180, 1e-12);
    // The zero-width cell between the two horizon rows holds nothing, so nothing draws it.
    const SkyTables t = makeSkyTables(g);
    const std::size_t C = g.phiCount() - 1;
    for (std::size_t j = 0; j < C; ++j) {
        EXPECT_EQ(g.cellIntegralSin(h, j), 0.0);
        EXPECT_EQ(g.cellIntegralFlat(h, j), 0.0);
        EXPECT_EQ(t.cellSin[h * C + j], 0.0);
        EXPECT_EQ(g.cellClippedIntegral(h, j, kUp), 0.0);
        EXPECT_EQ(glm::length(g.cellDirectionIntegral(h, j)), 0.0);
        EXPECT_GT(t.cellSin[(h + 1) * C + j], 0.0);
    }
    EXPECT_EQ(t.maxLuminance_cd_m2, std::max(makeSkyTables(alone).maxLuminance_cd_m2, g.groundLuminance()));
    // Refining keeps the step and the function.
    const Goniogram r = g.refined(0.3 * M_PI / 180, 0.2);
    EXPECT_TRUE(r.hasGround());
    for (double th : {0.3, 1.2, kHalfPi, kHalfPi + 0.01, 2.0, 3.0})
        for (double p : {0.1, 2.0, 5.0})
            EXPECT_NEAR(r.eval(th, p), g.eval(th, p), 1e-9 * (1 + g.eval(th, p)));
    EXPECT_NEAR(r.illuminance(kDown), g.illuminance(kDown), 1e-9 * g.illuminance(kDown));
    // The constructor's rules for a whole sphere.
    const std::vector<double> ph = {0, 3, 2 * M_PI};
    auto err = [&](std::vector<double> th, double nadir2 = 1.0) {
        std::vector<double> v(th.size() * 3, 1.0);
        v[v.size() - 2] = nadir2;
        return errorOf([&] { Goniogram(th, ph, v, "where-tag"); });
    };
    EXPECT_EQ(err({0, kHalfPi, kHalfPi, M_PI}), "(no error)");
    EXPECT_TRUE(contains(err({0, 1.0, 2.0, M_PI}), "must hold pi/2 twice")) << err({0, 1.0, 2.0, M_PI});
    EXPECT_TRUE(contains(err({0, kHalfPi, 2.0, M_PI}), "must hold pi/2 twice"));
    EXPECT_TRUE(contains(err({0, kHalfPi, kHalfPi, kHalfPi, M_PI}), "strictly increasing"));
    EXPECT_TRUE(contains(err({0, kHalfPi, kHalfPi, 2.5, 2.0, M_PI}), "strictly increasing"));
    EXPECT_TRUE(contains(err({0, kHalfPi, kHalfPi, M_PI}, 2.0), "theta = pi is one direction"));
    EXPECT_TRUE(contains(errorOf([&] { g.withGround(1.0); }), "has a ground already"));
    EXPECT_TRUE(contains(errorOf([&] { alone.withGround(-1.0, "w"); }), "w: the ground's luminance"));
    EXPECT_TRUE(contains(errorOf([&] { alone.withGround(NAN, "w"); }), "w: the ground's luminance"));
}

// A small lit scene file whose sky carries `albedo` (a JSON value) as ground_albedo.
std::string sceneWithGround(const std::string& dir, const std::string& name, const nlohmann::json& albedo)
{
    test::GltfWriter w;
    w.addMeshNode("plate", {{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}}});
    w.doc()["scenes"][0]["extras"] = {{"sky", {{"type", "uniform"}, {"luminance", 100}, {"ground_albedo", albedo}}}};
    return w.write(dir + "/" + name);
}

TEST(GroundGlow, BadAlbedosAreOneLineErrorsNamingTheKeyOrOption)
{
    const std::string dir = test::tempDir("ground-albedo");
    EXPECT_EQ(loadGltf(sceneWithGround(dir, "ok.gltf", 0.25)).sky.groundAlbedo, 0.25);
    EXPECT_EQ(loadGltf(sceneWithGround(dir, "one.gltf", 1)).sky.groundAlbedo, 1.0);
    const std::pair<nlohmann::json, const char*> file[] = {
        {1.5, "bad0.gltf: scenes[0].extras.sky.ground_albedo: 1.5 is outside [0, 1]"},
        {-0.1, "bad1.gltf: scenes[0].extras.sky.ground_albedo: -0.1 is outside [0, 1]"},
        {"0.2", "bad2.gltf: scenes[0].extras.sky.ground_albedo: must be a number"},
        {nullptr, "bad3.gltf: scenes[0].extras.sky.ground_albedo: must be a number"},
    };
    int n = 0;
    for (const auto& [value, expect] : file) {
        const std::string e = errorOf([&] { loadGltf(sceneWithGround(dir, "bad" + std::to_string(n++) + ".gltf", value)); });
        EXPECT_TRUE(contains(e, expect)) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    // The command line: a number in [0, 1], overriding the file's; 0 turns the ground off.
    Scene s = loadGltf(sceneWithGround(dir, "cli.gltf", 0.25));
    SkySunOptions o;
    o.groundAlbedo = 0.0;
    applySkySunOptions(o, &s);
    EXPECT_EQ(s.sky.groundAlbedo, 0.0);
    o.groundAlbedo = 0.6;
    applySkySunOptions(o, &s);
    EXPECT_EQ(s.sky.groundAlbedo, 0.6);
    // --sky replaces the sky, not the ground the file (or the command line) gave it.
    SkySunOptions sky;
    sky.sky = "cie:1";
    sky.skyZenith_cd_m2 = 100.0;
    applySkySunOptions(sky, &s);
    EXPECT_EQ(s.sky.type, SkySpec::Type::Cie);
    EXPECT_EQ(s.sky.groundAlbedo, 0.6);
    for (double bad : {1.5, -0.2, double(NAN)}) {
        Scene t = loadGltf(sceneWithGround(dir, "cli2.gltf", 0.25));
        SkySunOptions b;
        b.groundAlbedo = bad;
        const std::string e = errorOf([&] { applySkySunOptions(b, &t); });
        EXPECT_TRUE(contains(e, "--ground-albedo ")) << e;
        EXPECT_TRUE(contains(e, "must be in 0..1")) << e;
        EXPECT_EQ(t.sky.groundAlbedo, 0.25);
    }
    // No sky to put a ground under.
    Scene t = loadGltf(sceneWithGround(dir, "cli3.gltf", 0.25));
    SkySunOptions none;
    none.sky = "none";
    none.groundAlbedo = 0.3;
    EXPECT_TRUE(contains(errorOf([&] { applySkySunOptions(none, &t); }), "--ground-albedo: the scene has no sky"));
    none.groundAlbedo = 0.0;
    applySkySunOptions(none, &t);  // off is fine
    EXPECT_EQ(t.sky.type, SkySpec::Type::None);
}

}  // namespace
}  // namespace fen
