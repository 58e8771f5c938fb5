// device_scene.cpp — uploading a Scene (device_scene.h).
#include "render/device_scene.h"

#include <cstring>

#include "shared/fen_render.h"

namespace fen {

namespace {

float asFloat(std::uint32_t u)
{
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

}  // namespace

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
                    asFloat(m.glass ? FEN_MATERIAL_GLASS : FEN_MATERIAL_DIFFUSE)};
        d.transmission = {m.transmission.r, m.transmission.g, m.transmission.b, m.ior};
        mats.push_back(d);
    }
    std::vector<dev::ShadeTri> tris(scene.triangles.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        const std::uint32_t mat = scene.triangleMaterial[i];
        hasGlass_ = hasGlass_ || scene.materials[mat].glass;
        tris[i].p0 = {t.p0.x, t.p0.y, t.p0.z, asFloat(mat)};
        tris[i].p1 = {t.p1.x, t.p1.y, t.p1.z, asFloat(scene.triangleNode[i])};
        tris[i].p2 = {t.p2.x, t.p2.y, t.p2.z, 0.0f};
    }
    tris_ = ctx.buffer(CL_MEM_READ_ONLY, tris.size() * sizeof(dev::ShadeTri), "shading triangles",
                       tris.data());
    materials_ = ctx.buffer(CL_MEM_READ_ONLY, mats.size() * sizeof(dev::DevMaterial), "materials",
                            mats.data());
}

std::vector<std::string> DeviceScene::defines() const
{
    std::vector<std::string> d{bvh_->widthDefine()};
    if (hasGlass_)
        d.push_back("FEN_HAS_GLASS=1");
    return d;
}

}  // namespace fen
