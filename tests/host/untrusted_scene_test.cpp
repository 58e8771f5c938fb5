// untrusted_scene_test.cpp — a scene from someone else reads only what is its own (README,
// "Untrusted scenes"): URIs stay inside the scene's folder, sizes and offsets cannot wrap, GLB
// framing is checked, nesting is bounded, numbers are not squeezed, shapes and types are checked,
// and far geometry is reported. Each case is a regression test for a problem found by fuzzing:
// every bad file gives one fen::Error naming the file and the glTF path, never a crash, and no
// message quotes another file's bytes or size.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "scene/gltf_load.h"
#include "scene/scene_files.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

namespace fs = std::filesystem;

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

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The message without the test's folder (whose name holds a process id, digits that could match).
std::string withoutDir(std::string e, const std::string& dir)
{
    for (std::size_t at; (at = e.find(dir)) != std::string::npos;)
        e.erase(at, dir.size());
    return e;
}

// A file of `size` bytes outside the scene's folder, standing for someone's private data.
std::string secretFile(const std::string& dir, std::size_t size)
{
    const std::string path = dir + "/secret.bin";
    std::ofstream f(path, std::ios::binary);
    for (std::size_t i = 0; i < size; ++i)
        f.put(static_cast<char>('a' + i % 26));
    return path;
}

// dir/scene/s.gltf, one triangle in an external buffer whose uri is then replaced by `uri`.
std::string sceneWithBufferUri(const std::string& dir, const std::string& uri)
{
    fs::create_directories(dir + "/scene");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    const std::string path = w.writeExternal(dir + "/scene/s.gltf", "tri.bin");
    nlohmann::json j;
    std::ifstream(path) >> j;
    j["buffers"][0]["uri"] = uri;
    std::ofstream(path) << j.dump();
    return path;
}

// --- 1. URIs stay inside the scene's folder ---------------------------------------------------

