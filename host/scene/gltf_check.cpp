// gltf_check.cpp — checks on a glTF document's JSON before tinygltf reads it (gltf_check.h).
#include "scene/gltf_check.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>

#include "scene/json_reader.h"
#include "scene/scene_files.h"
#include "util/error.h"

namespace fen {

namespace {

using nlohmann::json;

// Top-level array `key` ("nodes", "meshes", ...) whose elements must all be objects; absent: empty.
const json& objects(const json& doc, const char* key, const std::string& path)
{
    static const json none = json::array();
    const json& v = member(doc, key);
    if (v.is_null())
        return none;
    if (!v.is_array())
        throw Error(cat(path, ": ", key, ": must be an array, not ", describe(v)));
    for (std::size_t i = 0; i < v.size(); ++i)
        if (!v[i].is_object())
            throw Error(cat(path, ": ", key, "[", i, "]: must be an object, not ", describe(v[i])));
    return v;
}

// An unsigned JSON integer no larger than `max`, as uint64 (tinygltf would have cast it to int).
bool isUnsigned(const json& v, std::uint64_t max)
{
    return v.is_number_unsigned() && v.get<std::uint64_t>() <= max;
}

// `v` names one of `count` elements of `list`.
void checkIndex(const json& v, std::size_t count, const char* list, const std::string& where)
{
    if (!isUnsigned(v, count == 0 ? 0 : count - 1) || count == 0)
        throw Error(cat(where, ": ", describe(v), " is not an index of ", list, " (", count, " of them)"));
}

// obj[key], when present, names one of `count` elements of `list`.
void checkIndexMember(const json& obj, const char* key, std::size_t count, const char* list,
                      const std::string& where)
{
    if (obj.contains(key))
        checkIndex(obj[key], count, list, cat(where, ".", key));
}

// obj[key], when present (or always, when required), an integer in [lo, hi].
void checkInteger(const json& obj, const char* key, std::uint64_t lo, std::uint64_t hi, bool required,
                  const std::string& where)
{
    if (!obj.contains(key)) {
        if (required)
            throw Error(cat(where, ".", key, ": missing"));
        return;
    }
    const json& v = obj[key];
    if (!isUnsigned(v, hi) || v.get<std::uint64_t>() < lo)
        throw Error(cat(where, ".", key, ": must be an integer from ", lo, " to ", hi, ", not ", describe(v)));
}

// Skins and animations are not used, but every index in them must name something that exists
// (glTF 2.0; tinygltf would read an index of 2^32 as 0).
void checkAnimationAndSkinIndices(const json& doc, std::size_t nodes, std::size_t accessors, const std::string& path)
{
    const json& skins = objects(doc, "skins", path);
    for (std::size_t i = 0; i < skins.size(); ++i) {
        const std::string where = cat(path, ": skins[", i, "]");
        checkIndexMember(skins[i], "inverseBindMatrices", accessors, "accessors", where);
        checkIndexMember(skins[i], "skeleton", nodes, "nodes", where);
        const json& joints = member(skins[i], "joints");
        if (!joints.is_array())
            throw Error(cat(where, ".joints: must be an array of node indices, not ", describe(joints)));
        for (std::size_t k = 0; k < joints.size(); ++k)
            checkIndex(joints[k], nodes, "nodes", cat(where, ".joints[", k, "]"));
    }
    const json& animations = objects(doc, "animations", path);
    for (std::size_t i = 0; i < animations.size(); ++i) {
        const std::string where = cat(path, ": animations[", i, "]");
        const json& samplers = member(animations[i], "samplers");
        const json& channels = member(animations[i], "channels");
        if (!samplers.is_array() || !channels.is_array())
            throw Error(cat(where, ": must have arrays 'samplers' and 'channels'"));
        for (std::size_t k = 0; k < samplers.size(); ++k) {
            const std::string at = cat(where, ".samplers[", k, "]");
            if (!samplers[k].is_object())
                throw Error(cat(at, ": must be an object, not ", describe(samplers[k])));
            for (const char* key : {"input", "output"}) {
                if (!samplers[k].contains(key))
                    throw Error(cat(at, ".", key, ": missing"));
                checkIndex(samplers[k][key], accessors, "accessors", cat(at, ".", key));
            }
        }
        for (std::size_t k = 0; k < channels.size(); ++k) {
            const std::string at = cat(where, ".channels[", k, "]");
            if (!channels[k].is_object())
                throw Error(cat(at, ": must be an object, not ", describe(channels[k])));
            if (!channels[k].contains("sampler"))
                throw Error(cat(at, ".sampler: missing"));
            checkIndex(channels[k]["sampler"], samplers.size(), "the animation's samplers", cat(at, ".sampler"));
            const json& target = member(channels[k], "target");
            if (!target.is_object())
                throw Error(cat(at, ".target: must be an object, not ", describe(target)));
            checkIndexMember(target, "node", nodes, "nodes", at + ".target");
        }
    }
}

// The texture references every material makes (textureInfo objects: base colour, metallic-roughness,
// normal, occlusion, emissive), textures' images and samplers, and the samplers' enumerations:
// tinygltf would take an index of 2^32 as 0 and an unknown wrap mode as REPEAT.
void checkTextureIndices(const json& doc, const json& materials, const json& images, const std::string& path)
{
    const json& textures = objects(doc, "textures", path);
    const json& samplers = objects(doc, "samplers", path);
    auto textureInfo = [&](const json& owner, const char* key, const std::string& where) {
        const json& info = member(owner, key);
        if (info.is_null())
            return;
        const std::string at = cat(where, ".", key);
        if (!info.is_object())
            throw Error(cat(at, ": must be an object, not ", describe(info)));
        if (!info.contains("index"))
            throw Error(cat(at, ".index: missing"));
        checkIndex(info["index"], textures.size(), "textures", at + ".index");
        checkInteger(info, "texCoord", 0, 7, false, at);
    };
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const std::string where = cat(path, ": materials[", i, "]");
        const json& pbr = member(materials[i], "pbrMetallicRoughness");
        if (!pbr.is_null() && !pbr.is_object())
            throw Error(cat(where, ".pbrMetallicRoughness: must be an object, not ", describe(pbr)));
        if (pbr.is_object()) {
            textureInfo(pbr, "baseColorTexture", where + ".pbrMetallicRoughness");
            textureInfo(pbr, "metallicRoughnessTexture", where + ".pbrMetallicRoughness");
        }
        for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
            textureInfo(materials[i], key, where);
    }
    for (std::size_t i = 0; i < textures.size(); ++i) {
        const std::string where = cat(path, ": textures[", i, "]");
        checkIndexMember(textures[i], "source", images.size(), "images", where);
        checkIndexMember(textures[i], "sampler", samplers.size(), "samplers", where);
    }
    for (std::size_t i = 0; i < samplers.size(); ++i) {
        const std::string where = cat(path, ": samplers[", i, "]");
        for (const char* key : {"wrapS", "wrapT"}) {
            const json& v = member(samplers[i], key);
            if (!v.is_null() && !(isUnsigned(v, 65535) && (v == 10497 || v == 33071 || v == 33648)))
                throw Error(cat(where, ".", key, ": ", describe(v),
                                " is not a wrap mode (10497 REPEAT, 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT)"));
        }
        const json& mag = member(samplers[i], "magFilter");
        if (!mag.is_null() && !(isUnsigned(mag, 65535) && (mag == 9728 || mag == 9729)))
            throw Error(cat(where, ".magFilter: ", describe(mag), " is not a magnification filter (9728 NEAREST, "
                                                                  "9729 LINEAR)"));
    }
}

// Every index fenestra or tinygltf follows, every size, offset, count and enumeration, read as
// the 64-bit integer it is written as: tinygltf 2.7 casts indices to int (2^32 becomes 0) and
// treats a size it cannot read as absent (a byteOffset of -4 or 4.0 becomes 0).
void checkIndicesAndSizes(const json& doc, const std::string& path)
{
    const std::uint64_t any = std::numeric_limits<std::uint64_t>::max();
    const json& scenes = objects(doc, "scenes", path);
    const json& nodes = objects(doc, "nodes", path);
    const json& meshes = objects(doc, "meshes", path);
    const json& accessors = objects(doc, "accessors", path);
    const json& bufferViews = objects(doc, "bufferViews", path);
    const json& buffers = objects(doc, "buffers", path);
    const json& materials = objects(doc, "materials", path);
    const json& cameras = objects(doc, "cameras", path);
    const json& images = objects(doc, "images", path);

    if (doc.contains("scene"))
        checkIndex(doc["scene"], scenes.size(), "scenes", path + ": scene");
    auto nodeList = [&](const json& obj, const char* key, const std::string& where) {
        if (!obj.contains(key))
            return;
        const json& list = obj[key];
        if (!list.is_array())
            throw Error(cat(where, ".", key, ": must be an array of node indices, not ", describe(list)));
        for (std::size_t k = 0; k < list.size(); ++k)
            checkIndex(list[k], nodes.size(), "nodes", cat(where, ".", key, "[", k, "]"));
    };
    for (std::size_t i = 0; i < scenes.size(); ++i)
        nodeList(scenes[i], "nodes", cat(path, ": scenes[", i, "]"));
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const std::string where = cat(path, ": nodes[", i, "]");
        nodeList(nodes[i], "children", where);
        checkIndexMember(nodes[i], "mesh", meshes.size(), "meshes", where);
        checkIndexMember(nodes[i], "camera", cameras.size(), "cameras", where);
        checkIndexMember(nodes[i], "skin", objects(doc, "skins", path).size(), "skins", where);
    }
    checkAnimationAndSkinIndices(doc, nodes.size(), accessors.size(), path);
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const json& prims = member(meshes[i], "primitives");
        const std::string mesh = cat(path, ": meshes[", i, "].primitives");
        if (!prims.is_array())
            throw Error(cat(mesh, ": must be an array, not ", describe(prims)));
        if (prims.empty())  // glTF requires one; without, the mesh would vanish without a word
            throw Error(cat(mesh, ": is empty; a mesh has at least one primitive"));
        for (std::size_t j = 0; j < prims.size(); ++j) {
            const std::string where = cat(mesh, "[", j, "]");
            const json& prim = prims[j];
            if (!prim.is_object())
                throw Error(cat(where, ": must be an object, not ", describe(prim)));
            const json& attributes = member(prim, "attributes");
            if (!attributes.is_object())
                throw Error(cat(where, ".attributes: must be an object, not ", describe(attributes)));
            for (auto it = attributes.begin(); it != attributes.end(); ++it)
                checkIndex(it.value(), accessors.size(), "accessors",
                           cat(where, ".attributes.", printable(it.key(), 60)));
            // Morph targets are not used, but their accessors must exist (glTF: every index does).
            const json& targets = member(prim, "targets");
            if (!targets.is_null() && !targets.is_array())
                throw Error(cat(where, ".targets: must be an array, not ", describe(targets)));
            for (std::size_t t = 0; targets.is_array() && t < targets.size(); ++t) {
                if (!targets[t].is_object())
                    throw Error(cat(where, ".targets[", t, "]: must be an object, not ", describe(targets[t])));
                for (auto it = targets[t].begin(); it != targets[t].end(); ++it)
                    checkIndex(it.value(), accessors.size(), "accessors",
                               cat(where, ".targets[", t, "].", printable(it.key(), 60)));
            }
            checkIndexMember(prim, "indices", accessors.size(), "accessors", where);
            checkIndexMember(prim, "material", materials.size(), "materials", where);
            checkInteger(prim, "mode", 0, 6, false, where);
        }
    }
    for (std::size_t i = 0; i < accessors.size(); ++i) {
        const std::string where = cat(path, ": accessors[", i, "]");
        checkIndexMember(accessors[i], "bufferView", bufferViews.size(), "bufferViews", where);
        checkInteger(accessors[i], "byteOffset", 0, any, false, where);
        checkInteger(accessors[i], "count", 1, any, true, where);
        checkInteger(accessors[i], "componentType", 5120, 5126, true, where);
        if (accessors[i]["componentType"] == 5124)  // there is no signed 32-bit type in glTF
            throw Error(cat(where, ".componentType: 5124 is not a glTF component type"));
    }
    for (std::size_t i = 0; i < bufferViews.size(); ++i) {
        const std::string where = cat(path, ": bufferViews[", i, "]");
        checkIndexMember(bufferViews[i], "buffer", buffers.size(), "buffers", where);
        if (!bufferViews[i].contains("buffer"))
            throw Error(cat(where, ".buffer: missing"));
        checkInteger(bufferViews[i], "byteOffset", 0, any, false, where);
        checkInteger(bufferViews[i], "byteLength", 1, any, true, where);
        checkInteger(bufferViews[i], "byteStride", 4, 252, false, where);
        if (bufferViews[i].contains("byteStride") && bufferViews[i]["byteStride"].get<std::uint64_t>() % 4 != 0)
            throw Error(cat(where, ".byteStride: ", bufferViews[i]["byteStride"].get<std::uint64_t>(),
                            " is not a multiple of 4"));
    }
    for (std::size_t i = 0; i < buffers.size(); ++i)
        checkInteger(buffers[i], "byteLength", 1, any, true, cat(path, ": buffers[", i, "]"));
    checkTextureIndices(doc, materials, images, path);
    // tinygltf passes an image's bytes on as &buffer.data[byteOffset] without a check of its own
    // (accessors' views are checked where they are read, gltf_load.cpp).
    for (std::size_t i = 0; i < images.size(); ++i) {
        const std::string where = cat(path, ": images[", i, "]");
        checkIndexMember(images[i], "bufferView", bufferViews.size(), "bufferViews", where);
        if (!images[i].contains("bufferView"))
            continue;
        const std::size_t v = images[i]["bufferView"].get<std::size_t>();
        const json& view = bufferViews[v];
        const std::size_t b = view["buffer"].get<std::size_t>();
        const std::uint64_t offset = view.value("byteOffset", std::uint64_t(0));
        const std::uint64_t length = view["byteLength"].get<std::uint64_t>();
        const std::uint64_t bufferLength = buffers[b]["byteLength"].get<std::uint64_t>();
        std::uint64_t end = 0;
        if (__builtin_add_overflow(offset, length, &end) || end > bufferLength)
            throw Error(cat(where, ".bufferView: bufferViews[", v, "] (byteOffset ", offset, ", byteLength ", length,
                            ") lies outside buffers[", b, "] (byteLength ", bufferLength, ")"));
    }
}

