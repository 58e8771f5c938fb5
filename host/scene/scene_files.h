// scene_files.h — the bytes a scene may read, checked before any parser sees them (README,
// "Untrusted scenes"). Scenes come from other people; these are the walls around them.
//
// - readSceneFile: a whole regular file of at most kMaxSceneFileBytes.
// - checkGlb: the GLB header and every chunk length against the bytes there are.
// No message quotes a file's content or the size of a file other than the scene itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fen {

// tinygltf counts bytes in `int` (images) and `unsigned int` (documents): stay below both.
constexpr std::uint64_t kMaxSceneFileBytes = (1ull << 31) - 1;

// The whole of a regular file. Throws Error naming `path` ("cannot open file", not a regular
// file, larger than kMaxSceneFileBytes).
std::vector<unsigned char> readSceneFile(const std::string& path);

// A binary glTF's JSON chunk, after checking the 12-byte header (magic "glTF", version 2, a total
// length no larger than the file) and that every chunk's 8-byte header and data lie inside that
// length: the JSON chunk first, the BIN chunk (if any) second, each a multiple of 4 bytes.
struct GlbLayout {
    std::size_t length = 0;      // the header's total length: the bytes tinygltf may see
    std::size_t jsonOffset = 0, jsonSize = 0;
};
GlbLayout checkGlb(const unsigned char* data, std::size_t size, const std::string& name);

}  // namespace fen