TEST(UntrustedScene, BufferUriLeavingTheFolderIsRefused)
{
    const std::string dir = test::tempDir("untrusted-dotdot");
    secretFile(dir, 1221);
    for (const std::string uri : {"../secret.bin", "..%2Fsecret.bin", "%2e%2e/secret.bin",
                                  "sub/../../secret.bin", "./../secret.bin"}) {
        const std::string e = errorOf(sceneWithBufferUri(dir, uri));
        EXPECT_TRUE(contains(e, "s.gltf: buffers[0].uri")) << uri << ": " << e;
        EXPECT_TRUE(contains(e, "outside the scene's folder")) << uri << ": " << e;
        EXPECT_FALSE(contains(withoutDir(e, dir), "1221")) << "reveals the file's size: " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
}

TEST(UntrustedScene, AbsoluteAndFileUrisAreRefused)
{
    const std::string dir = test::tempDir("untrusted-abs");
    const std::string secret = secretFile(dir, 36);  // exactly the triangle's byteLength
    for (const std::string& uri : std::vector<std::string>{secret, "file://" + secret, "file:" + secret, "FILE://" + secret,
                                  "http://example.com/tri.bin", "tri.bin%00/../../secret.bin"}) {
        const std::string e = errorOf(sceneWithBufferUri(dir, uri));
        EXPECT_TRUE(contains(e, "s.gltf: buffers[0].uri")) << uri << ": " << e;
        EXPECT_TRUE(contains(e, "refused")) << uri << ": " << e;
    }
}

TEST(UntrustedScene, SymlinkOutOfTheFolderIsRefused)
{
    const std::string dir = test::tempDir("untrusted-symlink");
    const std::string secret = secretFile(dir, 36);
    const std::string path = sceneWithBufferUri(dir, "link.bin");
    fs::create_symlink(secret, dir + "/scene/link.bin");
    const std::string e = errorOf(path);
    EXPECT_TRUE(contains(e, "s.gltf: buffers[0].uri")) << e;
    EXPECT_TRUE(contains(e, "outside the scene's folder")) << e;
    // A link that stays inside is fine.
    const std::string inside = sceneWithBufferUri(dir, "inner.bin");
    fs::create_symlink("tri.bin", dir + "/scene/inner.bin");
    EXPECT_EQ(loadGltf(inside).triangles.size(), 1u);
}

TEST(UntrustedScene, UrisInsideTheFolderLoad)
{
    const std::string dir = test::tempDir("untrusted-inside");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    EXPECT_EQ(loadGltf(w.writeExternal(dir + "/a.gltf", "meshes/tri.bin")).triangles.size(), 1u);
    EXPECT_EQ(loadGltf(w.writeExternal(dir + "/b.gltf", "my mesh.bin", "my%20mesh.bin")).triangles.size(), 1u);
    EXPECT_EQ(loadGltf(w.writeExternal(dir + "/c.gltf", "x/tri.bin", "x/../x/./tri.bin")).triangles.size(), 1u);
    EXPECT_EQ(loadGltf(w.write(dir + "/d.gltf")).triangles.size(), 1u);  // data: URI
}

TEST(UntrustedScene, ImageUriLeavingTheFolderIsRefused)
{
    const std::string dir = test::tempDir("untrusted-image");
    secretFile(dir, 100);
    fs::create_directories(dir + "/scene");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    w.doc()["images"] = {{{"uri", "../secret.bin"}}};
    const std::string e = errorOf(w.write(dir + "/scene/s.gltf"));
    EXPECT_TRUE(contains(e, "s.gltf: images[0].uri")) << e;
    EXPECT_TRUE(contains(e, "outside the scene's folder")) << e;
}

TEST(UntrustedScene, WorkingDirectoryIsNotSearched)
{
    // tinygltf looks for a file in the scene's folder, then in the working directory.
    const std::string dir = test::tempDir("untrusted-cwd");
    fs::create_directories(dir + "/cwd");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    w.writeExternal(dir + "/cwd/unused.gltf", "elsewhere.bin");
    const std::string path = sceneWithBufferUri(dir, "elsewhere.bin");
    const fs::path before = fs::current_path();
    fs::current_path(dir + "/cwd");
    const std::string e = errorOf(path);
    fs::current_path(before);
    EXPECT_TRUE(contains(e, "s.gltf: buffers[0].uri: 'elsewhere.bin' not found in the scene's folder")) << e;
}

TEST(UntrustedScene, OnlyRegularFilesAreRead)
{
    const std::string dir = test::tempDir("untrusted-special");
    const std::string path = sceneWithBufferUri(dir, "sub");
    fs::create_directories(dir + "/scene/sub");
    std::string e = errorOf(path);
    EXPECT_TRUE(contains(e, "s.gltf: buffers[0].uri: 'sub' is not a regular file")) << e;
    // A FIFO would block the reader forever.
    const std::string fifo = sceneWithBufferUri(dir, "pipe");
    ASSERT_EQ(::mkfifo((dir + "/scene/pipe").c_str(), 0600), 0);
    e = errorOf(fifo);
    EXPECT_TRUE(contains(e, "s.gltf: buffers[0].uri: 'pipe' is not a regular file")) << e;
}

TEST(UntrustedScene, NoMessageQuotesAFilesSizeOrBytes)
{
    const std::string dir = test::tempDir("untrusted-size");
    // A buffer file inside the folder whose size is not its byteLength: the message names the
    // buffer and its byteLength, not the file's size.
    const std::string path = sceneWithBufferUri(dir, "big.bin");
    secretFile(dir + "/scene", 1221);
    fs::rename(dir + "/scene/secret.bin", dir + "/scene/big.bin");
    std::string e = errorOf(path);
    EXPECT_TRUE(contains(e, "s.gltf: buffers[0]")) << e;
    EXPECT_TRUE(contains(e, "byteLength 36")) << e;
    EXPECT_FALSE(contains(withoutDir(e, dir), "1221")) << e;
    // Indices read from a buffer: an out-of-range one is reported by position, not by value
    // (the value is the file's content).
    test::GltfWriter w;
    w.addIndexedMeshNode("quad", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {0, 1, 1936876918u});
    e = errorOf(w.write(dir + "/i.gltf"));
    EXPECT_TRUE(contains(e, "i.gltf: node 0 'quad'")) << e;
    EXPECT_TRUE(contains(e, "index at position 2 exceeds")) << e;
    EXPECT_FALSE(contains(withoutDir(e, dir), "1936876918")) << e;
}

// --- 2. Offsets, lengths and counts cannot wrap past 2^64 ---------------------------------------

TEST(UntrustedScene, OffsetsNear2To64AreRefused)
{
    const std::string dir = test::tempDir("untrusted-wrap");
    const std::uint64_t top = ~std::uint64_t(0);
    auto variant = [&](const std::string& name, auto edit) {
        test::GltfWriter w;
        w.addIndexedMeshNode("quad", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3});
        edit(w.doc());
        return errorOf(w.write(dir + "/" + name + ".gltf"));
    };
    // bufferView 0: 48 bytes of positions at 0; bufferView 1: 24 bytes of indices at 48.
    std::string e = variant("view", [&](nlohmann::json& d) { d["bufferViews"][0]["byteOffset"] = top - 7; });
    EXPECT_TRUE(contains(e, "view.gltf: node 0 'quad', mesh 0, primitive 0, accessor 0: bufferView 0")) << e;
    e = variant("viewlen", [&](nlohmann::json& d) { d["bufferViews"][1]["byteLength"] = top - 40; });
    EXPECT_TRUE(contains(e, "viewlen.gltf: node 0 'quad', mesh 0, primitive 0, accessor 1: bufferView 1")) << e;
    e = variant("acc", [&](nlohmann::json& d) {
        d["accessors"][0]["byteOffset"] = top - 3;
        d["accessors"][0].erase("min");
        d["accessors"][0].erase("max");
    });
    EXPECT_TRUE(contains(e, "acc.gltf: node 0 'quad', mesh 0, primitive 0, accessor 0")) << e;
    EXPECT_TRUE(contains(e, "do not fit in bufferView 0")) << e;
    // 12 * 2^62 wraps to 0: the elements "fit", then 2^62 vertices are allocated.
    e = variant("count", [&](nlohmann::json& d) {
        d["accessors"][0]["count"] = (std::uint64_t(1) << 62) + 1;
        d["accessors"][0].erase("min");
        d["accessors"][0].erase("max");
    });
    EXPECT_TRUE(contains(e, "count.gltf: node 0 'quad', mesh 0, primitive 0, accessor 0")) << e;
    EXPECT_TRUE(contains(e, "do not fit in bufferView 0")) << e;
    e = variant("indices", [&](nlohmann::json& d) { d["accessors"][1]["count"] = (std::uint64_t(1) << 62) + 1; });
    EXPECT_TRUE(contains(e, "indices.gltf: node 0 'quad', mesh 0, primitive 0, accessor 1")) << e;
    EXPECT_TRUE(contains(e, "do not fit in bufferView 1")) << e;
}

// --- 4. Depth: node chains, DAGs, JSON nesting ------------------------------------------------

// Replaces the JSON string "PLACEHOLDER" in a written file by `raw` (which nlohmann could not
// dump: its serialiser recurses).
std::string spliceRaw(const std::string& path, const std::string& raw)
{
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find("\"PLACEHOLDER\"");
    EXPECT_NE(at, std::string::npos);
    text.replace(at, 13, raw);
    std::ofstream(path) << text;
    return path;
}

std::string nested(int depth, const std::string& open, const std::string& inner, const std::string& close)
{
    std::string s;
    for (int i = 0; i < depth; ++i)
        s += open;
    s += inner;
    for (int i = 0; i < depth; ++i)
        s += close;
    return s;
}

