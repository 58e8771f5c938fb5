// device_bvh.cpp — BVH upload and the trace_rays.cl launches (device_bvh.h).
#include "trace/device_bvh.h"

#include "cl/launch.h"

namespace fen {

int defaultBvhWidth(bool gpu) { return gpu ? 2 : 8; }

int bvhLayoutWidth(const std::string& name)
{
    for (const int w : {2, 4, 8})
        if (name == std::to_string(w) || name == "bvh" + std::to_string(w))
            return w;
    return 0;
}

DeviceBvh::DeviceBvh(ocl::Context& ctx, const FlatBvh& bvh)
    : width_(bvh.width),
      nodes_(ctx.buffer(CL_MEM_READ_ONLY, bvh.nodeBytes(), "BVH nodes", bvh.nodeWords.data())),
      packets_(ctx.buffer(CL_MEM_READ_ONLY, bvh.packetBytes(), "BVH triangle packets",
                          bvh.packets.data()))
{
}

std::string DeviceBvh::widthDefine() const { return cat("FEN_BVH_WIDTH=", width_); }

RayQueries::RayQueries(ocl::Context& ctx, const DeviceBvh& bvh) : ctx_(ctx), bvh_(bvh)
{
    cl::Program prog = ctx.program("trace_rays.cl", {bvh.widthDefine()});
    closest_ = cl::Kernel(prog, "intersect_closest");
    any_ = cl::Kernel(prog, "intersect_any");
}

void RayQueries::closest(const cl::Buffer& rays, const cl::Buffer& hits, std::uint32_t n)
{
    ocl::setKernelArgs(closest_, rays, hits, n, bvh_.nodes(), bvh_.packets());
    ocl::launch(ctx_, closest_, "intersect_closest", n);
}

void RayQueries::any(const cl::Buffer& rays, const cl::Buffer& occluded, std::uint32_t n)
{
    ocl::setKernelArgs(any_, rays, occluded, n, bvh_.nodes(), bvh_.packets());
    ocl::launch(ctx_, any_, "intersect_any", n);
}

std::vector<dev::Hit> RayQueries::closest(const std::vector<dev::Ray>& rays)
{
    const auto n = static_cast<std::uint32_t>(rays.size());
    cl::Buffer rb = ctx_.buffer(CL_MEM_READ_ONLY, rays.size() * sizeof(dev::Ray), "rays", rays.data());
    cl::Buffer hb = ctx_.buffer(CL_MEM_WRITE_ONLY, rays.size() * sizeof(dev::Hit), "hits");
    closest(rb, hb, n);
    std::vector<dev::Hit> hits(rays.size());
    if (n > 0)
        ctx_.queue().enqueueReadBuffer(hb, CL_TRUE, 0, hits.size() * sizeof(dev::Hit), hits.data());
    return hits;
}

std::vector<std::uint32_t> RayQueries::any(const std::vector<dev::Ray>& rays)
{
    const auto n = static_cast<std::uint32_t>(rays.size());
    cl::Buffer rb = ctx_.buffer(CL_MEM_READ_ONLY, rays.size() * sizeof(dev::Ray), "rays", rays.data());
    cl::Buffer ob = ctx_.buffer(CL_MEM_WRITE_ONLY, rays.size() * sizeof(std::uint32_t), "occlusion flags");
    any(rb, ob, n);
    std::vector<std::uint32_t> occ(rays.size());
    if (n > 0)
        ctx_.queue().enqueueReadBuffer(ob, CL_TRUE, 0, occ.size() * 4, occ.data());
    return occ;
}

}  // namespace fen
