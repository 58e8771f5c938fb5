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

}  // namespace
}  // namespace fen