TEST(UntrustedScene, LongNodeChainLoads)
{
    // A legal hierarchy 10,000 deep: the walk must not recurse (6,500 overflowed the stack).
    const std::string dir = test::tempDir("untrusted-chain");
    test::GltfWriter w;
    w.addMeshNode("leaf", kTri);
    const int n = 10000;
    for (int i = 1; i <= n; ++i)
        w.doc()["nodes"].push_back({{"children", {i - 1}}, {"translation", {0.001, 0, 0}}});
    w.doc()["scenes"][0]["nodes"] = {n};
    const Scene s = loadGltf(w.write(dir + "/chain.gltf"));
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_NEAR(s.triangles[0].p1.x, 11.0f, 1e-4f);
    EXPECT_EQ(s.nodeParent[0], 1);
}

TEST(UntrustedScene, NodeWithTwoParentsIsRefused)
{
    const std::string dir = test::tempDir("untrusted-dag");
    test::GltfWriter w;
    w.addMeshNode("leaf", kTri);
    w.doc()["nodes"].push_back({{"name", "a"}, {"children", {0}}});
    w.doc()["nodes"].push_back({{"name", "b"}, {"children", {0}}});
    w.doc()["scenes"][0]["nodes"] = {1, 2};
    std::string e = errorOf(w.write(dir + "/two.gltf"));
    EXPECT_TRUE(contains(e, "two.gltf: nodes[0] 'leaf' is a child of both nodes[1] and nodes[2]")) << e;
    w.doc()["nodes"][1]["children"] = {0, 0};
    w.doc()["scenes"][0]["nodes"] = {1};
    w.doc()["nodes"][2].erase("children");
    e = errorOf(w.write(dir + "/twice.gltf"));
    EXPECT_TRUE(contains(e, "twice.gltf: nodes[1].children[1]: nodes[0] 'leaf' is listed twice")) << e;
}

TEST(UntrustedScene, DoublingDagIsRefusedAtOnce)
{
    // 30 levels, each node listing the next twice: 2^30 paths to the leaf from a 6 KB file.
    const std::string dir = test::tempDir("untrusted-dag30");
    test::GltfWriter w;
    w.addMeshNode("leaf", kTri);
    for (int i = 1; i <= 30; ++i)
        w.doc()["nodes"].push_back({{"children", {i - 1, i - 1}}});
    w.doc()["scenes"][0]["nodes"] = {30};
    const std::string e = errorOf(w.write(dir + "/dag.gltf"));
    EXPECT_TRUE(contains(e, "dag.gltf: nodes[1].children[1]: nodes[0] 'leaf' is listed twice")) << e;
}

TEST(UntrustedScene, CyclesAndNonRootSceneNodesAreRefused)
{
    const std::string dir = test::tempDir("untrusted-cycle");
    test::GltfWriter w;
    w.addMeshNode("leaf", kTri);
    w.doc()["nodes"].push_back({{"name", "a"}, {"children", {2}}});
    w.doc()["nodes"].push_back({{"name", "b"}, {"children", {1}}});
    std::string e = errorOf(w.write(dir + "/cycle.gltf"));  // the cycle is outside the scene
    EXPECT_TRUE(contains(e, "cycle.gltf: nodes[1] 'a' is its own ancestor")) << e;
    w.doc()["nodes"][2]["children"] = {2};
    w.doc()["nodes"][1].erase("children");
    e = errorOf(w.write(dir + "/self.gltf"));
    EXPECT_TRUE(contains(e, "self.gltf: nodes[2].children[0]: nodes[2] 'b' is its own child")) << e;
    w.doc()["nodes"][2]["children"] = {0};
    w.doc()["scenes"][0]["nodes"] = {0, 2};
    e = errorOf(w.write(dir + "/root.gltf"));
    EXPECT_TRUE(contains(e, "root.gltf: scenes[0].nodes[0]: nodes[0] 'leaf' is a child of nodes[2]")) << e;
    w.doc()["scenes"][0]["nodes"] = {2, 2};
    e = errorOf(w.write(dir + "/dup.gltf"));
    EXPECT_TRUE(contains(e, "dup.gltf: scenes[0].nodes[1]: nodes[2] 'b' is listed twice")) << e;
}

TEST(UntrustedScene, DeepJsonIsRefusedBeforeParsing)
{
    const std::string dir = test::tempDir("untrusted-deep");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    w.node(0)["extras"] = "PLACEHOLDER";
    // 20,000 nested objects in a node's extras overflowed the stack (tinygltf recurses).
    std::string e = errorOf(spliceRaw(w.write(dir + "/deep.gltf"), nested(20000, "{\"a\":", "1", "}")));
    EXPECT_TRUE(contains(e, "deep.gltf: JSON nested deeper than 64 levels")) << e;
    e = errorOf(spliceRaw(w.write(dir + "/arrays.gltf"), nested(100000, "[", "", "]")));
    EXPECT_TRUE(contains(e, "arrays.gltf: JSON nested deeper than 64 levels")) << e;
    // The limit is exact, and brackets inside strings (escaped quotes too) do not count:
    // root { asset { extras: n arrays } } is 2 + n levels.
    w.node(0).erase("extras");
    w.doc()["asset"]["extras"] = "PLACEHOLDER";
    const std::string text = "\"\\\"[[[[{{{{\"";
    EXPECT_EQ(loadGltf(spliceRaw(w.write(dir + "/64.gltf"), nested(62, "[", text, "]"))).triangles.size(), 1u);
    e = errorOf(spliceRaw(w.write(dir + "/65.gltf"), nested(63, "[", text, "]")));
    EXPECT_TRUE(contains(e, "65.gltf: JSON nested deeper than 64 levels")) << e;
}

// --- 5. Integers are read wide and range-checked -------------------------------------------------

const std::uint64_t k2To32 = std::uint64_t(1) << 32;