// buffers[i].uri / images[i].uri: inside the folder, and an external buffer exactly byteLength
// long (tinygltf's rule; its own message would quote the file's size).
void checkUris(const nlohmann::json& doc, const std::string& path, const SceneFolder& folder)
{
    for (const char* key : {"buffers", "images"}) {
        const auto list = doc.find(key);
        if (list == doc.end() || !list->is_array())
            continue;
        const bool buffer = std::string(key) == "buffers";
        for (std::size_t i = 0; i < list->size(); ++i) {
            const nlohmann::json& item = (*list)[i];
            const std::string where = cat(path, ": ", key, "[", i, "]");
            if (!item.is_object() || !item.contains("uri"))
                continue;
            const nlohmann::json& uri = item["uri"];
            if (!uri.is_string())
                throw Error(cat(where, ".uri: must be a string"));
            if (uri.get<std::string>().empty())
                continue;  // no file: a GLB's BIN chunk (tinygltf reports it elsewhere)
            // Images are ignored: one missing is no reason to refuse the scene.
            const std::string file = folder.resolve(uri.get<std::string>(), where + ".uri", buffer);
            if (!buffer || file.empty())
                continue;
            const auto length = item.find("byteLength");
            std::error_code ec;
            const std::uintmax_t size = std::filesystem::file_size(file, ec);
            if (length != item.end() && length->is_number_unsigned() &&
                (ec || size != length->get<std::uint64_t>()))
                throw Error(cat(where, ".uri: '", printable(uri.get<std::string>()),
                                "' is not byteLength ", length->get<std::uint64_t>(), " bytes long"));
        }
    }
}

