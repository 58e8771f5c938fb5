// determinism_test.cpp — the same seed, scene, settings and device give a bit-identical image
// (counter-based random numbers + 128-bit fixed-point accumulation); another seed does not.
#include <gtest/gtest.h>

#include <cstring>

#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"

namespace fen {
namespace {

RenderResult renderRoom(ocl::Context& ctx, std::uint32_t seed, std::uint32_t pool,
                        EmissionMethod method = EmissionMethod::Uniform,
                        std::optional<int> rouletteDepth = std::nullopt)
{
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/room.gltf");
    const auto sky = buildSky(scene.sky);
    RenderSettings s;
    s.paths = 1u << 20;
    s.seed = seed;
    s.poolSize = pool;
    s.emission.method = method;
    s.rouletteDepth = rouletteDepth;
    s.kernels = KernelMode::Wavefront;  // the pool is the wavefront's (fused: fused_test.cpp)
    Renderer r(ctx, scene, sky, scene.cameras.at(0), 96, 72, s);
    return r.render();
}

TEST(Determinism, SameSeedGivesBitIdenticalImages)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const RenderResult a = renderRoom(*ctx, 7, 1u << 16);
    // A different pool size changes which slot traces which path and in what order pixels are
    // added to: the image must not change.
    const RenderResult b = renderRoom(*ctx, 7, 1u << 15);
    ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * 4));
    EXPECT_EQ(a.counts.extensionRays, b.counts.extensionRays);
    EXPECT_EQ(a.counts.shadowRays, b.counts.shadowRays);
    double sum = 0.0;
    for (float v : a.image.rgb)
        sum += v;
    EXPECT_GT(sum, 0.0) << "the test scene rendered black";
    const RenderResult c = renderRoom(*ctx, 8, 1u << 16);
    EXPECT_NE(0, std::memcmp(a.image.rgb.data(), c.image.rgb.data(), a.image.rgb.size() * 4));
}

// Settings that leave the roulette depth to the method (unset, RenderSettings' default) render what
// the method's default depth renders, bit for bit: the renderer hands the kernels the resolved
// depth.
TEST(Determinism, TheMethodsRouletteDefaultIsTheDepthRendered)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    for (EmissionMethod m : {EmissionMethod::Uniform, EmissionMethod::Portal}) {
        SCOPED_TRACE(methodName(m));
        const RenderResult byDefault = renderRoom(*ctx, 7, 1u << 16, m);
        const RenderResult given = renderRoom(*ctx, 7, 1u << 16, m, defaultRouletteDepth(m));
        EXPECT_EQ(0, std::memcmp(byDefault.image.rgb.data(), given.image.rgb.data(),
                                 byDefault.image.rgb.size() * 4));
        EXPECT_EQ(byDefault.counts.extensionRays, given.counts.extensionRays);
        EXPECT_EQ(byDefault.rouletteDepth, defaultRouletteDepth(m));  // what the JSON reports
        const RenderResult other = renderRoom(*ctx, 7, 1u << 16, m, defaultRouletteDepth(m) + 1);
        EXPECT_NE(byDefault.counts.extensionRays, other.counts.extensionRays);
    }
    EXPECT_EQ(defaultRouletteDepth(EmissionMethod::Uniform), 5);
    EXPECT_EQ(defaultRouletteDepth(EmissionMethod::Portal), 3);
    EXPECT_EQ(defaultRouletteDepth(EmissionMethod::Adaptive), 3);
}

}  // namespace
}  // namespace fen
