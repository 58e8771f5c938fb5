// portal_test.cpp — portal emission is unbiased where all light enters through the marked portals
// (one window, two windows, two panes in line, an opening marked by its frame): portal and uniform
// agree within 4 sigma of their combined standard error. Without the overlap correction the
// panes in line come out high; the paper's rejection and the 1/N weighting agree. And where the
// portals are wrong (the inner room lit through the gap under its door, marked instead of the
// window), the estimate is biased low, as the paper found.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"

namespace fen {
namespace {

using test::rect;

enum class Windows { One, Two, InLine, Frame, DeepFrame };

// A closed 3 x 2.5 x 3 m room lit only through its windows: a south window (1 x 1 m), optionally
// an east one, a second pane 30 cm outside the first, or an open hole marked by its frame. Nothing
// outside can send light back in: outer faces only face away from every opening.
Scene windowRoom(Windows w)
{
    test::SceneBuilder b;
    const int wall = b.material("wall", glm::vec3(0.6f));
    const int floor = b.material("floor", glm::vec3(0.5f));
    const int glass = b.glass("glass", glm::vec3(0.85f), 1.5f);
    const float X = 3, Y = 2.5f, Z = 3;
    b.add("floor", rect({0, 0, 0}, {X, 0, 0}, {0, 0, Z}), floor);
    std::vector<Triangle> shell;
    auto put = [&](const std::vector<Triangle>& r) { shell.insert(shell.end(), r.begin(), r.end()); };
    put(rect({0, Y, 0}, {X, 0, 0}, {0, 0, Z}));  // ceiling
    put(rect({0, 0, 0}, {X, 0, 0}, {0, Y, 0}));  // north
    put(rect({0, 0, 0}, {0, 0, Z}, {0, Y, 0}));  // west
    // south wall around a hole x in [1, 2], y in [1, 2]
    put(rect({0, 0, Z}, {X, 0, 0}, {0, 1, 0}));
    put(rect({0, 2, Z}, {X, 0, 0}, {0, Y - 2, 0}));
    put(rect({0, 1, Z}, {1, 0, 0}, {0, 1, 0}));
    put(rect({2, 1, Z}, {X - 2, 0, 0}, {0, 1, 0}));
    if (w == Windows::Two) {  // east wall around a hole z in [1, 2], y in [1, 2]
        put(rect({X, 0, 0}, {0, 0, Z}, {0, 1, 0}));
        put(rect({X, 2, 0}, {0, 0, Z}, {0, Y - 2, 0}));
        put(rect({X, 1, 0}, {0, 0, 1}, {0, 1, 0}));
        put(rect({X, 1, 2}, {0, 0, Z - 2}, {0, 1, 0}));
        b.add("east_pane", rect({X, 1, 1}, {0, 0, 1}, {0, 1, 0}), glass, PortalMark::Panes);
    } else {
        put(rect({X, 0, 0}, {0, 0, Z}, {0, Y, 0}));
    }
    b.add("shell", shell, wall);
    if (w == Windows::DeepFrame) {
        // an open hole with 20 cm deep reveals (sill, head, jambs) outside the wall: the frame's
        // hull is a box, a non-planar hull whose surface light is emitted through
        std::vector<Triangle> frame;
        for (const auto& r : {rect({1, 1, Z}, {1, 0, 0}, {0, 0, 0.2f}), rect({1, 2, Z}, {1, 0, 0}, {0, 0, 0.2f}),
                              rect({1, 1, Z}, {0, 1, 0}, {0, 0, 0.2f}), rect({2, 1, Z}, {0, 1, 0}, {0, 0, 0.2f})})
            frame.insert(frame.end(), r.begin(), r.end());
        b.add("frame", frame, wall, PortalMark::Hull);
    } else if (w == Windows::Frame) {
        // an open hole; its frame: four 2 cm reveals around it in the wall plane
        std::vector<Triangle> frame;
        for (const auto& r : {rect({0.98f, 0.98f, Z}, {1.04f, 0, 0}, {0, 0.02f, 0}),
                              rect({0.98f, 2.0f, Z}, {1.04f, 0, 0}, {0, 0.02f, 0}),
                              rect({0.98f, 1.0f, Z}, {0.02f, 0, 0}, {0, 1, 0}),
                              rect({2.0f, 1.0f, Z}, {0.02f, 0, 0}, {0, 1, 0})})
            frame.insert(frame.end(), r.begin(), r.end());
        b.add("frame", frame, wall, PortalMark::Hull);
    } else {
        b.add("south_pane", rect({1, 1, Z}, {1, 0, 0}, {0, 1, 0}), glass, PortalMark::Panes);
    }
    if (w == Windows::InLine) {
        // A second pane 30 cm outside the first, the cavity between them closed by black reveals:
        // otherwise light reflected by the wall's outer face could reach the inner pane without
        // crossing a portal on its first segment -- the "light reflected from outside" failure,
        // measured at -1.8 sigma on average over six seeds before the reveals.
        b.add("outer_pane", rect({1, 1, Z + 0.3f}, {1, 0, 0}, {0, 1, 0}), glass, PortalMark::Panes);
        std::vector<Triangle> reveals;
        for (const auto& r : {rect({1, 1, Z}, {1, 0, 0}, {0, 0, 0.3f}), rect({1, 2, Z}, {1, 0, 0}, {0, 0, 0.3f}),
                              rect({1, 1, Z}, {0, 1, 0}, {0, 0, 0.3f}), rect({2, 1, Z}, {0, 1, 0}, {0, 0, 0.3f})})
            reveals.insert(reveals.end(), r.begin(), r.end());
        b.add("reveals", reveals, b.material("black", glm::vec3(0.0f)));
    }
    b.sun(40.0, 165.0, 30000.0);
    b.uniformSky(3000.0);
    b.camera({0.3, 1.6, 0.3}, {1.8, 0.4, 2.2}, {0, 1, 0}, 60.0);
    return b.build();
}

struct Measured {
    double mean, se;
};

Measured measure(ocl::Context& ctx, const Scene& scene, EmissionMethod method, std::uint64_t paths,
                 PortalOverlap overlap = PortalOverlap::Reject, const std::string& portals = "",
                 int width = 48, int height = 36, Roi roi = Roi{12, 9, 36, 27})
{
    const auto sky = buildSky(scene.sky);
    RenderSettings s;
    s.method = method;
    s.overlap = overlap;
    s.portals = portals;
    s.paths = paths;
    s.rois = {roi};
    if (const char* e = std::getenv("FEN_TEST_SEED"))
        s.seed += static_cast<std::uint32_t>(std::strtoul(e, nullptr, 10));
    Renderer r(ctx, scene, sky, scene.cameras.at(0), width, height, s);
    const RenderResult res = r.render();
    EXPECT_EQ(res.badContributions, 0u);
    EXPECT_EQ(res.overflows, 0u);
    return {res.roiMean(0), res.roiMeanStdErr(0)};
}

void expectAgree(const Measured& a, const Measured& b, const char* what)
{
    const double comb = std::sqrt(a.se * a.se + b.se * b.se);
    std::printf("[ portal   ] %s: %.5g +- %.3g vs %.5g +- %.3g: %+.2f sigma\n", what, a.mean, a.se,
                b.mean, b.se, (a.mean - b.mean) / comb);
    EXPECT_NEAR(a.mean, b.mean, 4.0 * comb) << what;
    EXPECT_LT(comb, 0.02 * b.mean) << what << ": too noisy to compare";
}

class PortalUnbiased : public ::testing::TestWithParam<Windows> {};

TEST_P(PortalUnbiased, AgreesWithUniform)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = windowRoom(GetParam());
    const Measured u = measure(*ctx, scene, EmissionMethod::Uniform, 12u << 20);
    const Measured p = measure(*ctx, scene, EmissionMethod::Portal, 2u << 20);
    expectAgree(p, u, "portal vs uniform");
    EXPECT_LT(p.se, u.se) << "portals should be the less noisy with fewer paths";
}

std::string roomName(const ::testing::TestParamInfo<Windows>& info)
{
    switch (info.param) {
    case Windows::One:
        return "OneWindow";
    case Windows::Two:
        return "TwoWindows";
    case Windows::InLine:
        return "PanesInLine";
    case Windows::Frame:
        return "OpeningByFrame";
    case Windows::DeepFrame:
        return "OpeningByDeepFrame";
    }
    return "Unknown";
}

INSTANTIATE_TEST_SUITE_P(Rooms, PortalUnbiased,
                         ::testing::Values(Windows::One, Windows::Two, Windows::InLine, Windows::Frame,
                                           Windows::DeepFrame),
                         roomName);

TEST(PortalOverlap, CorrectionMattersAndBothFixesAgree)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = windowRoom(Windows::InLine);
    const Measured rej = measure(*ctx, scene, EmissionMethod::Portal, 2u << 20, PortalOverlap::Reject);
    const Measured wgt = measure(*ctx, scene, EmissionMethod::Portal, 2u << 20, PortalOverlap::Weight);
    const Measured none = measure(*ctx, scene, EmissionMethod::Portal, 2u << 20, PortalOverlap::None);
    expectAgree(rej, wgt, "reject vs weight");
    const double comb = std::sqrt(none.se * none.se + wgt.se * wgt.se);
    std::printf("[ portal   ] no correction: %.5g vs %.5g (%+.1f sigma high)\n", none.mean, wgt.mean,
                (none.mean - wgt.mean) / comb);
    EXPECT_GT(none.mean - wgt.mean, 4.0 * comb) << "double-counted light must show";
}

