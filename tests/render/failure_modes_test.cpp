// failure_modes_test.cpp — the shipped scenes where portal emission fails because light reaches
// the windows after reflecting off outside surfaces (scenes/README.md): the sunlit snow around
// the house, the sunlit wall across the courtyard. Portal emission through correctly marked
// windows is biased low there, by more than 4 sigma of the combined standard error, and its
// complement paths say so (emission.unreached); adaptive emission agrees with uniform emission
// within 4 sigma over either base, the portal base included: its disk share finds the
// reflected light. (The other failures: a wrong portal, the gap under the inner room's door, and
// an unmarked window, in adaptive_test.cpp; a rare light path, ibid.) Small images (48 x 36) and
// the whole image's mean keep the budgets small.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scene/gltf_load.h"
#include "support/cl_fixture.h"
#include "support/window_rooms.h"

namespace fen {
namespace {

using test::expectAgree;
using test::Measured;
using test::measure;

const Roi kWhole{0, 0, 48, 36};
// The comparisons' power: a combined standard error up to 12 % of the mean still shows the
// failures documented here (portal emission 50 % and 95 % low) at more than 4 sigma.
constexpr double kMaxRelSe = 0.12;

struct Case {
    const char* scene;
    std::uint64_t uniformPaths, portalPaths, adaptivePaths;
};

class ReflectedLight : public ::testing::TestWithParam<Case> {};

TEST_P(ReflectedLight, PortalsMissItAndSayItAdaptiveDoesNot)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Case& c = GetParam();
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/" + c.scene);
    const Measured u = measure(*ctx, scene, EmissionMethod::Uniform, c.uniformPaths, PortalOverlap::Reject, "", 48,
                               36, kWhole);
    // A quarter of the portal paths estimate the complement (the default is 5 %): enough for its
    // share to be measured against the shortfall at this budget; the image is the portals' alone.
    EmissionSettings pe;
    pe.method = EmissionMethod::Portal;
    pe.portal.complement = 0.25;
    const Measured p = measure(*ctx, scene, pe, c.portalPaths, 48, 36, kWhole);
    std::printf("[ failure  ] %s: uniform %.5g +- %.3g, portal %.5g +- %.3g (%.2fx), unreached %s\n", c.scene, u.mean,
                u.se, p.mean, p.se, p.mean / u.mean, p.emission["unreached"].dump().c_str());
    EXPECT_GT(u.mean - p.mean, 4.0 * std::hypot(u.se, p.se)) << c.scene << ": portal emission should be low";
    // The complement measures the missing share of the light at the camera: unbiased, so it must
    // account for the shortfall within its own and the means' noise.
    const double share = p.emission["unreached"]["share"], shareSe = p.emission["unreached"]["std_err"];
    EXPECT_GT(share, 4.0 * shareSe) << c.scene << ": the complement must see the light portals miss";
    const double missing = 1.0 - p.mean / u.mean;
    const double missingSe = p.mean / u.mean * std::hypot(u.se / u.mean, p.se / p.mean);
    EXPECT_NEAR(share, missing, 4.0 * std::hypot(shareSe, missingSe))
        << c.scene << ": the reported share and the measured shortfall disagree";
    for (EmissionMethod base : {EmissionMethod::Uniform, EmissionMethod::Portal}) {
        EmissionSettings e;
        e.method = EmissionMethod::Adaptive;
        e.adaptive.base = base;
        const Measured a = measure(*ctx, scene, e, c.adaptivePaths, 48, 36, kWhole);
        expectAgree(a, u, base == EmissionMethod::Uniform ? "adaptive (uniform base) vs uniform"
                                                          : "adaptive (portal base) vs uniform",
                    "failure", kMaxRelSe);
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ReflectedLight,
                         ::testing::Values(Case{"house_snow.gltf", 8u << 20, 4u << 20, 16u << 20},
                                           Case{"courtyard.gltf", 4u << 20, 2u << 20, 8u << 20}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             std::string n = info.param.scene;
                             return n.substr(0, n.find('.'));
                         });

}  // namespace
}  // namespace fen
