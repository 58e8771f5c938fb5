// device_scene.cpp — uploading a Scene (device_scene.h).
#include "render/device_scene.h"

#include "render/checkpoint.h"

#include <cmath>

#include "shared/fen_render.h"

namespace fen {

namespace {

// The IEC 61966-2-1 sRGB decoding of an 8-bit code (glTF: base-colour textures are sRGB).
float srgbToLinear(std::uint32_t code)
{
    const double c = code / 255.0;
    return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

std::uint32_t wrapBits(TextureWrap w)
{
    return w == TextureWrap::ClampToEdge ? FEN_WRAP_CLAMP : w == TextureWrap::MirroredRepeat ? FEN_WRAP_MIRROR
                                                                                            : FEN_WRAP_REPEAT;
}

}  // namespace

// Texture coordinates are affine over a triangle: with e1 = p1 - p0, e2 = p2 - p0, n = e1 x e2,
// the dual vectors d1 = (e2 x n) / |n|^2, d2 = (n x e1) / |n|^2 give a point x of the triangle's
// plane its barycentrics b1 = d1 . (x - p0), b2 = d2 . (x - p0); so u(x) = u0 + b1 (u1 - u0) +
// b2 (u2 - u0) = r . x + w, a plane per coordinate (texture.h). Computed in double; a degenerate
// triangle gets the constant u0.
std::vector<dev::fen_float4> textureCoordinatePlanes(const Scene& scene)
{
    std::vector<dev::fen_float4> planes(2 * scene.triangles.size(), dev::fen_float4{0.0f, 0.0f, 0.0f, 0.0f});
    for (std::size_t t = 0; t < scene.triangles.size() && t < scene.triangleUv.size(); ++t) {
        const glm::dvec3 p0(scene.triangles[t].p0), p1(scene.triangles[t].p1), p2(scene.triangles[t].p2);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, n = glm::cross(e1, e2);
        const double nn = glm::dot(n, n);
        const glm::dvec3 d1 = nn > 0.0 ? glm::cross(e2, n) / nn : glm::dvec3(0.0);
        const glm::dvec3 d2 = nn > 0.0 ? glm::cross(n, e1) / nn : glm::dvec3(0.0);
        const auto& uv = scene.triangleUv[t];
        for (int k = 0; k < 2; ++k) {
            const glm::dvec3 r = d1 * double(uv[1][k] - uv[0][k]) + d2 * double(uv[2][k] - uv[0][k]);
            const double w = double(uv[0][k]) - glm::dot(r, p0);
            planes[2 * t + static_cast<std::size_t>(k)] = {static_cast<float>(r.x), static_cast<float>(r.y),
                                                           static_cast<float>(r.z), static_cast<float>(w)};
        }
    }
    return planes;
}

DeviceScene::DeviceScene(ocl::Context& ctx, const Scene& scene, int bvhWidth)
{
    const BinaryBvh bin = buildBinnedSah(scene.triangles);
    flat_ = flattenBvh(bin, scene.triangles, bvhWidth);
    bvhSeconds_ = bin.buildSeconds + flat_.flattenSeconds;
    bvh_ = std::make_unique<DeviceBvh>(ctx, flat_);

    // The texel buffer: the sRGB decode table, then each texture's texels (texture.h).
    std::vector<std::uint32_t> texels(FEN_SRGB_TABLE);
    for (std::uint32_t c = 0; c < FEN_SRGB_TABLE; ++c)
        texels[c] = dev::fen_as_uint(srgbToLinear(c));
    std::vector<std::uint32_t> textureOffset;
    for (const Texture& t : scene.textures) {
        textureOffset.push_back(static_cast<std::uint32_t>(texels.size() - FEN_SRGB_TABLE));
        for (std::size_t i = 0; i < t.rgb.size(); i += 3)
            texels.push_back(std::uint32_t{t.rgb[i]} | std::uint32_t{t.rgb[i + 1]} << 8 |
                             std::uint32_t{t.rgb[i + 2]} << 16);
    }

    std::vector<dev::DevMaterial> mats;
    for (const Material& m : scene.materials) {
        dev::DevMaterial d{};
        d.albedo = {m.albedo.r, m.albedo.g, m.albedo.b,
                    dev::fen_as_float(m.glass ? FEN_MATERIAL_GLASS : FEN_MATERIAL_DIFFUSE)};
        d.transmission = {m.transmission.r, m.transmission.g, m.transmission.b, m.ior};
        if (m.texture >= 0) {
            const Texture& t = scene.textures[static_cast<std::size_t>(m.texture)];
            d.tex_offset = textureOffset[static_cast<std::size_t>(m.texture)];
            d.tex_width = static_cast<std::uint32_t>(t.width);
            d.tex_height = static_cast<std::uint32_t>(t.height);
            d.tex_flags = FEN_TEX_PRESENT | (t.nearest ? FEN_TEX_NEAREST : 0u) |
                          wrapBits(t.wrapS) << FEN_TEX_WRAP_S_SHIFT | wrapBits(t.wrapT) << FEN_TEX_WRAP_T_SHIFT;
        }
        mats.push_back(d);
    }
    for (const std::uint32_t m : scene.triangleMaterial) {
        hasGlass_ = hasGlass_ || scene.materials[m].glass;
        hasTextures_ = hasTextures_ || scene.materials[m].texture >= 0;
    }
    materials_ = ctx.buffer(CL_MEM_READ_ONLY, mats.size() * sizeof(dev::DevMaterial), "materials",
                            mats.data());
    primMaterial_ = ctx.buffer(CL_MEM_READ_ONLY, scene.triangleMaterial.size() * 4,
                               "material per primitive", scene.triangleMaterial.data());
    if (hasTextures_) {
        const std::vector<dev::fen_float4> planes = textureCoordinatePlanes(scene);
        primUv_ = ctx.buffer(CL_MEM_READ_ONLY, planes.size() * sizeof(dev::fen_float4),
                             "texture coordinates per primitive", planes.data());
        texels_ = ctx.buffer(CL_MEM_READ_ONLY, texels.size() * 4, "texels", texels.data());
    } else {
        const dev::fen_float4 none[2]{};
        primUv_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof none, "no texture coordinates", none);
        texels_ = ctx.buffer(CL_MEM_READ_ONLY, FEN_SRGB_TABLE * 4, "no texels", texels.data());
    }
}

std::vector<std::string> DeviceScene::defines() const
{
    std::vector<std::string> d{bvh_->widthDefine()};
    if (hasGlass_)
        d.push_back("FEN_HAS_GLASS=1");
    if (hasTextures_)
        d.push_back("FEN_HAS_TEXTURES=1");
    return d;
}

std::shared_ptr<const DeviceScene> DeviceSceneCache::get(ocl::Context& ctx, const Scene& scene, int bvhWidth,
                                                         bool* reused)
{
    const std::uint64_t hash = geometryHash(scene);
    *reused = scene_ && ctx_ == &ctx && hash_ == hash && width_ == bvhWidth;
    if (!*reused) {
        scene_.reset();  // the old one's buffers go before the new one's are made
        scene_ = std::make_shared<const DeviceScene>(ctx, scene, bvhWidth);
        ctx_ = &ctx, hash_ = hash, width_ = bvhWidth;
    }
    return scene_;
}

}  // namespace fen
