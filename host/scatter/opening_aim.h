// opening_aim.h — the opening aim's openings, statistics and learning on the host (DESIGN.md §3.5;
// device half: kernels/lib/opening_aim.h, layout: kernels/shared/fen_openings.h). A scattering
// feature, beside the first-bounce guide: the adaptive strategy owns one and learns it on its passes.
//
// Light that bounces outside before it gets in (off a neighbour's wall, the ground, snow) must be
// sent, at some bounce, through an opening a few hundredths of the hemisphere wide. The openings
// are the scene's glass, found without marking: glass triangles joined where they share a corner
// and lie in one plane (findOpenings). Which of them lead to the camera is learned: every path that
// enters by an opening side after a diffuse bounce adds its weight there, and its camera
// contributions afterwards; their ratio is the light a unit of weight sent in there brings to the
// image (light straight from the sky is not counted: the aim never sends it). Outside, every
// diffuse vertex aims at the openings in proportion to that ratio times the solid angle each
// subtends (one sample of a mixture with the cosine, unbiased). Told where the openings are, such
// an aim at every vertex outside made the courtyard 2.7x and the snow house 3.7x as efficient as
// the learned tables; learned, it made them 1.9x and 1.6x, the house 1.1x (docs/results/guiding.md,
// "Told where the openings are", "The opening aim"). The mixture's cosine share is learned too
// (learnShare(), from sums the guide keeps beside the weight windows'), one for the scene.
//
// Deterministic: the statistics are integer sums and the choices ordered, so the aim after a pass
// depends only on the seed and the path counts. Off (enabled = false, or no glass): the device's
// OpeningAim has no triangles and no primitives, and the kernels scatter as without it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cl/context.h"
#include "shared/fen_openings.h"
#include "team/summed_buffer.h"

namespace fen {

struct Scene;
class StateReader;
class StateWriter;

struct OpeningAimOptions {
    // On by default: at equal time it made adaptive 1.9x as efficient on the courtyard, 1.6x under
    // snow and 1.1x on the house (docs/results/guiding.md, "The opening aim").
    bool enabled = true;
    // The cosine's share of the mixture at an aimed vertex (with learnShare: past a path's first
    // diffuse vertex, and where the first vertex's starts). A path's weight grows by up to 1/share
    // at a vertex whose cosine draw misses the panes, and over several bounces outside those paths
    // became the houses' fireflies at 0.5 (snow house 0.67-2.97x in three seeds); 0.75 held 1.6x
    // there and 1.1x on the house, where 0.5 won only the courtyard (2.4x against 1.9x).
    double cosineShare = 0.75;
    // Learn the share at a path's first diffuse vertex from what the paths deliver (learnShare()):
    // after each pass, the share that minimises the second moment A / (1 - s) + B / s of that
    // vertex's scatter, A of what leaves where the aim's density dominates, were it drawn by the
    // aim alone, B of the rest, were it drawn by the cosine alone -- s = sqrt(B) / (sqrt(A) +
    // sqrt(B)) -- within [shareMin, shareMax], one for the scene. Off by default: it made the
    // courtyard about 1.4x as efficient and left the houses at 0.9-1.0x over five seeds, the snow
    // house's median under 0.95 (docs/results/guiding.md, "The aim's share, learned"). Learned per
    // place (the guide's slots), rare heavy paths left most places' B too low and the houses lost
    // more; used at every vertex, the share a first vertex wants was too low for the later ones.
    bool learnShare = false;
    double shareMin = 0.25;
    double shareMax = 0.95;
    // An opening side is aimed at once this many paths have entered by it ...
    double minEntries = 64.0;
    // ... and while its weight times its area is at least this share of the largest's.
    double minShare = 0.01;
    // The aim weighs a side by its learned ratio to this power (relative to the largest): 1 the
    // mean itself; below 1 spreads the aim over the openings whose ratio is smaller.
    double power = 1.0;
    // No aim: placeholders bound where a strategy has none (nothing aimed at, nothing learned).
    static OpeningAimOptions off()
    {
        OpeningAimOptions o;
        o.enabled = false;
        return o;
    }
};
// Throws a one-line error naming the option for a value out of range.
void validateOpeningAimOptions(const OpeningAimOptions& o);

// A pane of glass: connected coplanar glass triangles (scene indices), each with whether its
// normal points against the pane's (the first triangle's).
struct Opening {
    std::vector<std::uint32_t> triangles;
    std::vector<char> flipped;
    double area_m2 = 0.0;
    glm::dvec3 normal{0.0};
};
// The scene's openings, largest first (equal areas by first triangle).
std::vector<Opening> findOpenings(const Scene& scene);

class OpeningAim {
public:
    // Off, or a scene without glass: placeholders (nothing aimed, nothing learned).
    OpeningAim(ocl::Context& ctx, const OpeningAimOptions& o, const Scene* scene);
    const cl::Buffer& aim() const { return aim_; }
    const cl::Buffer& prims() const { return prims_; }
    const cl::Buffer& stats() const { return stats_; }
    // Per opening side: two 128-bit sums and a count (fen_openings.h).
    SummedBuffer summed() const { return {&stats_, 2 * openings_.size(), {2, 2, 1}}; }
    std::size_t deviceBytes() const { return deviceBytes_; }

