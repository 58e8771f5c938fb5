// gltf_load.cpp — glTF 2.0 to Scene (gltf_load.h), via tinygltf. The order is the point: framing,
// nesting and the JSON are checked before tinygltf reads anything, tinygltf reads files only
// through the scene folder's callbacks, and the members fenestra reads from tinygltf's model are
// those gltf_check has made sure it copied faithfully; extras come from the JSON itself.
#include "scene/gltf_load.h"

#include <algorithm>
#include <optional>
#include <set>
#include <cstring>
#include <filesystem>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_check.h"
#include "scene/json_reader.h"
#include "scene/scene_files.h"
#include "scene/texture_image.h"
#include "util/error.h"

namespace fen {

namespace {

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                      [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

std::string nodeLabel(const tinygltf::Model& m, int node)
{
    const std::string& name = m.nodes[static_cast<std::size_t>(node)].name;
    return name.empty() ? cat("node ", node) : cat("node ", node, " '", printable(name), "'");
}

bool isFiniteMatrix(const glm::dmat4& m)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                return false;
    return true;
}

glm::dmat4 localTransform(const tinygltf::Node& n)
{
    if (n.matrix.size() == 16)
        return glm::make_mat4(n.matrix.data());
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (n.translation.size() == 3)
        t = glm::translate(glm::dmat4(1.0),
                           glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4)  // glTF stores x, y, z, w
        r = glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
    if (n.scale.size() == 3)
        s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return t * r * s;
}

// Bounds-checked element access to an accessor's data.
class AccessorView {
public:
    AccessorView(const tinygltf::Model& m, int index, const std::string& where) : where_(where)
    {
        if (index < 0 || index >= static_cast<int>(m.accessors.size()))
            throw Error(cat(where, ": accessor ", index, " does not exist"));
        acc_ = &m.accessors[static_cast<std::size_t>(index)];
        where_ = cat(where, ", accessor ", index);
        if (acc_->sparse.isSparse)
            throw Error(cat(where_, ": sparse accessors are not supported"));
        if (acc_->bufferView < 0 || acc_->bufferView >= static_cast<int>(m.bufferViews.size()))
            throw Error(cat(where_, ": has no valid bufferView"));
        const tinygltf::BufferView& bv = m.bufferViews[static_cast<std::size_t>(acc_->bufferView)];
        if (bv.buffer < 0 || bv.buffer >= static_cast<int>(m.buffers.size()))
            throw Error(cat(where_, ": bufferView ", acc_->bufferView, " names no buffer"));
        const tinygltf::Buffer& buf = m.buffers[static_cast<std::size_t>(bv.buffer)];
        const int stride = acc_->ByteStride(bv);
        const int comp = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(acc_->componentType));
        const int ncomp = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(acc_->type));
        if (stride <= 0 || comp <= 0 || ncomp <= 0)
            throw Error(cat(where_, ": invalid component type, type or byteStride"));
        elemSize_ = static_cast<std::size_t>(comp * ncomp);
        stride_ = static_cast<std::size_t>(stride);
        // Offsets, lengths and counts come from the file as 64-bit integers: a sum or product
        // near 2^64 must not wrap into something that looks in bounds.
        std::size_t viewEnd = 0, last = 0, end = 0;
        if (__builtin_add_overflow(bv.byteOffset, bv.byteLength, &viewEnd) || viewEnd > buf.data.size())
            throw Error(cat(where_, ": bufferView ", acc_->bufferView, " (byteOffset ", bv.byteOffset,
                            ", byteLength ", bv.byteLength, ") lies outside buffer ", bv.buffer,
                            buf.data.empty() ? " (was its file found?)" : ""));
        if (acc_->count > 0 &&
            (__builtin_mul_overflow(stride_, acc_->count - 1, &last) ||
             __builtin_add_overflow(last, acc_->byteOffset, &end) ||
             __builtin_add_overflow(end, elemSize_, &end) || end > bv.byteLength))
            throw Error(cat(where_, ": ", acc_->count, " elements from byteOffset ", acc_->byteOffset,
                            " do not fit in bufferView ", acc_->bufferView));
        base_ = buf.data.data() + bv.byteOffset + acc_->byteOffset;
    }

    std::size_t count() const { return acc_->count; }
    int componentType() const { return acc_->componentType; }
    int type() const { return acc_->type; }
    const std::string& where() const { return where_; }

    glm::vec3 vec3(std::size_t i) const
    {
        float v[3];
        std::memcpy(v, base_ + i * stride_, sizeof v);
        return glm::vec3(v[0], v[1], v[2]);
    }
    // A TEXCOORD_n element: float, or normalised unsigned byte / short (glTF 2.0, "Meshes").
    glm::vec2 texcoord(std::size_t i) const
    {
        const unsigned char* p = base_ + i * stride_;
        switch (acc_->componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return glm::vec2(p[0], p[1]) / 255.0f;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v[2];
            std::memcpy(v, p, sizeof v);
            return glm::vec2(v[0], v[1]) / 65535.0f;
        }
        default: {
            float v[2];
            std::memcpy(v, p, sizeof v);
            return glm::vec2(v[0], v[1]);
        }
        }
    }
    std::uint32_t index(std::size_t i) const
    {
        const unsigned char* p = base_ + i * stride_;
        switch (acc_->componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return *p;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        default: {
            std::uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        }
    }

private:
    const tinygltf::Accessor* acc_ = nullptr;
    std::string where_;
    const unsigned char* base_ = nullptr;
    std::size_t elemSize_ = 0, stride_ = 0;
};

