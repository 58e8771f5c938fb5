// device_scene.cpp — uploading a Scene (device_scene.h).
#include "render/device_scene.h"

#include "shared/fen_render.h"

namespace fen {

DeviceScene::DeviceScene(ocl::Context& ctx, const Scene& scene, int bvhWidth)
{
    const BinaryBvh bin = buildBinnedSah(scene.triangles);
    flat_ = flattenBvh(bin, scene.triangles, bvhWidth);
    bvhSeconds_ = bin.buildSeconds + flat_.flattenSeconds;
    bvh_ = std::make_unique<DeviceBvh>(ctx, flat_);

    std::vector<dev::DevMaterial> mats;
    for (const Material& m : scene.materials) {
        dev::DevMaterial d{};
        d.albedo = {m.albedo.r, m.albedo.g, m.albedo.b,
                    dev::fen_as_float(m.glass ? FEN_MATERIAL_GLASS : FEN_MATERIAL_DIFFUSE)};
        d.transmission = {m.transmission.r, m.transmission.g, m.transmission.b, m.ior};
        mats.push_back(d);
    }
    for (const std::uint32_t m : scene.triangleMaterial)
        hasGlass_ = hasGlass_ || scene.materials[m].glass;
    materials_ = ctx.buffer(CL_MEM_READ_ONLY, mats.size() * sizeof(dev::DevMaterial), "materials",
                            mats.data());
    primMaterial_ = ctx.buffer(CL_MEM_READ_ONLY, scene.triangleMaterial.size() * 4,
                               "material per primitive", scene.triangleMaterial.data());
}

std::vector<std::string> DeviceScene::defines() const
{
    std::vector<std::string> d{bvh_->widthDefine()};
    if (hasGlass_)
        d.push_back("FEN_HAS_GLASS=1");
    return d;
}

}  // namespace fen
