// device_scene.h — a Scene on an OpenCL device: its BVH (bvh/, trace/), the material of every
// primitive and the materials (shared/fen_render.h), and the defines every render program needs.
// Stages read a hit triangle's vertices from its BVH packet, so no other copy of the geometry.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cl/context.h"
#include "scene/scene.h"
#include "trace/device_bvh.h"

namespace fen {

class DeviceScene {
public:
    // width: BVH layout (2, 4, 8).
    DeviceScene(ocl::Context& ctx, const Scene& scene, int bvhWidth);

    const DeviceBvh& bvh() const { return *bvh_; }
    const FlatBvh& flat() const { return flat_; }
    const cl::Buffer& materials() const { return materials_; }
    const cl::Buffer& primMaterial() const { return primMaterial_; }  // uint per primitive
    bool hasGlass() const { return hasGlass_; }
    double bvhBuildSeconds() const { return bvhSeconds_; }
    // FEN_BVH_WIDTH=..., and FEN_HAS_GLASS when any triangle is glass.
    std::vector<std::string> defines() const;

private:
    FlatBvh flat_;
    std::unique_ptr<DeviceBvh> bvh_;
    cl::Buffer materials_, primMaterial_;
    bool hasGlass_ = false;
    double bvhSeconds_ = 0.0;
};

}  // namespace fen