// One plate, a directional sun and a uniform sky: every key of fenestra's extras has a place.
test::GltfWriter litScene()
{
    test::GltfWriter w;
    w.addMeshNode("plate", kTri);
    w.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "directional"}, {"intensity", 1000}}};
    w.doc()["nodes"].push_back({{"name", "sun"}, {"rotation", {-0.7071067811865476, 0, 0, 0.7071067811865476}},
                               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    w.doc()["scenes"][0]["nodes"].push_back(1);
    w.doc()["scenes"][0]["extras"] = {{"sky", {{"type", "uniform"}, {"luminance", 100}}}};
    return w;
}

TEST(UntrustedScene, WideIntegersInExtrasAreReadWide)
{
    const std::string dir = test::tempDir("untrusted-wide");
    test::GltfWriter w = litScene();
    w.doc()["scenes"][0]["extras"]["sky"]["luminance"] = k2To32;  // was read as 0: no sky
    const Scene s = loadGltf(w.write(dir + "/lum.gltf"));
    EXPECT_EQ(s.sky.luminance_cd_m2, 4294967296.0);

    w = litScene();
    w.doc()["scenes"][0]["extras"]["sky"] = {{"type", "cie"}, {"cie_type", k2To32 + 12}, {"zenith_luminance", 1},
                                             {"sun_altitude_deg", 45}, {"sun_azimuth_deg", 0}};
    std::string e = errorOf(w.write(dir + "/cie.gltf"));  // passed as type 12
    EXPECT_TRUE(contains(e, "cie.gltf: scenes[0].extras.sky.cie_type: 4294967308 is not a CIE sky type")) << e;

    w = litScene();
    w.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["extras"] = {{"angular_radius_deg", k2To32}};
    e = errorOf(w.write(dir + "/radius.gltf"));  // passed as 0
    EXPECT_TRUE(contains(e, "radius.gltf: KHR_lights_punctual.lights[0].extras.angular_radius_deg")) << e;

    w = litScene();
    w.node(1)["extensions"]["KHR_lights_punctual"]["light"] = k2To32;  // aliased light 0
    e = errorOf(w.write(dir + "/light.gltf"));
    EXPECT_TRUE(contains(e, "light.gltf: node 1 'sun'.extensions.KHR_lights_punctual.light")) << e;
    EXPECT_TRUE(contains(e, "4294967296")) << e;
}

TEST(UntrustedScene, IndicesBeyond32BitsAreRefused)
{
    const std::string dir = test::tempDir("untrusted-index");
    int n = 0;
    auto expectRefused = [&](const std::string& key, auto edit) {
        test::GltfWriter w;
        w.addIndexedMeshNode("quad", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {0, 1, 2});
        w.doc()["materials"] = {{{"name", "m"}}};
        w.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
        edit(w.doc());
        const std::string name = "i" + std::to_string(n++) + ".gltf";
        const std::string e = errorOf(w.write(dir + "/" + name));
        EXPECT_TRUE(contains(e, name + ": " + key + ": ")) << key << ": " << e;
        EXPECT_TRUE(contains(e, "is not an index")) << key << ": " << e;
    };
    expectRefused("nodes[0].mesh", [](nlohmann::json& d) { d["nodes"][0]["mesh"] = k2To32; });
    expectRefused("nodes[0].mesh", [](nlohmann::json& d) { d["nodes"][0]["mesh"] = -1; });
    expectRefused("nodes[0].camera", [](nlohmann::json& d) { d["nodes"][0]["camera"] = k2To32; });
    expectRefused("nodes[0].children[0]", [](nlohmann::json& d) { d["nodes"][0]["children"] = {k2To32}; });
    expectRefused("scenes[0].nodes[0]", [](nlohmann::json& d) { d["scenes"][0]["nodes"] = {k2To32}; });
    expectRefused("scene", [](nlohmann::json& d) { d["scene"] = k2To32; });
    expectRefused("meshes[0].primitives[0].attributes.POSITION",
                  [](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = k2To32; });
    expectRefused("meshes[0].primitives[0].indices",
                  [](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["indices"] = k2To32 + 1; });
    expectRefused("meshes[0].primitives[0].material",
                  [](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["material"] = k2To32; });
    expectRefused("accessors[0].bufferView", [](nlohmann::json& d) { d["accessors"][0]["bufferView"] = k2To32; });
    expectRefused("bufferViews[1].buffer", [](nlohmann::json& d) { d["bufferViews"][1]["buffer"] = k2To32; });
    // What fenestra does not use must still name what exists: textures, skins, animations, morphs.
    expectRefused("materials[0].pbrMetallicRoughness.baseColorTexture.index", [](nlohmann::json& d) {
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 0;  // no textures at all
    });
    expectRefused("materials[0].normalTexture.index",
                  [](nlohmann::json& d) { d["materials"][0]["normalTexture"]["index"] = k2To32; });
    expectRefused("textures[0].source", [](nlohmann::json& d) { d["textures"] = {{{"source", 3}}}; });
    expectRefused("textures[0].sampler", [](nlohmann::json& d) { d["textures"] = {{{"sampler", 0}}}; });
    expectRefused("nodes[0].skin", [](nlohmann::json& d) { d["nodes"][0]["skin"] = 0; });
    expectRefused("skins[0].joints[0]", [](nlohmann::json& d) { d["skins"] = {{{"joints", {7}}}}; });
    expectRefused("animations[0].samplers[0].input", [](nlohmann::json& d) {
        d["animations"] = {{{"samplers", {{{"input", 99}, {"output", 0}}}}, {"channels", nlohmann::json::array()}}};
    });
    expectRefused("animations[0].channels[0].target.node", [](nlohmann::json& d) {
        d["animations"] = {{{"samplers", {{{"input", 0}, {"output", 0}}}},
                            {"channels", {{{"sampler", 0}, {"target", {{"node", k2To32}, {"path", "rotation"}}}}}}}};
    });
    expectRefused("meshes[0].primitives[0].targets[0].POSITION",
                  [](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 42}}}; });
}

