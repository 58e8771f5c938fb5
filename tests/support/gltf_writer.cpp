// gltf_writer.cpp — test glTF files (gltf_writer.h).
#include "support/gltf_writer.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fen { namespace test {

namespace {

std::string base64(const std::vector<unsigned char>& in)
{
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const unsigned v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += t[(v >> 6) & 63];
        out += t[v & 63];
    }
    if (i + 1 == in.size()) {
        const unsigned v = in[i] << 16;
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == in.size()) {
        const unsigned v = (in[i] << 16) | (in[i + 1] << 8);
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += t[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

}  // namespace

GltfWriter::GltfWriter()
{
    doc_ = {{"asset", {{"version", "2.0"}, {"generator", "fenestra tests"}}},
            {"scene", 0},
            {"scenes", nlohmann::json::array({{{"nodes", nlohmann::json::array()}}})},
            {"nodes", nlohmann::json::array()},
            {"meshes", nlohmann::json::array()},
            {"accessors", nlohmann::json::array()},
            {"bufferViews", nlohmann::json::array()},
            {"buffers", nlohmann::json::array()}};
}

int GltfWriter::addAccessor(const void* data, std::size_t bytes, int componentType,
                            const char* type, std::size_t count, int target)
{
    while (bin_.size() % 4)
        bin_.push_back(0);
    const std::size_t offset = bin_.size();
    bin_.resize(offset + bytes);
    std::memcpy(bin_.data() + offset, data, bytes);
    const int view = static_cast<int>(doc_["bufferViews"].size());
    doc_["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    nlohmann::json acc = {{"bufferView", view},
                          {"componentType", componentType},
                          {"count", count},
                          {"type", type}};
    if (std::string(type) == "VEC3" && count > 0) {
        const float* f = static_cast<const float*>(data);
        std::vector<float> lo(f, f + 3), hi(f, f + 3);
        for (std::size_t i = 0; i < count; ++i)
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], f[3 * i + a]);
                hi[a] = std::max(hi[a], f[3 * i + a]);
            }
        acc["min"] = lo;
        acc["max"] = hi;
    }
    doc_["accessors"].push_back(acc);
    return static_cast<int>(doc_["accessors"].size() - 1);
}

int GltfWriter::addMeshNode(const std::string& name, const std::vector<Triangle>& tris, int material)
{
    std::vector<float> pos;
    for (const auto& t : tris)
        for (const glm::vec3* p : {&t.p0, &t.p1, &t.p2})
            pos.insert(pos.end(), {p->x, p->y, p->z});
    const int acc = addAccessor(pos.data(), pos.size() * 4, 5126, "VEC3", 3 * tris.size(), 34962);
    nlohmann::json prim = {{"attributes", {{"POSITION", acc}}}};
    if (material >= 0)
        prim["material"] = material;
    doc_["meshes"].push_back({{"name", name}, {"primitives", {prim}}});
    const int node = static_cast<int>(doc_["nodes"].size());
    doc_["nodes"].push_back({{"name", name}, {"mesh", doc_["meshes"].size() - 1}});
    doc_["scenes"][0]["nodes"].push_back(node);
    return node;
}

int GltfWriter::addIndexedMeshNode(const std::string& name, const std::vector<glm::vec3>& positions,
                                   const std::vector<std::uint32_t>& indices)
{
    std::vector<float> pos;
    for (const auto& p : positions)
        pos.insert(pos.end(), {p.x, p.y, p.z});
    const int pa = addAccessor(pos.data(), pos.size() * 4, 5126, "VEC3", positions.size(), 34962);
    const int ia = addAccessor(indices.data(), indices.size() * 4, 5125, "SCALAR", indices.size(), 34963);
    doc_["meshes"].push_back(
        {{"name", name}, {"primitives", {{{"attributes", {{"POSITION", pa}}}, {"indices", ia}}}}});
    const int node = static_cast<int>(doc_["nodes"].size());
    doc_["nodes"].push_back({{"name", name}, {"mesh", doc_["meshes"].size() - 1}});
    doc_["scenes"][0]["nodes"].push_back(node);
    return node;
}

std::string GltfWriter::write(const std::string& path)
{
    doc_["buffers"] = nlohmann::json::array(
        {{{"byteLength", bin_.size()},
          {"uri", "data:application/octet-stream;base64," + base64(bin_)}}});
    std::ofstream f(path);
    f << doc_.dump(1);
    return path;
}

std::string GltfWriter::writeExternal(const std::string& path, const std::string& binName,
                                      const std::string& uri)
{
    namespace fs = std::filesystem;
    const fs::path bin = fs::path(path).parent_path() / binName;
    fs::create_directories(bin.parent_path());
    std::ofstream(bin, std::ios::binary).write(reinterpret_cast<const char*>(bin_.data()),
                                               static_cast<std::streamsize>(bin_.size()));
    doc_["buffers"] = nlohmann::json::array(
        {{{"byteLength", bin_.size()}, {"uri", uri.empty() ? binName : uri}}});
    std::ofstream(path) << doc_.dump(1);
    return path;
}

std::vector<unsigned char> GltfWriter::glbBytes()
{
    doc_["buffers"] = nlohmann::json::array({{{"byteLength", bin_.size()}}});
    std::string json = doc_.dump();
    while (json.size() % 4)
        json += ' ';
    std::vector<unsigned char> bin = bin_;
    while (bin.size() % 4)
        bin.push_back(0);
    std::vector<unsigned char> out;
    auto u32 = [&out](std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
    for (char c : std::string("glTF"))
        out.push_back(static_cast<unsigned char>(c));
    u32(2);
    u32(static_cast<std::uint32_t>(total));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    if (!bin.empty()) {
        u32(static_cast<std::uint32_t>(bin.size()));
        u32(0x004E4942u);  // "BIN\0"
        out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
}

std::string GltfWriter::writeGlb(const std::string& path)
{
    const std::vector<unsigned char> bytes = glbBytes();
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
    return path;
}

std::string tempDir(const std::string& tag)
{
    namespace fs = std::filesystem;
    const fs::path p = fs::temp_directory_path() /
                       ("fenestra-test-" + tag + "-" + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p.string();
}

} }  // namespace fen::test
