// portal_strategy.cpp — the `portal` strategy's buffers, report, warning and descriptor
// (portal_strategy.h).
#include "emission/portal_strategy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cl/launch.h"
#include "emission/uniform_emission.h"
#include "trace/device_bvh.h"
#include "io/state_io.h"
#include "util/error.h"
#include "util/fixed_point.h"

namespace fen {

namespace {

// The strategy warns when its complement paths carry more than this share of the light.
constexpr double kUnreachedWarning = 0.01;

const char* overlapName(PortalOverlap o)
{
    switch (o) {
    case PortalOverlap::Reject: return "reject";
    case PortalOverlap::Weight: return "weight";
    case PortalOverlap::None: return "none";
    }
    return "?";
}

class PortalStrategy final : public EmissionStrategy {
public:
    PortalStrategy(const EmissionSettings& settings, const EmissionInputs& in)
        : ctx_(in.ctx), sky_(in.deviceSky), overlap_(settings.portal.overlap), complement_(settings.portal.complement),
          fixedScale_(in.pixelFixedScale),
          pe_(setupPortalEmission(in.scene, in.sky, in.goniogram, settings.portals, in.bvhWidth)),
          uniform_(setupUniformEmission(in.scene, in.sky, in.goniogram))
    {
        validatePortalOptions(settings.portal);
        ocl::Context& c = in.ctx;
        // Sky paths: factor_k sin(theta) times 1 -- the portal part A_g |v.n_g| / P(g | bin) comes
        // in per path (lib/emit_portal.h).
        const dev::SourceParams sp = sourceParams(pe_.sources, pe_.sunWeight);
        sourceParams_ = c.buffer(CL_MEM_READ_ONLY, sizeof sp, "portal emission parameters", &sp);
        dev::PortalParams pp{};
        pp.groups = static_cast<std::uint32_t>(pe_.groups.size());
        // Portals in one plane: every emitted line crosses exactly one portal triangle, so N = 1
        // and the count (a traversal of the portals' BVH per path: 23 ns of a path's 141 of
        // emission on the inner room, whose two planes need it) is skipped -- the same paths and
        // weights (PortalSampling.OnePlaneNeedsNoCount; README "Portal emission").
        overlapCounted_ = overlap_ != PortalOverlap::None && !pe_.portals.singlePlane();
        pp.overlap = overlapCounted_ ? static_cast<std::uint32_t>(overlap_) : FEN_OVERLAP_NONE;
        pp.complement = static_cast<float>(complement_);
        pp.group_alias_shift = pe_.groupAliasShift;
        portalParams_ = c.buffer(CL_MEM_READ_ONLY, sizeof pp, "portal parameters", &pp);
        alias_ = c.buffer(CL_MEM_READ_ONLY, pe_.sources.alias.size() * 4, "source table", pe_.sources.alias.data());
        factor_ = c.buffer(CL_MEM_READ_ONLY, pe_.skyFactor.size() * 4, "sky weights", pe_.skyFactor.data());
        groups_ = c.buffer(CL_MEM_READ_ONLY, pe_.groups.size() * 16, "portal groups", pe_.groups.data());
        groupAlias_ = c.buffer(CL_MEM_READ_ONLY, pe_.groupAlias.size() * 4, "portal group tables",
                               pe_.groupAlias.data());
        groupRatio_ = c.buffer(CL_MEM_READ_ONLY, pe_.groupRatio.size() * 4, "portal group weights",
                               pe_.groupRatio.data());
        cellBin_ = c.buffer(CL_MEM_READ_ONLY, pe_.cellBin.size() * 4, "portal direction bins", pe_.cellBin.data());
        range_ = c.buffer(CL_MEM_READ_ONLY, pe_.groupRange.size() * 4, "portal groups", pe_.groupRange.data());
        cdf_ = c.buffer(CL_MEM_READ_ONLY, pe_.triangleCdf.size() * 8, "portal triangle table",
                        pe_.triangleCdf.data());
        vertices_ = c.buffer(CL_MEM_READ_ONLY, pe_.vertices.size() * 16, "portal triangles", pe_.vertices.data());
        bvh_ = std::make_unique<DeviceBvh>(c, pe_.bvh);
        const dev::SourceParams up = sourceParams(uniform_.sources, uniform_.sunWeight, &uniform_.box);
        uniformParams_ = c.buffer(CL_MEM_READ_ONLY, sizeof up, "complement emission parameters", &up);
        uniformAlias_ = c.buffer(CL_MEM_READ_ONLY, uniform_.sources.alias.size() * 4, "complement source table",
                                 uniform_.sources.alias.data());
        uniformFactor_ = c.buffer(CL_MEM_READ_ONLY, uniform_.skyFactor.size() * 4, "complement sky weights",
                                  uniform_.skyFactor.data());
        // Two parts: 0 the portal paths, 1 the complement.
        stats_ = c.buffer(CL_MEM_READ_WRITE, 2 * FEN_CELL_STATS_WORDS * 8, "portal statistics");
        c.queue().enqueueFillBuffer(stats_, cl_ulong(0), 0, 2 * FEN_CELL_STATS_WORDS * 8);
    }

