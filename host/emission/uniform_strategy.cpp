// uniform_strategy.cpp — the `uniform` strategy's buffers, report and descriptor (uniform_strategy.h).
#include "emission/uniform_strategy.h"

#include "cl/launch.h"
#include "emission/uniform_emission.h"

namespace fen {

namespace {

class UniformStrategy final : public EmissionStrategy {
public:
    explicit UniformStrategy(const EmissionInputs& in)
        : sky_(in.deviceSky), sources_(setupUniformEmission(in.scene, in.sky, in.goniogram))
    {
        const dev::SourceParams p = sourceParams(sources_.sources, sources_.sunWeight, &sources_.box);
        params_ = in.ctx.buffer(CL_MEM_READ_ONLY, sizeof p, "uniform emission parameters", &p);
        alias_ = in.ctx.buffer(CL_MEM_READ_ONLY, sources_.sources.alias.size() * 4, "source table",
                               sources_.sources.alias.data());
        factor_ = in.ctx.buffer(CL_MEM_READ_ONLY, sources_.skyFactor.size() * 4, "sky weights",
                                sources_.skyFactor.data());
        noStats_ = in.ctx.buffer(CL_MEM_READ_WRITE, 0, "cell statistics (none)");
    }

    EmissionMethod method() const override { return EmissionMethod::Uniform; }
    EmissionKernels kernels() const override
    {
        EmissionKernels k;
        k.emitProgram = "emit_uniform.cl";
        k.cellStats = &noStats_;
        return k;
    }
    void bindEmitArgs(cl::Kernel& emit, cl_uint first) override
    {
        ocl::setKernelArgsFrom(emit, first, params_, alias_, sky_.theta, sky_.phi, sky_.values, factor_);
    }
    double emittedFluxPerPath() const override { return sources_.sunFlux + sources_.skyFlux; }
    nlohmann::json report() const override
    {
        return {{"sun_flux_lm", sources_.sunFlux},
                {"sky_flux_lm", sources_.skyFlux},
                {"p_sun", sources_.pSun},
                {"box_size_m", {sources_.box.size.x, sources_.box.size.y, sources_.box.size.z}}};
    }

private:
    const DeviceSky& sky_;
    UniformSources sources_;
    cl::Buffer params_, alias_, factor_, noStats_;
};

}  // namespace

std::unique_ptr<EmissionStrategy> makeUniformStrategy(const EmissionInputs& in)
{
    return std::make_unique<UniformStrategy>(in);
}

// Roulette from the 5th interaction: its paths start outside the building and bounce there
// before any of their hits sees the camera (1.74x the efficiency of 3 on the inner room,
// 0.95-0.97x on the room and the bay window: docs/results/termination.md).
const StrategyDescriptor kUniformStrategy = {
    EmissionMethod::Uniform,
    "uniform",
    5,
    nullptr,
    [](const EmissionSettings&) { return false; },
    [](const EmissionSettings&) { return nlohmann::json::object(); },
    [](const EmissionSettings&, const EmissionInputs& in) { return makeUniformStrategy(in); },
};

}  // namespace fen
