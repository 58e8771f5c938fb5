// device_scene.h — a Scene on an OpenCL device: its BVH (bvh/, trace/), the material of every
// primitive and the materials (shared/fen_render.h), their textures, and the defines every render program needs.
// Stages read a hit triangle's vertices from its BVH packet, so no other copy of the geometry.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cl/context.h"
#include "scene/scene.h"
#include "shared/fen_types.h"
#include "trace/device_bvh.h"

namespace fen {

// Two texture-coordinate planes per triangle (kernels/lib/texture.h), from Scene::triangleUv.
std::vector<dev::fen_float4> textureCoordinatePlanes(const Scene& scene);

class DeviceScene {
public:
    // width: BVH layout (2, 4, 8).
    DeviceScene(ocl::Context& ctx, const Scene& scene, int bvhWidth);

    const DeviceBvh& bvh() const { return *bvh_; }
    const FlatBvh& flat() const { return flat_; }
    const cl::Buffer& materials() const { return materials_; }
    const cl::Buffer& primMaterial() const { return primMaterial_; }  // uint per primitive
    // Base-colour textures (kernels/lib/texture.h): two texture-coordinate planes per primitive,
    // and the sRGB decode table followed by every texture's texels; placeholders without textures.
    const cl::Buffer& primUv() const { return primUv_; }
    const cl::Buffer& texels() const { return texels_; }
    bool hasGlass() const { return hasGlass_; }
    bool hasTextures() const { return hasTextures_; }
    double bvhBuildSeconds() const { return bvhSeconds_; }
    // FEN_BVH_WIDTH=..., FEN_HAS_GLASS when any triangle is glass, FEN_HAS_TEXTURES when any
    // triangle's material has a texture.
    std::vector<std::string> defines() const;

private:
    FlatBvh flat_;
    std::unique_ptr<DeviceBvh> bvh_;
    cl::Buffer materials_, primMaterial_, primUv_, texels_;
    bool hasGlass_ = false, hasTextures_ = false;
    double bvhSeconds_ = 0.0;
};

// Device scenes kept for the renders of one process (`fenestra batch`): a render of the same
// geometry and materials, on the same context and BVH layout, reuses the BVH and buffers the last
// one built instead of building them again (the scene's sun and sky are not in them). Holds one
// scene: batches list a scene's jobs together.
class DeviceSceneCache {
public:
    // The device scene for `scene` at `bvhWidth` on `ctx`; *reused tells whether it was built before.
    std::shared_ptr<const DeviceScene> get(ocl::Context& ctx, const Scene& scene, int bvhWidth, bool* reused);

private:
    const ocl::Context* ctx_ = nullptr;
    std::uint64_t hash_ = 0;
    int width_ = 0;
    std::shared_ptr<const DeviceScene> scene_;
};

}  // namespace fen