    EmissionMethod method() const override { return EmissionMethod::Portal; }
    // With a complement, connect.cl adds up what the portal paths and the complement's deliver.
    EmissionKernels kernels() const override
    {
        EmissionKernels k;
        k.emitProgram = "emit_portal.cl";
        k.gatherStats = complement_ > 0.0;
        k.cellStats = &stats_;
        return k;
    }
    std::vector<SummedBuffer> summedBuffers() const override
    {
        static_assert(FEN_CELL_STATS_WORDS == 5, "a cell's statistics: two 128-bit sums and a count");
        return {{&stats_, complement_ > 0.0 ? 2u : 0u, {2, 2, 1}}};
    }
    void bindEmitArgs(cl::Kernel& emit, cl_uint first) override
    {
        ocl::setKernelArgsFrom(emit, first, sourceParams_, alias_, sky_.theta, sky_.phi, sky_.values,
                               factor_, portalParams_, groups_, groupAlias_, groupRatio_, cellBin_, range_,
                               cdf_, vertices_, bvh_->nodes(),
                               bvh_->packets(), uniformParams_, uniformAlias_, uniformFactor_);
    }
    // Through the portals (overlaps counted once per portal, so an upper bound), and with a
    // complement also the rest of the flux into the scene's box, which its paths carry.
    double emittedFluxPerPath() const override
    {
        const double portals = pe_.sunFlux_lm + pe_.skyFlux_lm;
        return complement_ > 0.0 ? std::max(portals, uniform_.sunFlux + uniform_.skyFlux) : portals;
    }
    // The complement's share of the light that reached the camera in the batch just ended.
    void afterPaths(std::uint64_t, std::uint64_t, bool batchEnd) override
    {
        if (!batchEnd || complement_ <= 0.0)
            return;
        std::uint64_t w[2 * FEN_CELL_STATS_WORDS];
        auto& q = ctx_.queue();
        q.enqueueReadBuffer(stats_, CL_TRUE, 0, sizeof w, w);
        double sum[2];
        for (int k = 0; k < 2; ++k)
            sum[k] = fixed128(w + FEN_CELL_STATS_WORDS * k + FEN_CELL_SUM_LO) / fixedScale_;
        unreached_.push_back(sum[0] + sum[1] > 0.0 ? sum[1] / (sum[0] + sum[1]) : 0.0);
        q.enqueueFillBuffer(stats_, cl_ulong(0), 0, 2 * FEN_CELL_STATS_WORDS * 8);
    }
    void saveState(StateWriter& w) const override { w.f64s("portal.unreached", unreached_); }
    void loadState(StateReader& r) override { unreached_ = r.f64s("portal.unreached", 1u << 20); }
    nlohmann::json report() const override
    {
        return {{"portal_nodes", pe_.portals.nodes},
                {"portal_triangles", pe_.portals.triangles.size()},
                {"portal_plane_groups", pe_.portals.groups.size()},
                {"portal_direction_bins", pe_.groupRatio.size() / pe_.portals.groups.size()},
                {"portal_overlap", overlapName(overlap_)},
                {"portal_overlap_counted", overlapCounted_},
                {"sun_flux_lm", pe_.sunFlux_lm},
                {"sky_flux_lm", pe_.skyFlux_lm},
                {"precompute_seconds", pe_.precomputeSeconds},
                {"complement", complement_},
                {"unreached", unreached()}};
    }

    // The portals' blind spot, when the complement measured it significantly.
    std::vector<std::string> warnings() const override
    {
        const nlohmann::json u = unreached();
        if (!u.is_object())
            return {};
        const double share = u["share"], se = u["std_err"];
        if (!(share > kUnreachedWarning && share > 2.0 * se))
            return {};
        char line[400];
        std::snprintf(line, sizeof line,
                      "%.1f %% (+- %.1f) of the light reaching the camera does not pass through the marked "
                      "portals (reflected from outside, or an unmarked opening): the portal image misses it; "
                      "--method adaptive does not",
                      100.0 * share, 100.0 * se);
        return {line};
    }

    // The complement's share over the batches: mean and standard error (null without a complement).
    nlohmann::json unreached() const
    {
        if (complement_ <= 0.0 || unreached_.empty())
            return nullptr;
        const double n = static_cast<double>(unreached_.size());
        double m = 0.0, ss = 0.0;
        for (double x : unreached_)
            m += x / n;
        for (double x : unreached_)
            ss += (x - m) * (x - m);
        const double se = unreached_.size() > 1 ? std::sqrt(ss / (n - 1.0) / n) : 0.0;
        return {{"share", m}, {"std_err", se}, {"batches", unreached_.size()}};
    }

private:
    ocl::Context& ctx_;
    const DeviceSky& sky_;
    PortalOverlap overlap_;
    bool overlapCounted_ = true;  // false: one plane, N = 1 for every line (no count needed)
    double complement_, fixedScale_;
    PortalEmission pe_;
    UniformSources uniform_;
    std::vector<double> unreached_;  // per batch (calibration batches too: each is an estimate)
    cl::Buffer sourceParams_, portalParams_, alias_, factor_, groups_, groupAlias_, groupRatio_, cellBin_,
        range_, cdf_, vertices_, stats_,
        uniformParams_, uniformAlias_, uniformFactor_;
    std::unique_ptr<DeviceBvh> bvh_;
};

}  // namespace

std::unique_ptr<EmissionStrategy> makePortalStrategy(const EmissionSettings& settings,
                                                     const EmissionInputs& in)
{
    return std::make_unique<PortalStrategy>(settings, in);
}

// Roulette from the 3rd interaction: its paths are aimed in from the start
// (docs/results/termination.md).
const StrategyDescriptor kPortalStrategy = {
    EmissionMethod::Portal,
    "portal",
    3,
    makePortalOptionBlock,
    [](const EmissionSettings&) { return true; },
    portalFingerprint,
    makePortalStrategy,
};

}  // namespace fen