void addPrimitive(const tinygltf::Model& m, const tinygltf::Primitive& prim, const glm::dmat4& xf,
                  int node, const std::string& where, Scene& scene)
{
    // Primitives without a material get glTF's default material, stored last.
    const std::uint32_t material = prim.material >= 0
                                       ? static_cast<std::uint32_t>(prim.material)
                                       : static_cast<std::uint32_t>(m.materials.size());
    if (prim.material >= static_cast<int>(m.materials.size()))
        throw Error(cat(where, ": material ", prim.material, " does not exist"));
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES)
        throw Error(cat(where, ": primitive mode ", mode,
                        " is not supported (only triangles, mode 4)"));
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end())
        throw Error(cat(where, ": primitive has no POSITION attribute"));
    const AccessorView p(m, pos->second, where);
    if (p.componentType() != TINYGLTF_COMPONENT_TYPE_FLOAT || p.type() != TINYGLTF_TYPE_VEC3)
        throw Error(cat(p.where(), ": POSITION must be float VEC3"));

    std::vector<glm::vec3> world(p.count());
    for (std::size_t i = 0; i < p.count(); ++i) {
        const glm::vec3 local = p.vec3(i);
        if (!isFinite(local))
            throw Error(cat(p.where(), ": vertex ", i, " has a non-finite coordinate"));
        world[i] = glm::vec3(xf * glm::dvec4(glm::dvec3(local), 1.0));
        if (!isFinite(world[i]))
            throw Error(cat(p.where(), ": vertex ", i, " is not finite after the node transforms"));
    }

    std::vector<std::uint32_t> idx;
    if (prim.indices >= 0) {
        const AccessorView ia(m, prim.indices, where);
        const int ct = ia.componentType();
        if (ia.type() != TINYGLTF_TYPE_SCALAR ||
            (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            throw Error(cat(ia.where(), ": indices must be unsigned byte/short/int scalars"));
        idx.resize(ia.count());
        for (std::size_t i = 0; i < ia.count(); ++i) {
            idx[i] = ia.index(i);
            if (idx[i] >= world.size())
                // By position: the value is the buffer's content, which no message quotes.
                throw Error(cat(ia.where(), ": index at position ", i, " exceeds the ",
                                world.size(), " vertices"));
        }
    } else {
        idx.resize(world.size());
        for (std::size_t i = 0; i < idx.size(); ++i)
            idx[i] = static_cast<std::uint32_t>(i);
    }
    if (idx.size() % 3 != 0)
        throw Error(cat(where, ": ", idx.size(), " indices is not a whole number of triangles"));
    // A textured material reads the texture by the primitive's TEXCOORD_n.
    std::vector<glm::vec2> uv;
    const Material& mat = scene.materials[material];
    if (mat.texture >= 0) {
        const std::string key = cat("TEXCOORD_", mat.texCoord);
        const auto tc = prim.attributes.find(key);
        if (tc == prim.attributes.end())
            throw Error(cat(where, ": material '", printable(mat.name), "' has a baseColorTexture read by ", key,
                            ", which the primitive does not have"));
        const AccessorView t(m, tc->second, where);
        const int ct = t.componentType();
        if (t.type() != TINYGLTF_TYPE_VEC2 ||
            (ct != TINYGLTF_COMPONENT_TYPE_FLOAT && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
            throw Error(cat(t.where(), ": ", key, " must be VEC2 of float or normalised unsigned byte/short"));
        if (t.count() != p.count())
            throw Error(cat(t.where(), ": ", key, " has ", t.count(), " elements for ", p.count(), " vertices"));
        uv.resize(t.count());
        for (std::size_t i = 0; i < uv.size(); ++i) {
            uv[i] = t.texcoord(i);
            if (!std::isfinite(uv[i].x) || !std::isfinite(uv[i].y))
                throw Error(cat(t.where(), ": element ", i, " of ", key, " is not finite"));
        }
    }
    for (std::size_t i = 0; i < idx.size(); i += 3) {
        scene.triangles.push_back({world[idx[i]], world[idx[i + 1]], world[idx[i + 2]]});
        scene.triangleNode.push_back(static_cast<std::uint32_t>(node));
        scene.triangleMaterial.push_back(material);
        if (!scene.textures.empty())
            scene.triangleUv.push_back(uv.empty() ? std::array<glm::vec2, 3>{}
                                                  : std::array<glm::vec2, 3>{uv[idx[i]], uv[idx[i + 1]], uv[idx[i + 2]]});
    }
}

std::string materialLabel(const tinygltf::Model& m, std::size_t i)
{
    const std::string& name = m.materials[i].name;
    return name.empty() ? cat("materials[", i, "]") : cat("materials[", i, "] '", printable(name), "'");
}

// The encoded bytes of each image tinygltf read (its image loader callback keeps them; gltf
// images are decoded only when a material uses them, texture_image.h).
struct EncodedImages {
    std::vector<std::vector<unsigned char>> bytes;  // per glTF image; empty: not read
    std::vector<char> read;                         // per glTF image: tinygltf passed its bytes on
};

bool keepEncodedImage(tinygltf::Image*, const int index, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user)
{
    auto* images = static_cast<EncodedImages*>(user);
    if (index < 0 || size < 0)
        return false;
    const auto i = static_cast<std::size_t>(index);
    if (images->bytes.size() <= i) {
        images->bytes.resize(i + 1);
        images->read.resize(i + 1, 0);
    }
    images->bytes[i].assign(bytes, bytes + size);
    images->read[i] = 1;
    return true;
}

TextureWrap wrapMode(int gl)
{
    return gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? TextureWrap::ClampToEdge
           : gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::MirroredRepeat
                                                         : TextureWrap::Repeat;
}

// The Scene::textures index of glTF texture `t` as a base colour, decoding its image the first
// time a material uses it. Indices were checked as written (gltf_check.cpp).
int baseColorTexture(const tinygltf::Model& m, int t, const std::string& path, const EncodedImages& images,
                     std::vector<int>& textureOfGltf, Scene& scene)
{
    int& cached = textureOfGltf[static_cast<std::size_t>(t)];
    if (cached >= 0)
        return cached;
    const tinygltf::Texture& tex = m.textures[static_cast<std::size_t>(t)];
    if (tex.source < 0)
        throw Error(cat(path, ": textures[", t, "]: has no source image (extensions' image formats are not supported)"));
    const auto source = static_cast<std::size_t>(tex.source);
    const tinygltf::Image& img = m.images[source];
    std::string label = cat("images[", source, "]");
    if (!img.name.empty())
        label += cat(" '", printable(img.name), "'");
    else if (!img.uri.empty() && img.uri.compare(0, 5, "data:") != 0)
        label += cat(" '", printable(img.uri), "'");
    const std::string where = cat(path, ": ", label);
    if (source >= images.read.size() || !images.read[source])
        throw Error(cat(where, ": could not be read (", img.uri.empty() ? "no data" : "missing or unreadable file",
                        "), and textures[", t, "] uses it"));
    Texture texture;
    texture.name = label;
    decodeTextureImage(images.bytes[source].data(), images.bytes[source].size(), where, &texture);
    std::size_t texels = std::size_t(texture.width) * std::size_t(texture.height);
    for (const Texture& other : scene.textures)
        texels += std::size_t(other.width) * std::size_t(other.height);
    if (texels > kMaxTextureTexels)
        throw Error(cat(where, ": the scene's textures together exceed ", kMaxTextureTexels, " texels"));
    if (tex.sampler >= 0) {
        const tinygltf::Sampler& s = m.samplers[static_cast<std::size_t>(tex.sampler)];
        texture.wrapS = wrapMode(s.wrapS);
        texture.wrapT = wrapMode(s.wrapT);
        texture.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    }
    scene.textures.push_back(std::move(texture));
    cached = static_cast<int>(scene.textures.size() - 1);
    return cached;
}

// `doc` is the file's JSON as written: the extensions are read from it (json_reader.h).
std::vector<Material> readMaterials(const tinygltf::Model& m, const nlohmann::json& doc,
                                    const std::string& path, const EncodedImages& images, Scene& scene)
{
    std::vector<Material> out;
    std::vector<int> textureOfGltf(m.textures.size(), -1);
    for (std::size_t i = 0; i < m.materials.size(); ++i) {
        const tinygltf::Material& src = m.materials[i];
        const std::string where = cat(path, ": ", materialLabel(m, i));
        Material mat;
        mat.name = src.name.empty() ? cat("material ", i) : src.name;
        const auto& bc = src.pbrMetallicRoughness.baseColorFactor;
        if (!bc.empty()) {
            if (bc.size() != 4)
                throw Error(cat(where, ": baseColorFactor must have 4 components"));
            for (int c = 0; c < 3; ++c) {
                if (!(bc[static_cast<std::size_t>(c)] >= 0.0 && bc[static_cast<std::size_t>(c)] <= 1.0))
                    throw Error(cat(where, ": baseColorFactor[", c, "] = ", bc[static_cast<std::size_t>(c)],
                                    " is outside [0, 1]"));
                mat.albedo[c] = static_cast<float>(bc[static_cast<std::size_t>(c)]);
            }
        }
        const auto& em = src.emissiveFactor;
        if ((em.size() == 3 && (em[0] > 0.0 || em[1] > 0.0 || em[2] > 0.0)) ||
            src.emissiveTexture.index >= 0)
            scene.warnings.push_back(cat(where, ": emission ignored (light comes from the sun and sky only)"));

        const nlohmann::json& extensions = member(element(member(doc, "materials"), i), "extensions");
        const nlohmann::json& tr = member(extensions, "KHR_materials_transmission");
        if (!tr.is_null()) {
            JsonReader r(tr, where + ".extensions.KHR_materials_transmission");
            const double t = r.number("transmissionFactor", 0.0);
            if (!(t >= 0.0 && t <= 1.0))
                throw Error(cat(r.keyPath("transmissionFactor"), ": ", t, " is outside [0, 1]"));
            if (r.has("transmissionTexture")) {
                r.raw("transmissionTexture");
                scene.warnings.push_back(cat(where, ": transmissionTexture ignored"));
            }
            r.rejectUnknownKeys();
            if (t > 0.0) {
                mat.glass = true;
                mat.transmission = static_cast<float>(t) * mat.albedo;
            }
        }
        const nlohmann::json& ior = member(extensions, "KHR_materials_ior");
        if (!ior.is_null()) {
            JsonReader r(ior, where + ".extensions.KHR_materials_ior");
            const double v = r.number("ior", 1.5);
            if (!(v >= 1.0 && v <= 10.0))
                throw Error(cat(r.keyPath("ior"), ": ", v, " must be in [1, 10]"));
            r.rejectUnknownKeys();
            mat.ior = static_cast<float>(v);
        }
        // Decoded only for a diffuse material: glass ignores its texture (and does not fail on it).
        const int texIndex = src.pbrMetallicRoughness.baseColorTexture.index;
        if (texIndex >= 0 && mat.glass) {
            scene.warnings.push_back(cat(where, ": baseColorTexture of a glass material ignored (its "
                                                "transmittance is transmissionFactor times baseColorFactor)"));
        } else if (texIndex >= 0) {
            mat.texture = baseColorTexture(m, texIndex, path, images, textureOfGltf, scene);
            mat.texCoord = src.pbrMetallicRoughness.baseColorTexture.texCoord;
        }
        out.push_back(mat);
    }
    Material def;
    def.name = "default (white)";
    out.push_back(def);
    return out;
}

// Luminances and illuminances become floats on the device: keep them far below float's range.
constexpr double kMaxLight = 1e30;

void checkLight(double v, const std::string& key)
{
    if (v > kMaxLight)
        throw Error(cat(key, ": ", v, " is beyond ", kMaxLight));
}

SkySpec readSky(const nlohmann::json& sky, const std::string& where)
{
    SkySpec spec;
    spec.where = where;
    JsonReader r(sky, where);
    const std::string type = r.string("type");
    if (type == "uniform") {
        spec.type = SkySpec::Type::Uniform;
        spec.luminance_cd_m2 = r.number("luminance");
        if (spec.luminance_cd_m2 < 0.0)
            throw Error(cat(r.keyPath("luminance"), ": negative luminance ", spec.luminance_cd_m2));
        checkLight(spec.luminance_cd_m2, r.keyPath("luminance"));
    } else if (type == "cie") {
        spec.type = SkySpec::Type::Cie;
        const std::int64_t cieType = r.integer("cie_type");
        if (cieType < 1 || cieType > 15)
            throw Error(cat(r.keyPath("cie_type"), ": ", cieType, " is not a CIE sky type (1..15)"));
        spec.cieType = static_cast<int>(cieType);
        spec.zenithLuminance_cd_m2 = r.number("zenith_luminance");
        if (spec.zenithLuminance_cd_m2 < 0.0)
            throw Error(cat(r.keyPath("zenith_luminance"), ": negative luminance ",
                            spec.zenithLuminance_cd_m2));
        // CIE skies brighten towards the sun by up to ~40x the zenith
        checkLight(spec.zenithLuminance_cd_m2 * 100.0, r.keyPath("zenith_luminance"));
        spec.sunAltitudeDeg = r.number("sun_altitude_deg");
        if (spec.sunAltitudeDeg < 0.0 || spec.sunAltitudeDeg > 90.0)
            throw Error(cat(r.keyPath("sun_altitude_deg"), ": ", spec.sunAltitudeDeg,
                            " is outside [0, 90]"));
        spec.sunAzimuthDeg = r.number("sun_azimuth_deg");
    } else if (type == "table") {
        spec.type = SkySpec::Type::Table;
        spec.zenithDeg = r.numbers("zenith_deg");
        spec.azimuthDeg = r.numbers("azimuth_deg");
        spec.table_cd_m2 = r.numberRows("luminance");
        for (std::size_t i = 0; i < spec.table_cd_m2.size(); ++i)
            for (std::size_t j = 0; j < spec.table_cd_m2[i].size(); ++j)
                checkLight(spec.table_cd_m2[i][j], cat(r.keyPath("luminance"), "[", i, "][", j, "]"));
    } else {
        throw Error(cat(r.keyPath("type"), ": unknown sky type '", printable(type),
                        "' (uniform, cie or table)"));
    }
    // Any type: the ground's albedo, its glow below the horizon (sky/sky_spec.h); 0 is off.
    if (r.has("ground_albedo")) {
        spec.groundAlbedo = r.number("ground_albedo");
        if (!(spec.groundAlbedo >= 0.0 && spec.groundAlbedo <= 1.0))
            throw Error(cat(r.keyPath("ground_albedo"), ": ", spec.groundAlbedo, " is outside [0, 1] (0: no ground glow)"));
    }
    r.rejectUnknownKeys();
    return spec;
}

// Orthonormal camera frame from a node's world transform (scale and shear removed).
CameraSpec readCamera(const tinygltf::Model& m, int node, const glm::dmat4& xf, const std::string& where)
{
    const tinygltf::Node& n = m.nodes[static_cast<std::size_t>(node)];
    if (n.camera >= static_cast<int>(m.cameras.size()))
        throw Error(cat(where, ": camera ", n.camera, " does not exist"));
    const tinygltf::Camera& cam = m.cameras[static_cast<std::size_t>(n.camera)];
    if (cam.type != "perspective")
        throw Error(cat(where, ": camera ", n.camera, " is '", printable(cam.type),
                        "'; only perspective cameras are supported"));
    // Below 0.001 degrees a pixel's solid angle underflows what the film can hold (the image
    // comes out black); beyond 179 the projection degenerates. Aspect ratios beyond 16:1 give
    // images a pixel high.
    constexpr double kMinYfov = 0.001 * M_PI / 180.0, kMaxYfov = 179.0 * M_PI / 180.0;
    if (!(cam.perspective.yfov >= kMinYfov && cam.perspective.yfov <= kMaxYfov))
        throw Error(cat(where, ": camera ", n.camera, ": yfov ", cam.perspective.yfov,
                        " rad must be in [", kMinYfov, ", ", kMaxYfov, "] (0.001 to 179 degrees)"));
    if (cam.perspective.aspectRatio != 0.0 &&
        !(cam.perspective.aspectRatio >= 1.0 / 16.0 && cam.perspective.aspectRatio <= 16.0))
        throw Error(cat(where, ": camera ", n.camera, ": aspectRatio ", cam.perspective.aspectRatio,
                        " must be in [1/16, 16]"));
    CameraSpec c;
    c.nodeName = n.name;
    c.cameraName = cam.name;
    c.position = glm::dvec3(xf[3]);
    if (!isFinite(glm::vec3(c.position)))  // the renderer places it in floats
        throw Error(cat(where, ": camera position (", c.position.x, ", ", c.position.y, ", ", c.position.z,
                        ") is beyond float range"));
    const glm::dvec3 back = glm::dvec3(xf[2]), upRaw = glm::dvec3(xf[1]);
    if (glm::length(back) == 0.0 || glm::length(upRaw) == 0.0)
        throw Error(cat(where, ": camera transform is degenerate"));
    c.forward = -glm::normalize(back);
    c.right = glm::cross(c.forward, upRaw);
    if (glm::length(c.right) < 1e-12)
        throw Error(cat(where, ": camera transform is degenerate"));
    c.right = glm::normalize(c.right);
    c.up = glm::cross(c.right, c.forward);
    c.yfovRad = cam.perspective.yfov;
    c.aspectRatio = cam.perspective.aspectRatio > 0.0 ? cam.perspective.aspectRatio : 0.0;
    return c;
}

// "nodes[3] 'window'": the glTF path of a node, with its name when it has one.
std::string nodeRef(const tinygltf::Model& m, int node)
{
    const std::string& name = m.nodes[static_cast<std::size_t>(node)].name;
    return name.empty() ? cat("nodes[", node, "]") : cat("nodes[", node, "] '", printable(name), "'");
}

// glTF nodes form disjoint strict trees (glTF 2.0, "Nodes and Hierarchy"): a node has at most one
// parent and is not its own ancestor. A node listed twice multiplies the work (30 levels of
// doubling: 2^30 copies from a 6 KB file), a cycle never ends: both are refused, for every node,
// in the file or not in the scene. Returns each node's parent, -1 for a root.
std::vector<int> checkNodeForest(const tinygltf::Model& m, const std::string& path)
{
    const int count = static_cast<int>(m.nodes.size());
    std::vector<int> parent(m.nodes.size(), -1);
    for (int i = 0; i < count; ++i) {
        const std::vector<int>& children = m.nodes[static_cast<std::size_t>(i)].children;
        for (std::size_t k = 0; k < children.size(); ++k) {
            const int c = children[k];
            const std::string where = cat(path, ": nodes[", i, "].children[", k, "]");
            if (c < 0 || c >= count)
                throw Error(cat(where, ": node ", c, " does not exist"));
            if (c == i)
                throw Error(cat(where, ": ", nodeRef(m, c), " is its own child"));
            int& p = parent[static_cast<std::size_t>(c)];
            if (p == i)
                throw Error(cat(where, ": ", nodeRef(m, c), " is listed twice"));
            if (p >= 0)
                throw Error(cat(path, ": ", nodeRef(m, c), " is a child of both nodes[", p, "] and nodes[",
                                i, "]; glTF nodes form trees"));
            p = i;
        }
    }
    // With one parent each, a cycle is a chain of parents that comes back to where it started.
    enum : char { Unknown, OnChain, ReachesRoot };
    std::vector<char> state(m.nodes.size(), Unknown);
    for (int i = 0; i < count; ++i) {
        int n = i;
        while (n >= 0 && state[static_cast<std::size_t>(n)] == Unknown) {
            state[static_cast<std::size_t>(n)] = OnChain;
            n = parent[static_cast<std::size_t>(n)];
        }
        if (n >= 0 && state[static_cast<std::size_t>(n)] == OnChain)
            throw Error(cat(path, ": ", nodeRef(m, n), " is its own ancestor (its children lead back to it)"));
        for (n = i; n >= 0 && state[static_cast<std::size_t>(n)] == OnChain; n = parent[static_cast<std::size_t>(n)])
            state[static_cast<std::size_t>(n)] = ReachesRoot;
    }
    return parent;
}

// A scene lists root nodes, each once: otherwise a subtree would be drawn twice.
void checkSceneRoots(const tinygltf::Model& m, int sceneIndex, const std::vector<int>& parent,
                     const std::string& path)
{
    const std::vector<int>& roots = m.scenes[static_cast<std::size_t>(sceneIndex)].nodes;
    std::vector<char> listed(m.nodes.size(), 0);
    for (std::size_t k = 0; k < roots.size(); ++k) {
        const int r = roots[k];
        const std::string where = cat(path, ": scenes[", sceneIndex, "].nodes[", k, "]");
        if (r < 0 || r >= static_cast<int>(m.nodes.size()))
            throw Error(cat(where, ": node ", r, " does not exist"));
        if (parent[static_cast<std::size_t>(r)] >= 0)
            throw Error(cat(where, ": ", nodeRef(m, r), " is a child of nodes[", parent[static_cast<std::size_t>(r)],
                            "]; a scene lists root nodes only"));
        if (listed[static_cast<std::size_t>(r)]++)
            throw Error(cat(where, ": ", nodeRef(m, r), " is listed twice"));
    }
}

// A box in double: the bounds of a scene a thousand kilometres wide, and their differences.
struct Box {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    void grow(const glm::dvec3& p)
    {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b)
    {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return !(lo.x <= hi.x); }
    double diameter() const { return empty() ? 0.0 : glm::length(hi - lo); }
    double distanceTo(const glm::dvec3& p) const
    {
        return glm::length(glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0)));
    }
};

// Uniform emission starts paths over the silhouette of the scene's bounding box (adaptive's disk
// covers its bounding sphere), so a node far from the rest (one triangle a thousand kilometres
// away) or much larger than it (a ground plane kilometres wide) leaves the part the camera sees a
// tiny share of the paths: the interior goes dark and noisy. Warned about, naming the node, when
//  (1) the bounding box of all geometry is more than kDominance times larger in diameter than
//      the box of the geometry outside the node's subtree (a node is taken with its descendants,
//      so that a far object built of several nodes is found by its root), and
//  (2) that rest is what the scene is about: a camera is nearer to its box than to the node's
//      (strictly: a camera inside both boxes decides nothing), or, in a scene without cameras,
//      the rest is the larger part. Without (2) a room would be reported for the small lamp
//      inside it: removing the room shrinks the box as much.
// The topmost such node is named, once. Not found: far geometry split among several root nodes
// that are far from the rest but near each other (no one of them alone shrinks the box).
void warnAboutDominantGeometry(const std::vector<int>& order, const std::vector<int>& parent, Scene& scene)
{
    constexpr double kDominance = 10.0;
    const std::size_t count = order.size();
    if (count < 2)
        return;
    std::vector<std::size_t> pre(parent.size(), 0);
    for (std::size_t k = 0; k < count; ++k)
        pre[static_cast<std::size_t>(order[k])] = k;
    std::vector<Box> own(count), subtree(count);
    for (std::size_t t = 0; t < scene.triangles.size(); ++t)
        for (const glm::vec3* p : {&scene.triangles[t].p0, &scene.triangles[t].p1, &scene.triangles[t].p2})
            own[pre[scene.triangleNode[t]]].grow(glm::dvec3(*p));
    // Pre-order puts a subtree in one run [k, end[k]) after its root: sizes from the back.
    std::vector<std::size_t> end(count);
    for (std::size_t k = count; k-- > 0;) {
        subtree[k].grow(own[k]);
        end[k] = std::max(end[k], k + 1);
        const int p = parent[static_cast<std::size_t>(order[k])];
        if (p >= 0) {
            const std::size_t pk = pre[static_cast<std::size_t>(p)];
            subtree[pk].grow(subtree[k]);
            end[pk] = std::max(end[pk], end[k]);
        }
    }
    std::vector<Box> before(count + 1), after(count + 1);  // boxes of order[0, k) and order[k, count)
    for (std::size_t k = 0; k < count; ++k) {
        before[k + 1] = before[k];
        before[k + 1].grow(own[k]);
    }
    for (std::size_t k = count; k-- > 0;) {
        after[k] = after[k + 1];
        after[k].grow(own[k]);
    }
    const double all = before[count].diameter();
    for (std::size_t k = 0; k < count;) {
        Box rest = before[k];
        rest.grow(after[end[k]]);
        const double restDiameter = rest.diameter();
        bool seen = false;
        for (const CameraSpec& c : scene.cameras)
            seen = seen || rest.distanceTo(c.position) < subtree[k].distanceTo(c.position);
        const bool restMatters = scene.cameras.empty() ? subtree[k].diameter() < restDiameter : seen;
        if (!rest.empty() && !subtree[k].empty() && all > kDominance * restDiameter && restMatters) {
            const int node = order[k];
            const std::string& name = scene.nodeNames[static_cast<std::size_t>(node)];
            scene.warnings.push_back(cat(
                scene.source, ": node ", node, name.empty() ? "" : cat(" '", printable(name), "'"),
                " makes the scene's bounding box ", all / std::max(restDiameter, 1e-30), " times larger (",
                all, " m across) than the rest of the geometry (", restDiameter,
                " m): uniform emission spreads its paths over the whole box, and the rest may come out "
                "dark and noisy (--method portal does not mind)"));
            k = end[k];  // its descendants would say the same
        } else {
            ++k;
        }
    }
}

}  // namespace