    // After a pass, before learn(): the pass's squares of what paths that left a first vertex by the
    // mixture delivered (mixed) and of those that left in the aim's region (aimed), any common
    // scale; with learnShare, the share for the next pass (uploaded by learn()).
    void learnShare(double mixed, double aimed);
    // After a pass: statistics into the totals, the aim rebuilt and uploaded, statistics cleared.
    void learn();
    double firstShare() const { return host_.first_share; }  // at a path's first diffuse vertex
    void clearStats();

    const std::vector<Opening>& openings() const { return openings_; }
    // Opening side's learned weight (the light a unit entering brings to the image, over the
    // largest such), 0 while it is not aimed at.
    double weight(std::size_t opening, int side) const { return weight_.at(opening)[static_cast<std::size_t>(side)]; }
    std::uint32_t aimedTriangles() const { return host_.triangles; }
    const dev::OpeningAim& deviceAim() const { return host_; }

    void save(StateWriter& w) const;
    void load(StateReader& r);
    nlohmann::json report() const;

private:
    struct SideTotals {
        double delivered = 0.0, entered = 0.0, entries = 0.0;
    };
    void rebuild();
    void upload();
    std::size_t statWords() const;  // the statistics buffer's words (one side's worth when empty)
    ocl::Context& ctx_;
    OpeningAimOptions opt_;
    std::vector<Opening> openings_;                       // learned ones: at most FEN_OPENING_MAX
    std::size_t ignoredOpenings_ = 0;                     // beyond FEN_OPENING_MAX, never learned
    // The learned openings' triangles as the device takes them, weights 0 (rebuild() sets them),
    // opening j's from firstTriangle_[j] on
    std::vector<dev::AimTriangle> triangles_;
    std::vector<std::size_t> firstTriangle_;
    std::vector<std::array<SideTotals, 2>> totals_;       // per opening, per side
    std::vector<std::array<double, 2>> weight_;
    std::size_t aimedOpenings_ = 0, skippedOpenings_ = 0;  // skipped: no room left in the aim
    dev::OpeningAim host_{};
    std::vector<std::uint64_t> raw_;
    double learnSeconds_ = 0.0;
    int passes_ = 0;
    // learnShare(): the estimates of A and B (the share's second moments), and the share they give
    double shareA_ = 0.0, shareB_ = 0.0;
    void setShare();
    cl::Buffer aim_, prims_, stats_;
    std::size_t deviceBytes_ = 0;
};

}  // namespace fen
