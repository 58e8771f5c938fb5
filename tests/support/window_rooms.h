// window_rooms.h — closed rooms lit only through their windows, and measuring a region's mean on
// them, shared by the tests of the emission strategies (portal_test.cpp, adaptive_test.cpp).
#pragma once

#include <string>

#include "render/renderer.h"
#include "scene/scene.h"

namespace fen { namespace test {

// A closed 3 x 2.5 x 3 m room lit only through its windows: a south window (1 x 1 m), optionally
// an east one, a second pane 30 cm outside the first, or an open hole marked by its frame (in the
// wall plane, or a 20 cm deep one). Nothing outside can send light back in: outer faces only face
// away from every opening.
enum class Windows { One, Two, InLine, Frame, DeepFrame };
Scene windowRoom(Windows w);
std::string windowRoomName(Windows w);

struct Measured {
    double mean, se;
    nlohmann::json emission;  // the strategy's report
};

// Renders `scene` with `settings` (paths, rois[0] and the seed shifted by FEN_TEST_SEED are
// filled in here) and returns the ROI's mean and standard error; checks the counters.
Measured measure(ocl::Context& ctx, const Scene& scene, EmissionSettings emission, std::uint64_t paths,
                 int width = 48, int height = 36, Roi roi = Roi{12, 9, 36, 27});
Measured measure(ocl::Context& ctx, const Scene& scene, EmissionMethod method, std::uint64_t paths,
                 PortalOverlap overlap = PortalOverlap::Reject, const std::string& portals = "",
                 int width = 48, int height = 36, Roi roi = Roi{12, 9, 36, 27});

// a and b agree within 4 sigma of their combined standard error, which must be below maxRelSe of
// b (else the comparison would mean nothing); prints the deviation in sigmas under `tag`.
void expectAgree(const Measured& a, const Measured& b, const char* what, const char* tag = "portal",
                 double maxRelSe = 0.02);

} }  // namespace fen::test
