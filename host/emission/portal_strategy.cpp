// portal_strategy.cpp — the `portal` strategy's buffers and report (portal_strategy.h).
#include "emission/portal_strategy.h"

#include "cl/launch.h"
#include "trace/device_bvh.h"

namespace fen {

namespace {

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
        : sky_(in.deviceSky), overlap_(settings.overlap),
          pe_(setupPortalEmission(in.scene, in.sky, in.goniogram, settings.portals, in.bvhWidth))
    {
        ocl::Context& c = in.ctx;
        // Sky paths: factor_k sin(theta) times 1 -- the portals' projected area W(v) comes in per
        // path (lib/emit_portal.h).
        const dev::SourceParams sp = sourceParams(pe_.sources, pe_.sunWeight, 1.0);
        sourceParams_ = c.buffer(CL_MEM_READ_ONLY, sizeof sp, "portal emission parameters", &sp);
        dev::PortalParams pp{};
        pp.groups = static_cast<std::uint32_t>(pe_.groups.size());
        pp.overlap = static_cast<std::uint32_t>(settings.overlap);
        portalParams_ = c.buffer(CL_MEM_READ_ONLY, sizeof pp, "portal parameters", &pp);
        alias_ = c.buffer(CL_MEM_READ_ONLY, pe_.sources.alias.size() * 4, "source table", pe_.sources.alias.data());
        factor_ = c.buffer(CL_MEM_READ_ONLY, pe_.skyFactor.size() * 4, "sky weights", pe_.skyFactor.data());
        groups_ = c.buffer(CL_MEM_READ_ONLY, pe_.groups.size() * 16, "portal groups", pe_.groups.data());
        range_ = c.buffer(CL_MEM_READ_ONLY, pe_.groupRange.size() * 4, "portal groups", pe_.groupRange.data());
        cdf_ = c.buffer(CL_MEM_READ_ONLY, pe_.triangleCdf.size() * 8, "portal triangle table",
                        pe_.triangleCdf.data());
        vertices_ = c.buffer(CL_MEM_READ_ONLY, pe_.vertices.size() * 16, "portal triangles", pe_.vertices.data());
        bvh_ = std::make_unique<DeviceBvh>(c, pe_.bvh);
        noStats_ = c.buffer(CL_MEM_READ_WRITE, 0, "cell statistics (none)");
    }

    EmissionMethod method() const override { return EmissionMethod::Portal; }
    std::string emitProgram() const override { return "emit_portal.cl"; }
    void bindEmitArgs(cl::Kernel& emit, cl_uint first) override
    {
        ocl::setKernelArgsFrom(emit, first, sourceParams_, alias_, sky_.theta, sky_.phi, sky_.values,
                               factor_, portalParams_, groups_, range_, cdf_, vertices_, bvh_->nodes(),
                               bvh_->packets());
    }
    const cl::Buffer& cellStats() const override { return noStats_; }
    nlohmann::json report() const override
    {
        return {{"portal_nodes", pe_.portals.nodes},
                {"portal_triangles", pe_.portals.triangles.size()},
                {"portal_plane_groups", pe_.portals.groups.size()},
                {"portal_overlap", overlapName(overlap_)},
                {"sun_flux_lm", pe_.sunFlux_lm},
                {"sky_flux_lm", pe_.skyFlux_lm},
                {"precompute_seconds", pe_.precomputeSeconds}};
    }

private:
    const DeviceSky& sky_;
    PortalOverlap overlap_;
    PortalEmission pe_;
    cl::Buffer sourceParams_, portalParams_, alias_, factor_, groups_, range_, cdf_, vertices_, noStats_;
    std::unique_ptr<DeviceBvh> bvh_;
};

}  // namespace

std::unique_ptr<EmissionStrategy> makePortalStrategy(const EmissionSettings& settings,
                                                     const EmissionInputs& in)
{
    return std::make_unique<PortalStrategy>(settings, in);
}

}  // namespace fen