// --- Shapes and types of the members fenestra reads -------------------------------------------
// tinygltf drops a member of the wrong type or length: a 3-element baseColorFactor left the
// material white, a 2-element translation was ignored, a string yfov or aspectRatio fell back to
// a default. JSON numbers are always finite here (nlohmann refuses 1e400).

bool has(const json& obj, const char* key) { return obj.is_object() && obj.contains(key); }

void checkString(const json& obj, const char* key, bool required, const std::string& where)
{
    if (!has(obj, key)) {
        if (required)
            throw Error(cat(where, ".", key, ": missing"));
        return;
    }
    if (!obj[key].is_string())
        throw Error(cat(where, ".", key, ": must be a string, not ", describe(obj[key])));
}

void checkNumber(const json& obj, const char* key, bool required, const std::string& where)
{
    if (!has(obj, key)) {
        if (required)
            throw Error(cat(where, ".", key, ": missing"));
        return;
    }
    if (!obj[key].is_number())
        throw Error(cat(where, ".", key, ": must be a number, not ", describe(obj[key])));
}

void checkObject(const json& obj, const char* key, const std::string& where)
{
    if (has(obj, key) && !obj[key].is_object())
        throw Error(cat(where, ".", key, ": must be a JSON object, not ", describe(obj[key])));
}