Scene loadGltf(const std::string& path)
{
    const std::vector<unsigned char> bytes = readSceneFile(path);
    const std::string folder = std::filesystem::path(path).parent_path().string();
    return loadGltfFromMemory(bytes.data(), bytes.size(), path, folder);
}

Scene loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& path,
                         const std::string& folder)
{
    if (size > kMaxSceneFileBytes)
        throw Error(cat(path, ": larger than ", kMaxSceneFileBytes, " bytes, the most a scene file may hold"));
    const bool binary = endsWith(path, ".glb") || (size >= 4 && std::memcmp(data, "glTF", 4) == 0);
    // tinygltf trusts a GLB's chunk lengths (2.7 reads past the end when BIN's is 8 too long):
    // it sees the bytes only once their framing is checked, and only the header's length of them.
    std::size_t glbLength = 0;
    const char* json = reinterpret_cast<const char*>(data);
    std::size_t jsonSize = size;
    if (binary) {
        const GlbLayout glb = checkGlb(data, size, path);
        glbLength = glb.length;
        json += glb.jsonOffset;
        jsonSize = glb.jsonSize;
    }
    // Parsers recurse (tinygltf's extras, nlohmann's dump): bound the depth before any of them.
    checkJsonNesting(json, jsonSize, path);
    const nlohmann::json doc = parseGltfJson(json, jsonSize, path);
    SceneFolder sceneFolder(folder);
    checkGltfJson(doc, path, sceneFolder);

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    // Images are kept encoded, and decoded only when a material's base colour uses them (an
    // unused or missing image costs nothing and fails nothing).
    EncodedImages images;
    loader.SetImageLoader(keepEncodedImage, &images);
    // Every external file tinygltf reads goes through the folder's rule (scene_files.h).
    sceneFolder.install(loader);
    std::string err, warn;
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data,
                                             static_cast<unsigned int>(glbLength), sceneFolder.path())
               : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data),
                                            static_cast<unsigned int>(size), sceneFolder.path());
    if (!ok && !sceneFolder.refusal().empty())
        throw Error(cat(path, ": ", sceneFolder.refusal()));
    if (!ok) {
        std::string msg = err.empty() ? warn : err;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' '))
            msg.pop_back();
        for (auto& c : msg)
            if (c == '\n')
                c = ';';
        throw Error(cat(path, ": not a valid glTF file: ", msg.empty() ? "unknown error" : printable(msg)));
    }
    const auto supported = [](const std::string& ext) {
        return ext == "KHR_materials_transmission" || ext == "KHR_materials_ior" || ext == "KHR_lights_punctual";
    };
    for (const auto& ext : model.extensionsRequired)
        if (!supported(ext))
            throw Error(cat(path, ": requires extension ", printable(ext), ", which fenestra does not support"));

    Scene scene;
    scene.source = path;
    scene.files.push_back(path);
    for (const std::string& f : sceneFolder.filesRead())
        scene.files.push_back(f);
    scene.nodeNames.resize(model.nodes.size());
    scene.nodePortal.assign(model.nodes.size(), PortalMark::None);
    scene.nodeParent = checkNodeForest(model, path);
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        scene.nodeNames[i] = model.nodes[i].name;
    std::string ignored;
    for (const auto& ext : model.extensionsUsed)
        if (!supported(ext))
            ignored += (ignored.empty() ? "" : ", ") + printable(ext);
    if (!ignored.empty())
        scene.warnings.push_back(cat(path, ": extensions not supported, ignored: ", printable(ignored, 400)));
    scene.materials = readMaterials(model, doc, path, images, scene);
    if (model.scenes.empty())
        throw Error(cat(path, ": the file has no scene"));
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (sceneIndex >= static_cast<int>(model.scenes.size()))
        throw Error(cat(path, ": default scene ", sceneIndex, " does not exist"));
    const tinygltf::Scene& gscene = model.scenes[static_cast<std::size_t>(sceneIndex)];

    const nlohmann::json& sceneExtras = member(element(member(doc, "scenes"), static_cast<std::size_t>(sceneIndex)), "extras");
    if (!sceneExtras.is_null()) {
        const std::string where = cat(path, ": scenes[", sceneIndex, "].extras");
        JsonReader r(sceneExtras, where);
        if (r.has("sky"))
            scene.sky = readSky(r.raw("sky"), r.keyPath("sky"));
        r.rejectUnknownKeys();
    }

    // The node forest, walked in the order a recursive walk would take (cameras keep it) with an
    // explicit stack: a legal hierarchy may be 10,000 deep. It is a forest (checkNodeForest), so
    // every node is visited at most once.
    checkSceneRoots(model, sceneIndex, scene.nodeParent, path);
    std::vector<std::pair<int, glm::dmat4>> stack;
    std::vector<int> order;  // the nodes in the order visited
    for (auto it = gscene.nodes.rbegin(); it != gscene.nodes.rend(); ++it)
        stack.emplace_back(*it, glm::dmat4(1.0));
    while (!stack.empty()) {
        const int node = stack.back().first;
        const glm::dmat4 parent = stack.back().second;
        stack.pop_back();
        order.push_back(node);
        const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
        const std::string where = cat(path, ": ", nodeLabel(model, node));
        const glm::dmat4 xf = parent * localTransform(n);
        // Finite numbers whose product overflows: a camera at infinity renders a flat image, a sun
        // along NaN nothing. (Vertices are checked one by one.)
        const bool placesSomething =
            n.camera >= 0 || !member(member(element(member(doc, "nodes"), static_cast<std::size_t>(node)),
                                            "extensions"), "KHR_lights_punctual").is_null();
        if (placesSomething && !isFiniteMatrix(xf))
            throw Error(cat(where, ": its world transform is not finite (the transforms of it and its "
                                   "parents overflow)"));
        std::optional<double> sensorCell;  // extras.sensor: the node measures light
        const nlohmann::json& rawNode = element(member(doc, "nodes"), static_cast<std::size_t>(node));
        const nlohmann::json& extras = member(rawNode, "extras");
        if (!extras.is_null()) {
            JsonReader r(extras, where + ".extras");
            if (r.has("portal")) {
                const nlohmann::json& p = r.raw("portal");
                // Blender writes a custom property ticked as a boolean, or typed as 1, as either.
                if (p.is_boolean() || (p.is_number_integer() && (p == 0 || p == 1)))
                    scene.nodePortal[static_cast<std::size_t>(node)] =
                        (p.is_boolean() ? p.get<bool>() : p == 1) ? PortalMark::Panes : PortalMark::None;
                else if (p.is_string() && p.get<std::string>() == "hull")
                    scene.nodePortal[static_cast<std::size_t>(node)] = PortalMark::Hull;
                else
                    throw Error(cat(r.keyPath("portal"), ": must be true, false (or 1, 0) or \"hull\", not ",
                                    describe(p)));
            }
            if (r.has("sensor")) {
                // true (cells of 0.1 m), or {"cell_m": side}: the node's triangles measure light
                // and block none (host/sensor/sensor_set.h).
                const nlohmann::json& v = r.raw("sensor");
                if (v.is_boolean() || (v.is_number_integer() && (v == 0 || v == 1))) {
                    if (v.is_boolean() ? v.get<bool>() : v == 1)
                        sensorCell = 0.1;
                } else if (v.is_object()) {
                    JsonReader sr(v, r.keyPath("sensor"));
                    sensorCell = sr.number("cell_m", 0.1);
                    if (!(*sensorCell > 0.0) || !std::isfinite(*sensorCell) || *sensorCell > 1e4)
                        throw Error(cat(sr.keyPath("cell_m"), ": ", *sensorCell,
                                        " must be a cell side in metres, more than 0 and at most 10 km"));
                    sr.rejectUnknownKeys();
                } else {
                    throw Error(cat(r.keyPath("sensor"), ": must be true, false or {\"cell_m\": side in metres}, not ",
                                    describe(v)));
                }
                if (sensorCell && scene.nodePortal[static_cast<std::size_t>(node)] != PortalMark::None)
                    throw Error(cat(r.keyPath("sensor"), ": the node is also a portal; a sensor blocks nothing, "
                                                       "so it cannot be a window"));
            }
            r.rejectUnknownKeys();
        }

        if (n.mesh >= 0) {
            if (n.mesh >= static_cast<int>(model.meshes.size()))
                throw Error(cat(where, " names mesh ", n.mesh, ", which does not exist"));
            const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(n.mesh)];
            const std::size_t first = scene.triangles.size();
            for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi)
                addPrimitive(model, mesh.primitives[pi], xf, node,
                             cat(where, ", mesh ", n.mesh, ", primitive ", pi), scene);
            if (sensorCell) {
                // A sensor's triangles leave the geometry: they measure, they block nothing.
                SensorMesh sm;
                sm.name = n.name.empty() ? cat("node ", node) : n.name;
                sm.source = where;
                sm.cell_m = *sensorCell;
                sm.triangles.assign(scene.triangles.begin() + static_cast<std::ptrdiff_t>(first), scene.triangles.end());
                scene.triangles.resize(first);
                scene.triangleNode.resize(first);
                scene.triangleMaterial.resize(first);
                if (scene.triangleUv.size() > first)
                    scene.triangleUv.resize(first);
                scene.sensorMeshes.push_back(std::move(sm));
            }
        } else if (sensorCell) {
            throw Error(cat(where, ".extras.sensor: the node has no mesh to measure on"));
        }
        if (n.camera >= 0) {
            scene.cameras.push_back(readCamera(model, node, xf, where));
            // Light paths reach a view in proportion to the surface it sees: a narrow one gets few.
            const double yfovDeg = scene.cameras.back().yfovRad * 180.0 / M_PI;
            if (yfovDeg < 1.0)
                scene.warnings.push_back(cat(where, ": camera ", n.camera, " sees only ", yfovDeg,
                                             " degrees; light paths reach so narrow a view rarely, and a short "
                                             "render may come out black or noisy"));
        }

        const nlohmann::json& light = member(member(rawNode, "extensions"), "KHR_lights_punctual");
        if (!light.is_null()) {
            JsonReader r(light, where + ".extensions.KHR_lights_punctual");
            const std::int64_t li = r.integer("light");
            r.rejectUnknownKeys();
            if (li < 0 || li >= static_cast<std::int64_t>(model.lights.size()))
                throw Error(cat(r.keyPath("light"), ": ", li, " is not an index of KHR_lights_punctual.lights (",
                                model.lights.size(), " of them)"));
            const tinygltf::Light& L = model.lights[static_cast<std::size_t>(li)];
            const std::string lwhere = cat(path, ": KHR_lights_punctual.lights[", li, "]");
            if (L.type != "directional")
                throw Error(cat(lwhere, ": '", printable(L.type), "' lights are not supported; the sun is the one "
                                "directional light"));
            if (scene.sun.present)
                throw Error(cat(where, ": a second directional light; the sun is the only one "
                                "(already on node '", printable(scene.sun.nodeName), "')"));
            if (!(L.intensity >= 0.0) || !std::isfinite(L.intensity))
                throw Error(cat(lwhere, ".intensity: ", L.intensity, " must be >= 0 (lux)"));
            glm::dvec3 color(1.0);
            if (!L.color.empty()) {
                if (L.color.size() != 3)
                    throw Error(cat(lwhere, ".color: must have 3 components"));
                for (int c = 0; c < 3; ++c) {
                    color[c] = L.color[static_cast<std::size_t>(c)];
                    if (!(color[c] >= 0.0) || !std::isfinite(color[c]))
                        throw Error(cat(lwhere, ".color[", c, "]: must be >= 0"));
                }
            }
            scene.sun.present = true;
            scene.sun.nodeName = n.name.empty() ? cat("node ", node) : n.name;
            const glm::dvec3 minusZ = -glm::dvec3(xf[2]);
            if (glm::length(minusZ) == 0.0)
                throw Error(cat(where, ": the sun's transform is degenerate"));
            scene.sun.travelDirection = glm::normalize(minusZ);
            if (!(scene.sun.travelDirection.y < 0.0))
                throw Error(cat(where, ": the sun is below the horizon (its light travels along -z = (",
                                scene.sun.travelDirection.x, ", ", scene.sun.travelDirection.y, ", ",
                                scene.sun.travelDirection.z, "), not downwards)"));
            scene.sun.illuminanceRgb_lux = L.intensity * color;
            checkLight(std::max({scene.sun.illuminanceRgb_lux.r, scene.sun.illuminanceRgb_lux.g,
                                 scene.sun.illuminanceRgb_lux.b}),
                       lwhere + ".intensity * color");
            const nlohmann::json& lextras =
                member(element(member(member(member(doc, "extensions"), "KHR_lights_punctual"), "lights"),
                               static_cast<std::size_t>(li)),
                       "extras");
            if (!lextras.is_null()) {
                JsonReader le(lextras, lwhere + ".extras");
                const double deg = le.number("angular_radius_deg", 0.0);
                if (!(deg >= 0.0 && deg <= 10.0))
                    throw Error(cat(le.keyPath("angular_radius_deg"), ": ", deg,
                                    " must be in [0, 10] degrees"));
                le.rejectUnknownKeys();
                scene.sun.angularRadiusRad = deg * M_PI / 180.0;
            }
        }
        for (auto it = n.children.rbegin(); it != n.children.rend(); ++it)
            stack.emplace_back(*it, xf);
    }

    for (const auto& t : scene.triangles) {
        scene.bounds.grow(t.p0);
        scene.bounds.grow(t.p1);
        scene.bounds.grow(t.p2);
    }
    warnAboutDominantGeometry(order, scene.nodeParent, scene);
    // A CIE sky is drawn for a sun position; a directional light elsewhere is likely a mistake.
    if (scene.sun.present && scene.sky.type == SkySpec::Type::Cie) {
        const glm::dvec3 toSun = -scene.sun.travelDirection;
        const double alt = std::asin(std::clamp(toSun.y, -1.0, 1.0)) * 180.0 / M_PI;
        const double h = scene.sky.sunAltitudeDeg * M_PI / 180.0, A = scene.sky.sunAzimuthDeg * M_PI / 180.0;
        const glm::dvec3 skySun(std::cos(h) * std::sin(A), std::sin(h), -std::cos(h) * std::cos(A));
        const double apart = std::acos(std::clamp(glm::dot(toSun, skySun), -1.0, 1.0)) * 180.0 / M_PI;
        if (apart > 1.0)
            scene.warnings.push_back(cat(path, ": the sun (node '", printable(scene.sun.nodeName), "', altitude ",
                                         alt, " deg) is ", apart, " deg from the CIE sky's sun ",
                                         "(sun_altitude_deg / sun_azimuth_deg)"));
    }
    return scene;
}

const CameraSpec& findCamera(const Scene& scene, const std::string& name)
{
    if (scene.cameras.empty())
        throw Error(cat(scene.source, ": the scene has no camera"));
    if (name.empty())
        return scene.cameras.front();
    for (const auto& c : scene.cameras)
        if (c.nodeName == name)
            return c;
    for (const auto& c : scene.cameras)
        if (c.cameraName == name)
            return c;
    std::string names;
    for (const auto& c : scene.cameras)
        names += (names.empty() ? "'" : ", '") + printable(c.nodeName.empty() ? c.cameraName : c.nodeName) + "'";
    throw Error(cat(scene.source, ": no camera named '", printable(name), "' (cameras: ", printable(names, 2000), ")"));
}

}  // namespace fen

namespace fen {

std::string nodesWithGeometry(const Scene& scene)
{
    std::set<std::string> withGeometry;
    for (std::uint32_t n : scene.triangleNode)
        withGeometry.insert(scene.nodeNames[n].empty() ? cat("node ", n) : scene.nodeNames[n]);
    std::string names;
    for (const auto& s : withGeometry)
        names += (names.empty() ? "'" : ", '") + s + "'";
    return names;
}

}  // namespace fen
