// gltf_load.cpp — glTF 2.0 to Scene (gltf_load.h), via tinygltf.
#include "scene/gltf_load.h"

#include <cstring>
#include <fstream>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

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
    return name.empty() ? cat("node ", node) : cat("node ", node, " '", name, "'");
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
        if (bv.byteOffset + bv.byteLength > buf.data.size())
            throw Error(cat(where_, ": bufferView ", acc_->bufferView, " lies outside buffer ",
                            bv.buffer, " (", buf.data.size(), " bytes",
                            buf.data.empty() ? "; was its file found?" : "", ")"));
        if (acc_->count > 0 &&
            acc_->byteOffset + stride_ * (acc_->count - 1) + elemSize_ > bv.byteLength)
            throw Error(cat(where_, ": ", acc_->count, " elements do not fit in bufferView ",
                            acc_->bufferView));
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
                throw Error(cat(ia.where(), ": index ", idx[i], " at ", i, " exceeds the ",
                                world.size(), " vertices"));
        }
    } else {
        idx.resize(world.size());
        for (std::size_t i = 0; i < idx.size(); ++i)
            idx[i] = static_cast<std::uint32_t>(i);
    }
    if (idx.size() % 3 != 0)
        throw Error(cat(where, ": ", idx.size(), " indices is not a whole number of triangles"));
    for (std::size_t i = 0; i < idx.size(); i += 3) {
        scene.triangles.push_back({world[idx[i]], world[idx[i + 1]], world[idx[i + 2]]});
        scene.triangleNode.push_back(static_cast<std::uint32_t>(node));
    }
}

}  // namespace

Scene loadGltf(const std::string& path)
{
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe)
            throw Error(cat(path, ": cannot open file"));
    }
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    // Textures are not used: do not decode images (and do not fail on a missing one).
    loader.SetImageLoader(
        [](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
           int, void*) { return true; },
        nullptr);
    std::string err, warn;
    const bool ok = endsWith(path, ".glb") ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok) {
        std::string msg = err.empty() ? warn : err;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' '))
            msg.pop_back();
        for (auto& c : msg)
            if (c == '\n')
                c = ';';
        throw Error(cat(path, ": not a valid glTF file: ", msg.empty() ? "unknown error" : msg));
    }

    Scene scene;
    scene.source = path;
    scene.nodeNames.resize(model.nodes.size());
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        scene.nodeNames[i] = model.nodes[i].name;
    if (model.scenes.empty())
        throw Error(cat(path, ": the file has no scene"));
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (sceneIndex >= static_cast<int>(model.scenes.size()))
        throw Error(cat(path, ": default scene ", sceneIndex, " does not exist"));

    std::vector<char> onPath(model.nodes.size(), 0);
    std::function<void(int, const glm::dmat4&)> visit = [&](int node, const glm::dmat4& parent) {
        if (node < 0 || node >= static_cast<int>(model.nodes.size()))
            throw Error(cat(path, ": reference to node ", node, ", which does not exist"));
        if (onPath[static_cast<std::size_t>(node)])
            throw Error(cat(path, ": ", nodeLabel(model, node), " is its own ancestor"));
        onPath[static_cast<std::size_t>(node)] = 1;
        const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
        const glm::dmat4 xf = parent * localTransform(n);
        if (n.mesh >= 0) {
            if (n.mesh >= static_cast<int>(model.meshes.size()))
                throw Error(cat(path, ": ", nodeLabel(model, node), " names mesh ", n.mesh,
                                ", which does not exist"));
            const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(n.mesh)];
            for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi)
                addPrimitive(model, mesh.primitives[pi], xf, node,
                             cat(path, ": ", nodeLabel(model, node), ", mesh ", n.mesh,
                                 ", primitive ", pi),
                             scene);
        }
        for (int c : n.children)
            visit(c, xf);
        onPath[static_cast<std::size_t>(node)] = 0;
    };
    for (int root : model.scenes[static_cast<std::size_t>(sceneIndex)].nodes)
        visit(root, glm::dmat4(1.0));

    for (const auto& t : scene.triangles) {
        scene.bounds.grow(t.p0);
        scene.bounds.grow(t.p1);
        scene.bounds.grow(t.p2);
    }
    return scene;
}

}  // namespace fen