// obj[key], when present: an array of exactly n numbers.
void checkNumbers(const json& obj, const char* key, std::size_t n, const std::string& where)
{
    if (!has(obj, key))
        return;
    const json& v = obj[key];
    if (!v.is_array() || v.size() != n)
        throw Error(cat(where, ".", key, ": must be an array of ", n, " numbers, not ", describe(v)));
    for (std::size_t k = 0; k < n; ++k)
        if (!v[k].is_number())
            throw Error(cat(where, ".", key, "[", k, "]: must be a number, not ", describe(v[k])));
}

void checkStrings(const json& doc, const char* key, const std::string& path)
{
    if (!has(doc, key))
        return;
    const json& v = doc[key];
    if (!v.is_array())
        throw Error(cat(path, ": ", key, ": must be an array of strings, not ", describe(v)));
    for (std::size_t k = 0; k < v.size(); ++k)
        if (!v[k].is_string())
            throw Error(cat(path, ": ", key, "[", k, "]: must be a string, not ", describe(v[k])));
}

void checkNode(const json& node, const std::string& where)
{
    checkString(node, "name", false, where);
    checkObject(node, "extensions", where);
    checkNumbers(node, "matrix", 16, where);
    checkNumbers(node, "translation", 3, where);
    checkNumbers(node, "rotation", 4, where);
    checkNumbers(node, "scale", 3, where);
    // tinygltf would take the matrix and drop the rest without a word.
    if (has(node, "matrix") && (has(node, "translation") || has(node, "rotation") || has(node, "scale")))
        throw Error(cat(where, ": has both a matrix and translation/rotation/scale; glTF allows one or the other"));
    if (has(node, "rotation")) {
        // A non-unit quaternion is a rotation and a scale and a shear; exporters write unit ones
        // to float precision, far inside this tolerance.
        double len2 = 0.0;
        for (const json& q : node["rotation"])
            len2 += q.get<double>() * q.get<double>();
        if (!(std::fabs(std::sqrt(len2) - 1.0) <= 1e-3))
            throw Error(cat(where, ".rotation: must be a unit quaternion (its length is ", std::sqrt(len2), ")"));
    }
}

