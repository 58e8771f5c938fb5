// first_bounce_guide.h — the first-bounce guide's tables, statistics and learning on the host
// (DESIGN.md §3.4; device half: kernels/lib/guide.h, layout: kernels/shared/fen_guide.h). A
// scattering feature -- it steers a path's first diffuse bounce, in shade.cl -- so it lives with
// the scattering code; the adaptive strategy owns one and learns it on its passes.
//
// Light that must bounce off something outside before it can enter (the ground in front of a
// window, a sunlit wall across a courtyard) is what emission alone cannot steer: the emitted ray
// only decides where the bounce happens, the bounce decides whether the light gets in. The guide
// learns, per slot (a voxel of the scene and the side a surface faces), which of 64 boxes of the
// cosine-hemisphere's square sends a unit of weight to the camera, and the device draws the first
// bounce from that: d(b) = 64 ((1 - share) m(b) / sum m + share / 64), m(b) = sqrt(S(b)) and S(b)
// the box's learned integral of the squared delivery -- the density that minimises the second
// moment sum S(b) / d(b) of what a unit of weight delivers (for a delivery that is the same for
// every path through a box, the first moment: the zero-variance density). `share` > 0 keeps every
// box drawable: the weights stay finite and the image unbiased. A slot is guided only when its
// statistics predict that the table cuts that second moment at least minGain times against the
// cosine's (sum S / sum S/d): where light leaves a surface towards the camera about as much in
// every direction (a sunlit floor in view), guiding buys nothing and its noisy tables cost.
// Learning runs on the owner's passes (the adaptive strategy's): learn() reads the pass's
// statistics, adds them to the totals (each sample's square times the density it was drawn with,
// so passes drawn from different tables add up), rebuilds every slot with at least
// minConnections contributions, uploads the tables and clears the statistics. Deterministic: the statistics are
// integer sums, so the tables after a pass depend only on the seed and the path counts.
// Off (enabled = false): GuideParams.slots = 0 and one-element placeholder buffers; the kernels
// then scatter exactly as without a guide.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cl/context.h"
#include "shared/fen_guide.h"

namespace fen {

class StateReader;
class StateWriter;

struct GuideOptions {
    // On by default: over seven interleaved seeds at equal time it made adaptive 2.5x more
    // efficient on the courtyard, 1.9x under snow, 1.2x in the room, and 0.95-1.1x on the bay
    // window and the house (docs/results/guide.md, "Seven seeds").
    bool enabled = true;
    double share = 0.25;              // the uniform table's share in every learned one
    double minConnections = 32.0;     // contributions a slot needs before it is learned
    double minGain = 2.0;             // ... and the second-moment cut its table must promise
    // Lattice: voxels across the scene's bounding sphere's radius. Coarse on purpose: a slot must
    // gather contributions before it is steered, and far from the camera they are rare (R/4 beat
    // R/32 on all six measured scenes: docs/results/guide.md).
    int voxelsAcross = 4;
    std::uint32_t slots = 1u << 13;   // hash slots (a power of 2)
};
// Throws a one-line error naming the option for a value out of range.
void validateGuideOptions(const GuideOptions& o);

class FirstBounceGuide {
public:
    // The lattice covers the sphere (centre, radius_m) at radius_m / voxelsAcross per voxel.
    FirstBounceGuide(ocl::Context& ctx, const GuideOptions& o, glm::dvec3 centre, double radius_m);
    bool enabled() const { return opt_.enabled; }
    const cl::Buffer& params() const { return params_; }
    const cl::Buffer& tables() const { return tables_; }
    const cl::Buffer& stats() const { return stats_; }
    std::size_t deviceBytes() const { return deviceBytes_; }

    // After a pass: statistics into the totals, new tables up, statistics cleared.
    void learn();
    // Clears the device statistics (a resumed render starts between passes).
    void clearStats();
    // The table a slot draws from: the realised probability of each box (for tests).
    std::vector<double> probabilities(std::uint32_t slot) const;
    std::uint32_t learnedSlots() const { return learnedSlots_; }

    void save(StateWriter& w) const;
    void load(StateReader& r);
    nlohmann::json report() const;

private:
    void rebuild();
    void upload();
    ocl::Context& ctx_;
    GuideOptions opt_;
    dev::GuideParams deviceParams_{};
    std::vector<double> sumSq_, connections_;       // per slot x box, over all passes: S(b), count
    std::vector<std::uint32_t> tablesHost_;         // the learned bitmap, then the columns (fen_guide.h)
    std::vector<float> densityHost_;                // per slot x box: d(b)
    std::uint32_t learnedSlots_ = 0, candidateSlots_ = 0;  // guided; with enough contributions
    cl::Buffer params_, tables_, stats_;
    std::size_t deviceBytes_ = 0;
};

}  // namespace fen