TEST(UntrustedScene, DegenerateCamerasAndEmptyMeshesAreErrors)
{
    const std::string dir = test::tempDir("untrusted-degenerate");
    auto scene = [&](auto edit) {
        test::GltfWriter w;
        w.addMeshNode("plate", kTri);
        w.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
        w.doc()["nodes"].push_back({{"name", "cam"}, {"camera", 0}, {"translation", {0, 0, 2}}});
        w.doc()["scenes"][0]["nodes"].push_back(1);
        edit(w.doc());
        return w;
    };
    // Both used to render: black (a pixel's solid angle underflowed), or 640 x 1.
    std::string e = errorOf(scene([](nlohmann::json& d) { d["cameras"][0]["perspective"]["yfov"] = 1e-7; })
                                .write(dir + "/narrow.gltf"));
    EXPECT_TRUE(contains(e, "narrow.gltf: node 1 'cam': camera 0: yfov 1e-07 rad must be in")) << e;
    e = errorOf(scene([](nlohmann::json& d) { d["cameras"][0]["perspective"]["aspectRatio"] = 1000.0; })
                    .write(dir + "/wide.gltf"));
    EXPECT_TRUE(contains(e, "wide.gltf: node 1 'cam': camera 0: aspectRatio 1000 must be in [1/16, 16]")) << e;
    // The extremes allowed load; a view narrower than a degree is warned about (light paths
    // reach it rarely: at 0.057 degrees, 4M paths in scenes/room.gltf left the image black).
    const Scene ok = loadGltf(scene([](nlohmann::json& d) {
                                  d["cameras"][0]["perspective"]["yfov"] = 0.001 * M_PI / 180.0 * 1.001;
                                  d["cameras"][0]["perspective"]["aspectRatio"] = 16.0;
                              }).write(dir + "/ok.gltf"));
    ASSERT_EQ(ok.warnings.size(), 1u);
    EXPECT_TRUE(contains(ok.warnings[0], "sees only 0.001")) << ok.warnings[0];
    // A mesh without primitives used to vanish without a word.
    e = errorOf(scene([](nlohmann::json& d) { d["meshes"][0]["primitives"] = nlohmann::json::array(); })
                    .write(dir + "/empty.gltf"));
    EXPECT_TRUE(contains(e, "empty.gltf: meshes[0].primitives: is empty")) << e;
}

// --- 6. Types and shapes ----------------------------------------------------------------------

// litScene plus a camera node (nodes[2] 'cam') and a material on the plate.
test::GltfWriter fullScene()
{
    test::GltfWriter w = litScene();
    w.doc()["meshes"][0]["primitives"][0]["material"] = 0;
    w.doc()["materials"] = {{{"name", "glass"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}},
                             {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}}}}}};
    w.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    w.doc()["nodes"].push_back({{"name", "cam"}, {"camera", 0}, {"translation", {0, 1, 3}}});
    w.doc()["scenes"][0]["nodes"].push_back(2);
    return w;
}