void checkMaterial(const json& m, const std::string& where)
{
    checkString(m, "name", false, where);
    checkObject(m, "pbrMetallicRoughness", where);
    const json& pbr = member(m, "pbrMetallicRoughness");
    checkNumbers(pbr, "baseColorFactor", 4, where + ".pbrMetallicRoughness");
    checkObject(pbr, "baseColorTexture", where + ".pbrMetallicRoughness");
    checkNumbers(m, "emissiveFactor", 3, where);
    checkObject(m, "emissiveTexture", where);
    checkObject(m, "extensions", where);
}

void checkCamera(const json& c, const std::string& where)
{
    checkString(c, "name", false, where);
    checkString(c, "type", true, where);
    checkObject(c, "perspective", where);
    const json& p = member(c, "perspective");
    if (!p.is_object())
        return;  // an orthographic camera: refused by name when it is used
    const std::string at = where + ".perspective";
    checkNumber(p, "yfov", true, at);
    checkNumber(p, "znear", false, at);
    checkNumber(p, "zfar", false, at);
    if (has(p, "aspectRatio") && !(p["aspectRatio"].is_number() && p["aspectRatio"].get<double>() > 0.0))
        throw Error(cat(at, ".aspectRatio: must be a positive number, not ", describe(p["aspectRatio"])));
}