TEST(PortalFailure, TheGapUnderTheDoorLosesMostOfTheLight)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // The paper's "portal on the gap": light reaching the inner room bounces in the outer room
    // first, so emitting through the gap alone misses it (the paper: 5.7x too dark).
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/inner_room.gltf");
    const Roi roi{24, 36, 72, 60};  // the inner room's floor and wall right of the door (96 x 72)
    const Measured right = measure(*ctx, scene, EmissionMethod::Portal, 4u << 20, PortalOverlap::Reject,
                                   "", 96, 72, roi);
    const Measured gap = measure(*ctx, scene, EmissionMethod::Portal, 4u << 20, PortalOverlap::Reject,
                                 "gap", 96, 72, roi);
    std::printf("[ portal   ] inner room: window + door %.4g +- %.2g, gap %.4g +- %.2g (%.1fx darker)\n",
                right.mean, right.se, gap.mean, gap.se, right.mean / gap.mean);
    EXPECT_LT(right.se, 0.05 * right.mean);
    EXPECT_GT(right.mean - gap.mean, 4.0 * std::sqrt(right.se * right.se + gap.se * gap.se));
    EXPECT_GT(right.mean / gap.mean, 2.0) << "the wrong portal should lose most of the light";
}

}  // namespace
}  // namespace fen