TEST(UntrustedScene, WrongShapesAndTypesAreErrors)
{
    const std::string dir = test::tempDir("untrusted-shape");
    {
        test::GltfWriter w = fullScene();
        const Scene s = loadGltf(w.write(dir + "/ok.gltf"));
        ASSERT_EQ(s.cameras.size(), 1u);
        EXPECT_TRUE(s.materials[0].glass);
    }
    int n = 0;
    auto expectError = [&](const std::string& fragment, auto edit) {
        test::GltfWriter w = fullScene();
        edit(w.doc());
        const std::string name = "s" + std::to_string(n++) + ".gltf";
        const std::string e = errorOf(w.write(dir + "/" + name));
        EXPECT_TRUE(contains(e, name + ": " + fragment)) << fragment << " -- " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    };
    // Each of these loaded, silently wrong: a white material, an ignored translation, a dropped
    // mesh, opaque glass, no sky, an unknown key unnoticed.
    expectError("materials[0].pbrMetallicRoughness.baseColorFactor: must be an array of 4 numbers",
                [](auto& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.5, 0.5}; });
    expectError("nodes[2].translation: must be an array of 3 numbers",
                [](auto& d) { d["nodes"][2]["translation"] = {0, 1}; });
    expectError("nodes[2].translation[1]: must be a number, not \"1\"",
                [](auto& d) { d["nodes"][2]["translation"] = {0, "1", 3}; });
    expectError("nodes[0].mesh: \"0\" is not an index of meshes", [](auto& d) { d["nodes"][0]["mesh"] = "0"; });
    expectError("materials[0] 'glass'.extensions.KHR_materials_transmission: must be a JSON object",
                [](auto& d) { d["materials"][0]["extensions"]["KHR_materials_transmission"] = {0.9}; });
    expectError("scenes[0].extras.sky.type: missing", [](auto& d) { d["scenes"][0]["extras"]["sky"] = nlohmann::json::object(); });
    expectError("scenes[0].extras.sky.brightness: unknown key",
                [](auto& d) { d["scenes"][0]["extras"]["sky"]["brightness"] = nlohmann::json::array(); });
    expectError("node 2 'cam'.extras.window: unknown key",
                [](auto& d) { d["nodes"][2]["extras"] = {{"window", nlohmann::json::array()}}; });
    expectError("nodes[2].rotation: must be a unit quaternion",
                [](auto& d) { d["nodes"][2]["rotation"] = {0, 0, 0, 0}; });
    expectError("nodes[2]: has both a matrix and translation/rotation/scale",
                [](auto& d) { d["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; });
    expectError("nodes[2].matrix: must be an array of 16 numbers", [](auto& d) {
        d["nodes"][2].erase("translation");
        d["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    });
    expectError("cameras[0].perspective.aspectRatio: must be a positive number",
                [](auto& d) { d["cameras"][0]["perspective"]["aspectRatio"] = "wide"; });
    expectError("cameras[0].perspective.yfov: must be a number",
                [](auto& d) { d["cameras"][0]["perspective"]["yfov"] = {0.8}; });
    expectError("KHR_lights_punctual.lights[0].intensity: must be a number",
                [](auto& d) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = "bright"; });
    expectError("KHR_lights_punctual.lights[0].color: must be an array of 3 numbers",
                [](auto& d) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["color"] = {1, 1}; });
    expectError("materials[0].emissiveFactor: must be an array of 3 numbers",
                [](auto& d) { d["materials"][0]["emissiveFactor"] = {1}; });
    expectError("extensionsRequired[0]: must be a string", [](auto& d) { d["extensionsRequired"] = {7}; });
    expectError("accessors[0].type: must be one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4",
                [](auto& d) { d["accessors"][0]["type"] = "VEC9"; });
    expectError("nodes[2].name: must be a string", [](auto& d) { d["nodes"][2]["name"] = 3; });
}

TEST(UntrustedScene, NonFiniteTransformsAreErrors)
{
    // Finite numbers in the file whose product overflows: the camera sat at infinity and the
    // image came out flat.
    const std::string dir = test::tempDir("untrusted-inf");
    test::GltfWriter w = fullScene();
    w.doc()["nodes"].push_back({{"name", "far"}, {"translation", {0, 1e308, 0}}, {"children", {2}}});
    w.doc()["nodes"][2]["translation"] = {0, 1e308, 0};
    w.doc()["scenes"][0]["nodes"] = {0, 1, 3};
    std::string e = errorOf(w.write(dir + "/cam.gltf"));
    EXPECT_TRUE(contains(e, "cam.gltf: node 2 'cam': its world transform is not finite")) << e;
    // Finite in double, beyond float, which the renderer uses.
    w.doc()["nodes"][3]["translation"] = {0, 1e39, 0};
    w.doc()["nodes"][2]["translation"] = {0, 1e39, 0};
    e = errorOf(w.write(dir + "/float.gltf"));
    EXPECT_TRUE(contains(e, "float.gltf: node 2 'cam': camera position")) << e;
    test::GltfWriter sun = fullScene();
    sun.doc()["nodes"].push_back({{"name", "huge"}, {"scale", {1e300, 1e300, 1e300}}, {"children", {1}}});
    sun.doc()["nodes"][1]["scale"] = {1e300, 1e300, 1e300};
    sun.doc()["scenes"][0]["nodes"] = {0, 2, 3};
    e = errorOf(sun.write(dir + "/sun.gltf"));
    EXPECT_TRUE(contains(e, "sun.gltf: node 1 'sun': its world transform is not finite")) << e;
}

TEST(UntrustedScene, ImageBufferViewOutsideItsBufferIsRefused)
{
    // tinygltf hands an image's bytes to the image loader as &buffer.data[byteOffset], unchecked.
    const std::string dir = test::tempDir("untrusted-imageview");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    w.doc()["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", std::uint64_t(1) << 63}, {"byteLength", 4}});
    w.doc()["images"] = {{{"bufferView", 1}, {"mimeType", "image/png"}}};
    const std::string e = errorOf(w.write(dir + "/img.gltf"));
    EXPECT_TRUE(contains(e, "img.gltf: images[0].bufferView: bufferViews[1] (byteOffset 9223372036854775808, "
                            "byteLength 4) lies outside buffers[0] (byteLength 36)")) << e;
}

// --- 3. GLB framing ---------------------------------------------------------------------------

void putU32(std::vector<unsigned char>& b, std::size_t at, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        b[at + static_cast<std::size_t>(i)] = static_cast<unsigned char>(v >> (8 * i));
}

std::uint32_t getU32(const std::vector<unsigned char>& b, std::size_t at)
{
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i)
        v = (v << 8) | b[at + static_cast<std::size_t>(i)];
    return v;
}

std::string writeBytes(const std::string& path, const std::vector<unsigned char>& b)
{
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()),
                                                static_cast<std::streamsize>(b.size()));
    return path;
}

TEST(UntrustedScene, GlbLoads)
{
    const std::string dir = test::tempDir("untrusted-glb-ok");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    const Scene s = loadGltf(w.writeGlb(dir + "/ok.glb"));
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
}

TEST(UntrustedScene, GlbBinChunkPastTheEndIsRefused)
{
    // The BIN chunk claims 8 more bytes than the file holds, and the buffer all of them: tinygltf
    // 2.7 forgets the chunk's own 8-byte header and copies past the end of the file's bytes.
    const std::string dir = test::tempDir("untrusted-glb-bin");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    std::vector<unsigned char> b = w.glbBytes();
    const std::size_t binHeader = 20 + getU32(b, 12);
    const std::uint32_t claimed = getU32(b, binHeader) + 8;
    w.doc()["buffers"][0]["byteLength"] = claimed;
    std::string json = w.doc().dump();
    while (json.size() % 4)
        json += ' ';
    ASSERT_EQ(json.size(), getU32(b, 12)) << "the same JSON length, so that the BIN chunk stays put";
    std::copy(json.begin(), json.end(), b.begin() + 20);
    putU32(b, binHeader, claimed);
    const std::string e = errorOf(writeBytes(dir + "/bin.glb", b));
    EXPECT_TRUE(contains(e, "bin.glb: GLB chunk 1 (BIN)")) << e;
    EXPECT_TRUE(contains(e, "runs past the end")) << e;
}

