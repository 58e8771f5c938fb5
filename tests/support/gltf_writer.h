// gltf_writer.h — builds small glTF 2.0 files for the tests: one buffer, embedded as base64
// (write), in a .bin file beside the .gltf (writeExternal) or in a .glb's BIN chunk (writeGlb).
//
// Meshes are given as triangle lists in the node's local frame; `doc` is the JSON and `bin` the
// buffer's bytes, open for the test to edit (add lights, cameras, extras, or break it on purpose)
// before writing. Each write sets buffers[0] afresh from `bin`.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry.h"

namespace fen { namespace test {

class GltfWriter {
public:
    GltfWriter();
    // Adds a mesh with one primitive (non-indexed) and a node for it; returns the node index.
    int addMeshNode(const std::string& name, const std::vector<Triangle>& tris, int material = -1);
    // Indexed variant: positions and 32-bit indices.
    int addIndexedMeshNode(const std::string& name, const std::vector<glm::vec3>& positions,
                           const std::vector<std::uint32_t>& indices);
    nlohmann::json& doc() { return doc_; }
    nlohmann::json& node(int i) { return doc_["nodes"][static_cast<std::size_t>(i)]; }
    std::vector<unsigned char>& bin() { return bin_; }
    // Finalises the buffer and writes the file; returns its path.
    std::string write(const std::string& path);
    // The buffer goes to `binName` (a path relative to the .gltf's folder, written there; the uri
    // is `uri` when given, else binName).
    std::string writeExternal(const std::string& path, const std::string& binName,
                              const std::string& uri = "");
    // Binary glTF: 12-byte header, JSON chunk (space-padded), BIN chunk (zero-padded) when the
    // buffer is not empty.
    std::string writeGlb(const std::string& path);
    // The .glb bytes writeGlb would write.
    std::vector<unsigned char> glbBytes();

private:
    int addAccessor(const void* data, std::size_t bytes, int componentType, const char* type,
                    std::size_t count, int target);
    nlohmann::json doc_;
    std::vector<unsigned char> bin_;
};

// A fresh empty directory for one test's files.
std::string tempDir(const std::string& tag);

} }  // namespace fen::test
