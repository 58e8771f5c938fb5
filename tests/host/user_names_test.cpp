// user_names_test.cpp — the names a user types (util/utf8.h, io/json_text.h, io/path_checks.h,
// render/checkpoint.h's target check): bytes reach the JSON as valid UTF-8, outputs never
// overwrite inputs (also through a link or a hard link), and only regular files are read.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/json_text.h"
#include "io/path_checks.h"
#include "render/checkpoint.h"
#include "support/gltf_writer.h"
#include "util/error.h"
#include "util/utf8.h"

namespace fen {
namespace {

TEST(UserNames, Utf8IsValidatedByTheRfcRules)
{
    EXPECT_TRUE(isValidUtf8("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x8C\x9E"));  // é, €, an emoji
    EXPECT_FALSE(isValidUtf8("caf\xE9"));                                   // Latin-1 é
    EXPECT_FALSE(isValidUtf8("\xC0\xAF"));                                  // overlong '/'
    EXPECT_FALSE(isValidUtf8("\xED\xA0\x80"));                              // a surrogate
    EXPECT_FALSE(isValidUtf8("\xF4\x90\x80\x80"));                          // beyond U+10FFFF
    EXPECT_FALSE(isValidUtf8("\xE2\x82"));                                  // cut short
    EXPECT_EQ(utf8OrEscaped("out/caf\xE9.exr"), "out/caf\\xE9.exr");
    EXPECT_EQ(utf8OrEscaped("caf\xC3\xA9"), "caf\xC3\xA9");
}

TEST(UserNames, JsonWithLatin1NamesDumpsAsValidUtf8)
{
    nlohmann::json j = {{"scene", "r\xE9sum\xE9.gltf"}, {"regions", {{"s\xFC" "d", {{"mean", 1.0}}}}}, {"n", 3}};
    EXPECT_THROW(j.dump(), nlohmann::json::type_error);  // what a render used to fail with, after rendering
    const std::string out = dumpUtf8(j);
    const auto back = nlohmann::json::parse(out);
    EXPECT_EQ(back["scene"], "r\\xE9sum\\xE9.gltf");
    EXPECT_TRUE(back["regions"].contains("s\\xFCd"));
    EXPECT_EQ(back["n"], 3);
}

TEST(UserNames, AnOutputIsNeverAnInput)
{
    const std::string dir = test::tempDir("names-inputs");
    std::ofstream(dir + "/scene.gltf") << "{}";
    std::filesystem::create_directories(dir + "/sub");
    std::filesystem::create_symlink(dir + "/scene.gltf", dir + "/link.gltf");
    ASSERT_EQ(::link((dir + "/scene.gltf").c_str(), (dir + "/hard.gltf").c_str()), 0);
    const std::vector<std::pair<std::string, std::string>> inputs = {{"the scene", dir + "/scene.gltf"}};
    for (const std::string& out : {dir + "/scene.gltf", dir + "/sub/../scene.gltf", dir + "/./link.gltf", dir + "/hard.gltf"}) {
        try {
            refuseOverwritingInputs(out, "--checkpoint", inputs);
            ADD_FAILURE() << out << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("is the scene"), std::string::npos) << e.what();
        }
    }
    EXPECT_NO_THROW(refuseOverwritingInputs(dir + "/new.ckpt", "--checkpoint", inputs));
}

TEST(UserNames, ACheckpointOverwritesOnlyACheckpoint)
{
    const std::string dir = test::tempDir("names-ckpt");
    EXPECT_NO_THROW(requireCheckpointTarget(dir + "/new.ckpt", "--checkpoint"));
    std::ofstream(dir + "/scene.gltf") << "{\"asset\": {\"version\": \"2.0\"}}";
    EXPECT_THROW(requireCheckpointTarget(dir + "/scene.gltf", "--checkpoint"), Error);
    std::ofstream(dir + "/old.ckpt") << "FENESTRA CHECKPOINT 1\n{}";
    EXPECT_NO_THROW(requireCheckpointTarget(dir + "/old.ckpt", "--checkpoint"));
    EXPECT_THROW(requireCheckpointTarget(dir, "--checkpoint"), Error);
}

TEST(UserNames, OnlyRegularFilesAreResumedFrom)
{
    const std::string dir = test::tempDir("names-fifo");
    ASSERT_EQ(::mkfifo((dir + "/pipe").c_str(), 0600), 0);
    try {
        requireRegularFile(dir + "/pipe", "--resume");  // opening it would block for ever
        ADD_FAILURE() << "a FIFO accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--resume must be a regular file, not a FIFO"), std::string::npos) << e.what();
    }
    EXPECT_THROW(requireRegularFile(dir, "--resume"), Error);
    EXPECT_THROW(requireRegularFile(dir + "/none", "--resume"), Error);
}

}  // namespace
}  // namespace fen