TEST(UntrustedScene, GlbHeaderIsChecked)
{
    const std::string dir = test::tempDir("untrusted-glb-header");
    test::GltfWriter w;
    w.addMeshNode("tri", kTri);
    const std::vector<unsigned char> good = w.glbBytes();
    auto variant = [&](const std::string& name, auto edit) {
        std::vector<unsigned char> b = good;
        edit(b);
        return errorOf(writeBytes(dir + "/" + name + ".glb", b));
    };
    std::string e = variant("magic", [](auto& b) { b[0] = 'x'; });
    EXPECT_TRUE(contains(e, "magic.glb: not a binary glTF file (no 'glTF' magic)")) << e;
    e = variant("version", [](auto& b) { putU32(b, 4, 1); });
    EXPECT_TRUE(contains(e, "version.glb: GLB version 1")) << e;
    e = variant("length", [](auto& b) { putU32(b, 8, static_cast<std::uint32_t>(b.size() + 4)); });
    EXPECT_TRUE(contains(e, "length.glb: GLB header length")) << e;
    e = variant("json", [](auto& b) { putU32(b, 12, static_cast<std::uint32_t>(b.size())); });
    EXPECT_TRUE(contains(e, "json.glb: GLB chunk 0 (JSON)")) << e;
    EXPECT_TRUE(contains(e, "runs past the end")) << e;
    e = variant("jsonlast", [](auto& b) { putU32(b, 8, 20 + getU32(b, 12) + 4); });
    EXPECT_TRUE(contains(e, "jsonlast.glb: GLB chunk 1")) << e;  // a chunk header cut in two
    e = variant("type", [](auto& b) { putU32(b, 16, 0x004E4942u); });
    EXPECT_TRUE(contains(e, "type.glb: GLB chunk 0 is not JSON")) << e;
    e = variant("bintype", [](auto& b) { putU32(b, 20 + getU32(b, 12) + 4, 0x12345678u); });
    EXPECT_TRUE(contains(e, "bintype.glb: GLB chunk 1 is not BIN")) << e;
    e = variant("short", [](auto& b) { b.resize(10); });
    EXPECT_TRUE(contains(e, "short.glb: too short")) << e;
    e = variant("empty", [](auto& b) { b.clear(); });
    EXPECT_TRUE(contains(e, "empty.glb: too short")) << e;
}

// --- 7. Far geometry is reported ----------------------------------------------------------------

// Two triangles making a w x w square at height y, centred on (cx, cz).
std::vector<Triangle> square(float w, float y = 0.0f, float cx = 0.0f, float cz = 0.0f)
{
    const float h = 0.5f * w;
    return {{{cx - h, y, cz - h}, {cx + h, y, cz - h}, {cx + h, y, cz + h}},
            {{cx - h, y, cz - h}, {cx + h, y, cz + h}, {cx - h, y, cz + h}}};
}

// A 5 m room (floor, ceiling) with a camera in it: nodes 0, 1 and 2 'cam'.
test::GltfWriter roomWithCamera()
{
    test::GltfWriter w;
    w.addMeshNode("floor", square(5.0f));
    w.addMeshNode("ceiling", square(5.0f, 2.8f));
    w.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    w.doc()["nodes"].push_back({{"name", "cam"}, {"camera", 0}, {"translation", {0, 1.5, 2}}});
    w.doc()["scenes"][0]["nodes"].push_back(2);
    return w;
}

std::vector<std::string> farWarnings(const Scene& s)
{
    std::vector<std::string> out;
    for (const auto& w : s.warnings)
        if (contains(w, "bounding box"))
            out.push_back(w);
    return out;
}

TEST(UntrustedScene, FarGeometryIsReported)
{
    const std::string dir = test::tempDir("untrusted-far");
    {
        // One triangle a thousand kilometres away widened the emission box 200,000-fold.
        test::GltfWriter w = roomWithCamera();
        w.addMeshNode("speck", {{{1e6f, 0, 0}, {1e6f + 1, 0, 0}, {1e6f, 1, 0}}});
        const auto warnings = farWarnings(loadGltf(w.write(dir + "/speck.gltf")));
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_TRUE(contains(warnings[0], "speck.gltf: node 3 'speck'")) << warnings[0];
    }
    {
        // A far object of several nodes is named by its root, once.
        test::GltfWriter w = roomWithCamera();
        const int a = w.addMeshNode("part a", square(1.0f, 0.0f, 5e4f, 0.0f));
        const int b = w.addMeshNode("part b", square(1.0f, 2.0f, 5e4f, 0.0f));
        w.doc()["nodes"].push_back({{"name", "far house"}, {"children", {a, b}}});
        w.doc()["scenes"][0]["nodes"] = {0, 1, 2, 5};
        const auto warnings = farWarnings(loadGltf(w.write(dir + "/group.gltf")));
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_TRUE(contains(warnings[0], "group.gltf: node 5 'far house'")) << warnings[0];
    }
    {
        // A ground plane 2 km wide under the room dominates the box as much, and is reported.
        test::GltfWriter w = roomWithCamera();
        w.addMeshNode("ground", square(2000.0f, -0.01f));
        const auto warnings = farWarnings(loadGltf(w.write(dir + "/ground.gltf")));
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_TRUE(contains(warnings[0], "node 3 'ground'")) << warnings[0];
    }
    {
        // Without a camera, the smaller part is the odd one out.
        test::GltfWriter w;
        w.addMeshNode("floor", square(5.0f));
        w.addMeshNode("speck", {{{0, 0, 1e5f}, {1, 0, 1e5f}, {0, 1, 1e5f}}});
        const auto warnings = farWarnings(loadGltf(w.write(dir + "/nocam.gltf")));
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_TRUE(contains(warnings[0], "node 1 'speck'")) << warnings[0];
    }
}