void checkLights(const json& doc, const std::string& path)
{
    if (has(doc, "extensions") && !doc["extensions"].is_object())
        throw Error(cat(path, ": extensions: must be a JSON object, not ", describe(doc["extensions"])));
    const json& ext = member(member(doc, "extensions"), "KHR_lights_punctual");
    if (ext.is_null())
        return;
    if (!ext.is_object())
        throw Error(cat(path, ": extensions.KHR_lights_punctual: must be a JSON object, not ", describe(ext)));
    const json& lights = objects(ext, "lights", path + ": KHR_lights_punctual");
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const std::string where = cat(path, ": KHR_lights_punctual.lights[", i, "]");
        checkString(lights[i], "name", false, where);
        checkString(lights[i], "type", true, where);
        checkNumber(lights[i], "intensity", false, where);
        checkNumbers(lights[i], "color", 3, where);
    }
}

void checkShapes(const json& doc, const std::string& path)
{
    checkStrings(doc, "extensionsUsed", path);
    checkStrings(doc, "extensionsRequired", path);
    const json& nodes = objects(doc, "nodes", path);
    for (std::size_t i = 0; i < nodes.size(); ++i)
        checkNode(nodes[i], cat(path, ": nodes[", i, "]"));
    const json& materials = objects(doc, "materials", path);
    for (std::size_t i = 0; i < materials.size(); ++i)
        checkMaterial(materials[i], cat(path, ": materials[", i, "]"));
    const json& cameras = objects(doc, "cameras", path);
    for (std::size_t i = 0; i < cameras.size(); ++i)
        checkCamera(cameras[i], cat(path, ": cameras[", i, "]"));
    const json& accessors = objects(doc, "accessors", path);
    for (std::size_t i = 0; i < accessors.size(); ++i) {
        const std::string where = cat(path, ": accessors[", i, "]");
        const json& type = member(accessors[i], "type");
        static const char* const types[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
        if (!type.is_string() || std::find(std::begin(types), std::end(types), type.get<std::string>()) == std::end(types))
            throw Error(cat(where, ".type: must be one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4, not ",
                            describe(type)));
        checkObject(accessors[i], "sparse", where);
    }
    const json& scenes = objects(doc, "scenes", path);
    for (std::size_t i = 0; i < scenes.size(); ++i)
        checkString(scenes[i], "name", false, cat(path, ": scenes[", i, "]"));
    checkLights(doc, path);
}

}  // namespace

nlohmann::json parseGltfJson(const char* text, std::size_t size, const std::string& path)
{
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text, text + size);
    } catch (const nlohmann::json::exception& e) {
        throw Error(cat(path, ": not a valid glTF file: ", printable(e.what())));
    }
    if (!doc.is_object())
        throw Error(cat(path, ": not a valid glTF file: the top level is not a JSON object"));
    return doc;
}

void checkGltfJson(const nlohmann::json& doc, const std::string& path, const SceneFolder& folder)
{
    checkIndicesAndSizes(doc, path);
    checkShapes(doc, path);
    checkUris(doc, path, folder);
}

}  // namespace fen
