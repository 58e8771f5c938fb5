// gltf_load_test.cpp — glTF geometry: transforms applied, indexed and not; every malformed input
// is one fen::Error naming the file and the node/accessor at fault.
#include <gtest/gtest.h>

#include <fstream>

#include "scene/gltf_load.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

const std::vector<Triangle> kTri = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};

std::string errorOf(const std::string& path)
{
    try {
        loadGltf(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(GltfLoad, TransformsAreApplied)
{
    const std::string dir = test::tempDir("gltf-xf");
    test::GltfWriter w;
    const int a = w.addMeshNode("moved", kTri);
    w.node(a)["translation"] = {10, 0, 0};
    w.node(a)["scale"] = {2, 2, 2};
    w.node(a)["rotation"] = {0, 0, 0.7071067811865476, 0.7071067811865476};  // 90 deg about z
    const int b = w.addMeshNode("matrix", kTri);
    w.node(b)["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1};
    // Nested: child of b inherits its translation.
    const int c = w.addMeshNode("child", kTri);
    w.doc()["scenes"][0]["nodes"] = {a, b};
    w.node(b)["children"] = {c};
    w.node(c)["translation"] = {0, 3, 0};
    const Scene s = loadGltf(w.write(dir + "/xf.gltf"));
    ASSERT_EQ(s.triangles.size(), 3u);
    // node a: (1,0,0) -> scale 2 -> rotate to (0,2,0) -> translate (10,2,0)
    EXPECT_NEAR(s.triangles[0].p1.x, 10.0f, 1e-5f);
    EXPECT_NEAR(s.triangles[0].p1.y, 2.0f, 1e-5f);
    EXPECT_NEAR(s.triangles[1].p1.z, -5.0f, 1e-6f);
    EXPECT_NEAR(s.triangles[2].p2.y, 4.0f, 1e-6f);
    EXPECT_NEAR(s.triangles[2].p2.z, -5.0f, 1e-6f);
    EXPECT_EQ(s.triangleNode[2], static_cast<std::uint32_t>(c));
    EXPECT_EQ(s.nodeNames[static_cast<std::size_t>(c)], "child");
}

TEST(GltfLoad, IndexedPrimitive)
{
    const std::string dir = test::tempDir("gltf-idx");
    test::GltfWriter w;
    w.addIndexedMeshNode("quad", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3});
    const Scene s = loadGltf(w.write(dir + "/q.gltf"));
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_EQ(s.triangles[1].p2, glm::vec3(0, 1, 0));
}

TEST(GltfLoad, MissingFile)
{
    const std::string e = errorOf("/nonexistent/dir/scene.gltf");
    EXPECT_NE(e.find("/nonexistent/dir/scene.gltf: cannot open file"), std::string::npos) << e;
}

TEST(GltfLoad, MalformedJson)
{
    const std::string path = test::tempDir("gltf-bad") + "/bad.gltf";
    std::ofstream(path) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {";
    const std::string e = errorOf(path);
    EXPECT_NE(e.find(path + ": not a valid glTF file"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "error must be one line: " << e;
}

TEST(GltfLoad, MissingBufferFile)
{
    const std::string dir = test::tempDir("gltf-buf");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    const std::string path = w.write(dir + "/m.gltf");
    nlohmann::json j;
    std::ifstream(path) >> j;
    j["buffers"][0]["uri"] = "missing.bin";
    std::ofstream(path) << j.dump();
    const std::string e = errorOf(path);
    EXPECT_NE(e.find(path), std::string::npos) << e;
    EXPECT_NE(e.find("missing.bin"), std::string::npos) << e;
}

TEST(GltfLoad, AccessorOutOfBounds)
{
    const std::string dir = test::tempDir("gltf-oob");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    w.doc()["accessors"][0]["count"] = 300;
    w.doc()["accessors"][0].erase("min");
    w.doc()["accessors"][0].erase("max");
    const std::string e = errorOf(w.write(dir + "/o.gltf"));
    EXPECT_NE(e.find("node 0 'tri'"), std::string::npos) << e;
    EXPECT_NE(e.find("accessor 0"), std::string::npos) << e;
}

TEST(GltfLoad, NonTrianglePrimitive)
{
    const std::string dir = test::tempDir("gltf-mode");
    test::GltfWriter w;
    w.addMeshNode("lines", kTri);
    w.doc()["meshes"][0]["primitives"][0]["mode"] = 1;
    const std::string e = errorOf(w.write(dir + "/l.gltf"));
    EXPECT_NE(e.find("node 0 'lines'"), std::string::npos) << e;
    EXPECT_NE(e.find("mode 1"), std::string::npos) << e;
}

TEST(GltfLoad, IndexOutOfRange)
{
    const std::string dir = test::tempDir("gltf-ix");
    test::GltfWriter w;
    w.addIndexedMeshNode("quad", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {0, 1, 7});
    const std::string e = errorOf(w.write(dir + "/i.gltf"));
    // By position: the value is the buffer's content, which no message quotes.
    EXPECT_NE(e.find("index at position 2 exceeds the 3 vertices"), std::string::npos) << e;
    EXPECT_EQ(e.find(" 7"), std::string::npos) << e;
    EXPECT_NE(e.find("node 0 'quad'"), std::string::npos) << e;
}

TEST(GltfLoad, NonFiniteVertex)
{
    // Finite in the file, beyond float range once scaled by the node.
    const std::string dir = test::tempDir("gltf-nan");
    test::GltfWriter w;
    const int n = w.addMeshNode("tri", kTri);
    w.node(n)["scale"] = {1e39, 1e39, 1e39};
    const std::string e = errorOf(w.write(dir + "/n.gltf"));
    EXPECT_NE(e.find("node 0 'tri'"), std::string::npos) << e;
    EXPECT_NE(e.find("not finite"), std::string::npos) << e;
}


// Extensions a file uses and fenestra does not read are listed in one warning (Blender writes
// KHR_materials_specular, KHR_texture_transform and others); one a file requires is an error.
TEST(GltfLoad, UnsupportedExtensionsAreOneWarningOrAnError)
{
    const std::string dir = test::tempDir("gltf-extensions");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    w.doc()["extensionsUsed"] = {"KHR_materials_transmission", "KHR_texture_transform", "KHR_materials_specular"};
    const Scene s = loadGltf(w.write(dir + "/used.gltf"));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("extensions not supported, ignored: KHR_texture_transform, KHR_materials_specular"),
              std::string::npos) << s.warnings[0];
    w.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    w.doc()["extensionsUsed"].push_back("KHR_draco_mesh_compression");
    const std::string e = errorOf(w.write(dir + "/required.gltf"));
    EXPECT_NE(e.find("required.gltf: requires extension KHR_draco_mesh_compression"), std::string::npos) << e;
}

}  // namespace
}  // namespace fen