TEST(UntrustedScene, OrdinaryScenesHaveNoFarGeometryWarning)
{
    const std::string dir = test::tempDir("untrusted-near");
    {
        // The room itself, seen from inside, is not "far" from a small lamp: it holds the camera.
        test::GltfWriter w = roomWithCamera();
        w.addMeshNode("lamp", square(0.1f, 2.5f));
        EXPECT_TRUE(farWarnings(loadGltf(w.write(dir + "/lamp.gltf"))).empty());
    }
    {
        // A garden seven times the room's diameter: below the threshold of 10.
        test::GltfWriter w = roomWithCamera();
        w.addMeshNode("garden", square(40.0f, -0.01f));
        EXPECT_TRUE(farWarnings(loadGltf(w.write(dir + "/garden.gltf"))).empty());
    }
    for (const char* name : {"room.gltf", "inner_room.gltf", "bay_window.gltf"}) {
        const Scene s = loadGltf(std::string(FEN_SCENES_DIR) + "/" + name);
        EXPECT_TRUE(farWarnings(s).empty()) << name << ": " << farWarnings(s).front();
    }
}

TEST(UntrustedScene, NamesWithControlCharactersStayOnOneLine)
{
    // Found by the fuzz target: a node named "p\ne" split the error naming it over two lines.
    const std::string dir = test::tempDir("untrusted-names");
    auto oneLine = [](const std::string& e) { return !e.empty() && e.find('\n') == std::string::npos; };
    test::GltfWriter w = fullScene();
    w.node(0)["name"] = "p\ne";
    w.doc()["meshes"][0]["primitives"][0]["mode"] = 3;
    std::string e = errorOf(w.write(dir + "/node.gltf"));
    EXPECT_TRUE(oneLine(e) && contains(e, "node 0 'p\\x0ae'")) << e;
    w = fullScene();
    w.doc()["materials"][0]["name"] = "g\rl\nass";
    w.doc()["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {2, 0, 0, 1};
    e = errorOf(w.write(dir + "/material.gltf"));
    EXPECT_TRUE(oneLine(e) && contains(e, "materials[0] 'g\\x0dl\\x0aass'")) << e;
    w = fullScene();
    w.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "po\nint";
    e = errorOf(w.write(dir + "/light.gltf"));
    EXPECT_TRUE(oneLine(e)) << e;
    w = fullScene();
    w.doc()["cameras"][0]["type"] = "ortho\ngraphic";
    e = errorOf(w.write(dir + "/camera.gltf"));
    EXPECT_TRUE(oneLine(e)) << e;
    w = fullScene();
    w.doc()["extensionsRequired"] = {"EXT_\nfoo"};
    e = errorOf(w.write(dir + "/ext.gltf"));
    EXPECT_TRUE(oneLine(e)) << e;
    w = fullScene();
    w.doc()["scenes"][0]["extras"]["sky"]["type"] = "sun\nset";
    e = errorOf(w.write(dir + "/sky.gltf"));
    EXPECT_TRUE(oneLine(e)) << e;
    w = fullScene();
    w.doc()["nodes"][1]["name"] = "s\nun";
    w.doc()["nodes"].push_back(w.doc()["nodes"][1]);
    w.doc()["scenes"][0]["nodes"].push_back(3);
    e = errorOf(w.write(dir + "/sun.gltf"));  // a second sun, naming the first
    EXPECT_TRUE(oneLine(e) && contains(e, "'s\\x0aun'")) << e;
    // Warnings too.
    w = fullScene();
    w.addMeshNode("far\naway", {{{1e6f, 0, 0}, {1e6f + 1, 0, 0}, {1e6f, 1, 0}}});
    const Scene s = loadGltf(w.write(dir + "/far.gltf"));
    ASSERT_FALSE(s.warnings.empty());
    for (const auto& warning : s.warnings)
        EXPECT_TRUE(oneLine(warning)) << warning;
    // findCamera lists the camera names.
    w = fullScene();
    w.node(2)["name"] = "c\nam";
    const Scene c = loadGltf(w.write(dir + "/cam.gltf"));
    try {
        findCamera(c, "nope");
        ADD_FAILURE();
    } catch (const Error& err) {
        EXPECT_TRUE(oneLine(err.what())) << err.what();
    }
}

// --- 8. The fuzz target's seeds ---------------------------------------------------------------

std::vector<unsigned char> readBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::vector<unsigned char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(UntrustedScene, FuzzSeedsLoadAsTheFuzzerSeesThem)
{
    // tests/fuzz/corpus through the fuzz target's entry, name and folder: the seeds are scenes
    // (one of them refused), so that mutations start from inputs that reach the whole loader.
    const std::string fuzz = FEN_FUZZ_DIR;
    for (const char* name : {"data_uri.gltf", "external_bin.gltf", "binary.glb", "table_sky.gltf", "textured.gltf"}) {
        const std::vector<unsigned char> b = readBytes(fuzz + "/corpus/" + name);
        ASSERT_FALSE(b.empty()) << name;
        const Scene s = loadGltfFromMemory(b.data(), b.size(), "fuzz.gltf", fuzz + "/files");
        EXPECT_GE(s.triangles.size(), 1u) << name;
        if (std::string(name) == "textured.gltf")
            EXPECT_EQ(s.textures.size(), 1u);  // files/sub/tex ture.png, decoded: the fuzzer reaches stb_image
    }
    const std::vector<unsigned char> b = readBytes(fuzz + "/corpus/refused_uri.gltf");
    try {
        loadGltfFromMemory(b.data(), b.size(), "fuzz.gltf", fuzz + "/files");
        ADD_FAILURE() << "refused_uri.gltf loaded";
    } catch (const Error& e) {
        EXPECT_TRUE(contains(e.what(), "fuzz.gltf: buffers[0].uri: '..%2Foutside.bin' leads outside")) << e.what();
    }
    // files/outside.bin is a link out of the folder.
    const std::string e = [&] {
        try {
            SceneFolder(fuzz + "/files").resolve("outside.bin", "images[0].uri");
        } catch (const Error& err) {
            return std::string(err.what());
        }
        return std::string();
    }();
    EXPECT_TRUE(contains(e, "images[0].uri: 'outside.bin' leads outside the scene's folder (through a symbolic link)")) << e;
}

}  // namespace
}  // namespace fen
