// golden_test.cpp — the emission-strategy seam changed no image: uniform and portal renders with
// the same seed are identical to the ones made before it (tests/data/golden/, how they were made
// and the tolerance on other devices: tests/data/golden/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "io/exr_io.h"
#include "render/renderer.h"
#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"

namespace fen {
namespace {

constexpr const char* kRecordedOn = "pthread-skylake-avx512-AMD EPYC";

struct Golden {
    const char* scene;
    EmissionMethod method;
    PortalOverlap overlap;
    const char* file;
};

class GoldenImage : public ::testing::TestWithParam<Golden> {};

TEST_P(GoldenImage, UnchangedByTheStrategySeam)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Golden& g = GetParam();
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/" + g.scene);
    const auto sky = buildSky(scene.sky);
    RenderSettings s;
    s.emission.method = g.method;
    s.emission.portal.overlap = g.overlap;
    s.emission.portal.complement = 0.0;  // the images were made before the complement existed
    s.maxBounces = 64;                  // ... and before the default cap rose to 1024
    s.rouletteDepth = 0;                // ... and before roulette began at the third interaction
    s.cameraPass = CameraPassMode::Fixed;  // ... and before the camera pass balanced its samples
    s.paths = 1048576;
    s.seed = 7;
    Renderer r(*ctx, scene, sky, scene.cameras.at(0), 96, 72, s);
    const Image img = r.render().image;
    const Image ref = readExr(std::string(FEN_TEST_DATA_DIR) + "/golden/" + g.file);
    ASSERT_EQ(img.rgb.size(), ref.rgb.size());
    if (ctx->info().device.getInfo<CL_DEVICE_NAME>() == kRecordedOn) {
        EXPECT_EQ(0, std::memcmp(img.rgb.data(), ref.rgb.data(), img.rgb.size() * 4)) << g.file;
        return;
    }
    std::size_t off = 0;
    double sum = 0.0, sumRef = 0.0;
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        off += std::fabs(img.rgb[i] - ref.rgb[i]) > 1e-4 * std::fabs(ref.rgb[i]);
        sum += img.rgb[i];
        sumRef += ref.rgb[i];
    }
    std::printf("[ golden   ] %s on another device: %zu of %zu values differ beyond 1e-4, mean %+.2g\n",
                g.file, off, img.rgb.size(), sum / sumRef - 1.0);
    EXPECT_LE(off, img.rgb.size() / 1000) << g.file;
    EXPECT_NEAR(sum / sumRef, 1.0, 1e-5) << g.file;
}

INSTANTIATE_TEST_SUITE_P(
    Renders, GoldenImage,
    ::testing::Values(Golden{"room.gltf", EmissionMethod::Uniform, PortalOverlap::Reject, "room_uniform.exr"},
                      Golden{"inner_room.gltf", EmissionMethod::Portal, PortalOverlap::Reject, "inner_room_portal.exr"},
                      Golden{"bay_window.gltf", EmissionMethod::Portal, PortalOverlap::Reject, "bay_window_portal.exr"},
                      Golden{"bay_window.gltf", EmissionMethod::Portal, PortalOverlap::Weight,
                             "bay_window_portal_weight.exr"}),
    [](const ::testing::TestParamInfo<Golden>& info) {
        std::string n = info.param.file;
        n = n.substr(0, n.size() - 4);
        for (char& c : n)
            if (c == '_')
                c = 'X';
        return n;
    });

}  // namespace
}  // namespace fen
