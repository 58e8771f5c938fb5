// emit_probe.cpp — an emission strategy's emitter run alone (emit_probe.h).
#include "support/emit_probe.h"

#include "cl/launch.h"
#include "emission/emission_sphere.h"

namespace fen { namespace test {

dev::RenderParams emissionParams(const Scene& scene, const SkyTables& sky, std::uint32_t seed)
{
    dev::RenderParams p{};
    glm::dvec3 centre;
    double radius;
    emissionSphere(scene, &centre, &radius);
    p.sphere = {float(centre.x), float(centre.y), float(centre.z), float(radius)};
    const glm::dvec3 sd = scene.sun.travelDirection;
    p.sun_dir = {float(sd.x), float(sd.y), float(sd.z), 1.0f};
    p.seed = seed;
    p.sky_theta_nodes = sky.thetaNodes;
    p.sky_phi_nodes = sky.phiNodes;
    return p;
}

EmittedPaths runEmitProbe(ocl::Context& ctx, cl::Kernel& kernel, const char* name, EmissionStrategy& strategy,
                          const dev::RenderParams& params, std::uint32_t n)
{
    const std::size_t bytes = std::size_t{n} * 16;
    cl::Buffer pb = ctx.buffer(CL_MEM_READ_ONLY, sizeof params, "params", &params);
    cl::Buffer beta = ctx.buffer(CL_MEM_WRITE_ONLY, bytes, "beta");
    cl::Buffer org = ctx.buffer(CL_MEM_WRITE_ONLY, bytes, "org");
    cl::Buffer dir = ctx.buffer(CL_MEM_WRITE_ONLY, bytes, "dir");
    strategy.bindEmitArgs(kernel, 5);
    kernel.setArg(0, pb);
    kernel.setArg(1, beta);
    kernel.setArg(2, org);
    kernel.setArg(3, dir);
    kernel.setArg(4, n);
    ocl::launch(ctx, kernel, name, n);
    EmittedPaths out;
    out.beta.resize(n);
    out.org.resize(n);
    out.dir.resize(n);
    ctx.queue().enqueueReadBuffer(beta, CL_FALSE, 0, bytes, out.beta.data());
    ctx.queue().enqueueReadBuffer(org, CL_FALSE, 0, bytes, out.org.data());
    ctx.queue().enqueueReadBuffer(dir, CL_TRUE, 0, bytes, out.dir.data());
    return out;
}

} }  // namespace fen::test
