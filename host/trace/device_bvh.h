// device_bvh.h — a FlatBvh uploaded to a device, and ray queries against it
// (kernels/trace_rays.cl, built for the tree's width).
#pragma once

#include <string>
#include <vector>

#include "bvh_flat.h"
#include "cl/context.h"

namespace fen {

// The layout a device traverses fastest (measured: docs/bvh.md).
int defaultBvhWidth(bool gpu);

// The width a layout's name gives: "bvh2" or "2" is 2, likewise 4 and 8; 0 for any other name.
int bvhLayoutWidth(const std::string& name);

class DeviceBvh {
public:
    DeviceBvh(ocl::Context& ctx, const FlatBvh& bvh);

    int width() const { return width_; }
    const cl::Buffer& nodes() const { return nodes_; }
    const cl::Buffer& packets() const { return packets_; }
    // "-DFEN_BVH_WIDTH=W" for any program that traverses this tree.
    std::string widthDefine() const;

private:
    int width_;
    cl::Buffer nodes_;
    cl::Buffer packets_;
};

class RayQueries {
public:
    RayQueries(ocl::Context& ctx, const DeviceBvh& bvh);

    // Enqueue only; buffers hold n Ray / Hit / cl_uint.
    void closest(const cl::Buffer& rays, const cl::Buffer& hits, std::uint32_t n);
    void any(const cl::Buffer& rays, const cl::Buffer& occluded, std::uint32_t n);

    // Round trips for tests.
    std::vector<dev::Hit> closest(const std::vector<dev::Ray>& rays);
    std::vector<std::uint32_t> any(const std::vector<dev::Ray>& rays);

private:
    ocl::Context& ctx_;
    const DeviceBvh& bvh_;
    cl::Kernel closest_;
    cl::Kernel any_;
};

}  // namespace fen
