// scene_files.h — the bytes a scene may read, checked before any parser sees them (README,
// "Untrusted scenes"). Scenes come from other people; these are the walls around them.
//
// - SceneFolder: a URI names a file only when, percent-decoded as tinygltf decodes it and with
//   every symbolic link followed, it is a regular file under the scene's folder (canonical paths);
//   absolute paths and every scheme but data: are refused. tinygltf reads external files only
//   through the FsCallbacks that SceneFolder::install puts in place, which apply the same rule:
//   that is the one boundary, and resolve() gives the same answer earlier, with a better message.
// - readSceneFile: a whole regular file of at most kMaxSceneFileBytes.
// - checkGlb: the GLB header and every chunk length against the bytes there are.
// - checkJsonNesting: the nesting depth of raw JSON text, before a recursive parser sees it.
// No message quotes a file's content or the size of a file other than the scene itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class TinyGLTF;
}

namespace fen {

// tinygltf counts bytes in `int` (images) and `unsigned int` (documents): stay below both.
constexpr std::uint64_t kMaxSceneFileBytes = (1ull << 31) - 1;

// Deeper JSON than this is refused; a glTF that fenestra reads needs about 8 levels.
constexpr int kMaxJsonDepth = 64;

class SceneFolder {
public:
    // `folder` must exist; "" means the working directory.
    explicit SceneFolder(const std::string& folder);
    const std::string& path() const { return canonical_; }

    // How a URI as written in the file (uri of buffers[i] or images[i]) resolves: the canonical
    // path of a regular file inside the folder, or "" for a data: URI (tinygltf decodes those) and
    // for a file that is not there when it is not `required`. Throws Error "<where>: '<uri>' ..."
    // for anything else.
    std::string resolve(const std::string& uri, const std::string& where, bool required = true) const;

    // Makes `loader` read external files through this folder's rule; the folder must outlive
    // every load made with it. A path it refuses is recorded in refusal().
    void install(tinygltf::TinyGLTF& loader);
    const std::string& refusal() const { return refusal_; }
    // The canonical paths of the files read through it (buffers, images), in order.
    const std::vector<std::string>& filesRead() const { return read_; }

private:
    // Why the file system path `path` (the folder, '/', a decoded URI: as tinygltf joins them)
    // may not be read; "" if it may, and then `canonicalOut` receives its canonical form.
    std::string refuse(const std::string& path, std::string* canonicalOut) const;
    static bool fileExists(const std::string& path, void* self);
    static std::string expandFilePath(const std::string& path, void* self);
    static bool readWholeFile(std::vector<unsigned char>* out, std::string* err,
                              const std::string& path, void* self);
    static bool writeWholeFile(std::string* err, const std::string& path,
                               const std::vector<unsigned char>& contents, void* self);

    std::string canonical_;  // no trailing '/', except for "/" itself
    std::string refusal_;
    std::vector<std::string> read_;
};

// tinygltf's decoding of a URI into a file name (its dlib::urldecode): "%XY" is a byte, a
// non-hex digit counts as 0, and '+' is a space. The check must see the name tinygltf opens.
std::string percentDecode(const std::string& uri);

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

// Throws Error naming `path`, the line and the byte when arrays and objects in JSON text nest
// deeper than kMaxJsonDepth. A linear scan (brackets inside strings do not count), so that no
// recursive parser ever sees the text: tinygltf's conversion of extras recurses, and 20,000
// levels overflow the stack.
void checkJsonNesting(const char* text, std::size_t size, const std::string& path);

}  // namespace fen
