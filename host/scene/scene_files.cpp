// scene_files.cpp — reading a scene's bytes and checking their framing (scene_files.h).
#include "scene/scene_files.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tiny_gltf.h>

#include "util/error.h"

namespace fen {

namespace {

constexpr std::uint32_t kChunkJson = 0x4E4F534Au;  // "JSON", little-endian
constexpr std::uint32_t kChunkBin = 0x004E4942u;   // "BIN\0"

std::uint32_t u32(const unsigned char* p)
{
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

const char* chunkName(std::uint32_t type)
{
    return type == kChunkJson ? "JSON" : type == kChunkBin ? "BIN" : "of unknown type";
}

// Closes the descriptor on every path out.
struct Fd {
    int fd;
    ~Fd()
    {
        if (fd >= 0)
            ::close(fd);
    }
};

// RFC 3986: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":". A relative reference
// cannot have a ':' in its first segment, so this is not a file name.
std::string schemeOf(const std::string& uri)
{
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0])))
        return "";
    for (std::size_t i = 1; i < uri.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(uri[i]);
        if (c == ':') {
            std::string s = uri.substr(0, i);
            for (auto& ch : s)
                ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            return s;
        }
        if (!std::isalnum(c) && c != '+' && c != '-' && c != '.')
            return "";
    }
    return "";
}

// Reasons a callback may meet in the normal course (tinygltf looks for a file in the scene's
// folder, then in ".") and that are not worth reporting instead of tinygltf's own message.
const char* const kNotFound = "not found in the scene's folder";
const char* const kNotJoined = "is not a path inside the scene's folder; refused";

}  // namespace

std::string percentDecode(const std::string& uri)
{
    auto hex = [](unsigned char c) -> unsigned char {
        if (c >= '0' && c <= '9')
            return static_cast<unsigned char>(c - '0');
        if (c >= 'a' && c <= 'f')
            return static_cast<unsigned char>(c - 'a' + 10);
        if (c >= 'A' && c <= 'F')
            return static_cast<unsigned char>(c - 'A' + 10);
        return 0;
    };
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && uri.size() > i + 2) {
            out += static_cast<char>(hex(static_cast<unsigned char>(uri[i + 1])) << 4 |
                                     hex(static_cast<unsigned char>(uri[i + 2])));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

SceneFolder::SceneFolder(const std::string& folder)
{
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::canonical(folder.empty() ? "." : folder, ec);
    if (ec)
        throw Error(cat(folder, ": cannot resolve the scene's folder (", ec.message(), ")"));
    canonical_ = p.string();
}

std::string SceneFolder::refuse(const std::string& path, std::string* canonicalOut) const
{
    namespace fs = std::filesystem;
    const std::string prefix = canonical_ == "/" ? canonical_ : canonical_ + "/";
    if (path.compare(0, prefix.size(), prefix) != 0 || path.size() == prefix.size())
        return kNotJoined;
    if (path.find('\0') != std::string::npos)
        return "contains a NUL byte; refused";
    // Lexically first: a path that climbs out is refused without asking whether its target exists.
    const fs::path rel = fs::path(path.substr(prefix.size())).lexically_normal();
    if (rel.is_absolute() || (!rel.empty() && *rel.begin() == ".."))
        return "leads outside the scene's folder; refused";
    std::error_code ec;
    const fs::path canonical = fs::canonical(path, ec);
    if (ec == std::errc::no_such_file_or_directory)
        return kNotFound;
    if (ec)
        return cat("cannot be resolved (", ec.message(), ")");
    const std::string c = canonical.string();
    if (c.compare(0, prefix.size(), prefix) != 0)
        return "leads outside the scene's folder (through a symbolic link); refused";
    if (!fs::is_regular_file(fs::status(canonical, ec)))
        return "is not a regular file";
    if (canonicalOut)
        *canonicalOut = c;
    return "";
}

std::string SceneFolder::resolve(const std::string& uri, const std::string& where, bool required) const
{
    const std::string scheme = schemeOf(uri);
    if (scheme == "data")
        return "";
    const std::string quoted = cat(where, ": '", printable(uri), "' ");
    if (!scheme.empty())
        throw Error(cat(quoted, "refused: only paths relative to the scene's folder and data: URIs "
                                "are read"));
    const std::string decoded = percentDecode(uri);
    if (!decoded.empty() && decoded[0] == '/')
        throw Error(cat(quoted, "refused: an absolute path; only paths relative to the scene's "
                                "folder and data: URIs are read"));
    std::string canonical;
    const std::string why = refuse((canonical_ == "/" ? "" : canonical_) + "/" + decoded, &canonical);
    if (why == kNotFound && !required)
        return "";
    if (!why.empty())
        throw Error(cat(quoted, why));
    return canonical;
}

void SceneFolder::install(tinygltf::TinyGLTF& loader)
{
    tinygltf::FsCallbacks fs{};
    fs.FileExists = &SceneFolder::fileExists;
    fs.ExpandFilePath = &SceneFolder::expandFilePath;
    fs.ReadWholeFile = &SceneFolder::readWholeFile;
    fs.WriteWholeFile = &SceneFolder::writeWholeFile;
    fs.user_data = this;
    loader.SetFsCallbacks(fs);
}

bool SceneFolder::fileExists(const std::string& path, void* self)
{
    auto* folder = static_cast<SceneFolder*>(self);
    const std::string why = folder->refuse(path, nullptr);
    if (!why.empty() && why != kNotFound && why != kNotJoined && folder->refusal_.empty())
        folder->refusal_ = cat("'", printable(path), "' ", why);
    return why.empty();
}

std::string SceneFolder::expandFilePath(const std::string& path, void*)
{
    return path;  // no "~" or "$VAR": a URI names a file relative to the scene, nothing else
}

bool SceneFolder::readWholeFile(std::vector<unsigned char>* out, std::string* err,
                                const std::string& path, void* self)
{
    auto* folder = static_cast<SceneFolder*>(self);
    std::string canonical;
    std::string why = folder->refuse(path, &canonical);
    if (why.empty()) {
        try {
            *out = readSceneFile(canonical);
            folder->read_.push_back(canonical);
            return true;
        } catch (const Error&) {
            why = "cannot be read";  // readSceneFile's message would repeat the path
        }
    }
    if (folder->refusal_.empty())
        folder->refusal_ = cat("'", printable(path), "' ", why);
    if (err)
        *err = why;
    return false;
}

bool SceneFolder::writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*)
{
    if (err)
        *err = "loading a scene writes nothing";
    return false;
}

std::vector<unsigned char> readSceneFile(const std::string& path)
{
    // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below anyway.
    Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (f.fd < 0)
        throw Error(cat(path, ": cannot open file (", std::strerror(errno), ")"));
    struct stat st {};
    if (::fstat(f.fd, &st) != 0 || !S_ISREG(st.st_mode))
        throw Error(cat(path, ": not a regular file"));
    if (static_cast<std::uint64_t>(st.st_size) > kMaxSceneFileBytes)
        throw Error(cat(path, ": larger than ", kMaxSceneFileBytes, " bytes, the most a scene file may hold"));
    std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
    std::size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t n = ::read(f.fd, bytes.data() + got, bytes.size() - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            throw Error(cat(path, ": read error (", std::strerror(errno), ")"));
        if (n == 0)
            break;  // shrank while we read: parse what there is
        got += static_cast<std::size_t>(n);
    }
    bytes.resize(got);
    return bytes;
}

GlbLayout checkGlb(const unsigned char* data, std::size_t size, const std::string& name)
{
    if (size < 12)
        throw Error(cat(name, ": too short for a binary glTF (", size, " bytes; its header alone is 12)"));
    if (std::memcmp(data, "glTF", 4) != 0)
        throw Error(cat(name, ": not a binary glTF file (no 'glTF' magic)"));
    const std::uint32_t version = u32(data + 4), length = u32(data + 8);
    if (version != 2)
        throw Error(cat(name, ": GLB version ", version, "; only version 2 is read"));
    if (length > size)
        throw Error(cat(name, ": GLB header length ", length, " exceeds the file's ", size, " bytes"));
    GlbLayout out;
    out.length = length;
    // 64-bit offsets: a chunk length near 2^32 must not wrap the sum.
    std::uint64_t at = 12;
    for (int k = 0; at < length; ++k) {
        if (length - at < 8)
            throw Error(cat(name, ": GLB chunk ", k, "'s 8-byte header runs past the end (GLB length ",
                            length, ")"));
        const std::uint32_t chunkLength = u32(data + at), type = u32(data + at + 4);
        if (chunkLength > length - at - 8)
            throw Error(cat(name, ": GLB chunk ", k, " (", chunkName(type), ") of ", chunkLength,
                            " bytes runs past the end (GLB length ", length, ")"));
        if (k == 0 && type != kChunkJson)
            throw Error(cat(name, ": GLB chunk 0 is not JSON"));
        if (k == 1 && type != kChunkBin)
            throw Error(cat(name, ": GLB chunk 1 is not BIN"));
        // The next chunk's header must start on a 4-byte boundary (glTF 2.0, "GLB File Format").
        if (chunkLength % 4 != 0)
            throw Error(cat(name, ": GLB chunk ", k, " (", chunkName(type), ") of ", chunkLength,
                            " bytes is not padded to a multiple of 4"));
        if (k == 0) {
            out.jsonOffset = static_cast<std::size_t>(at + 8);
            out.jsonSize = chunkLength;
        }
        at += 8ull + chunkLength;
    }
    if (out.jsonSize == 0)
        throw Error(cat(name, ": GLB has no JSON content"));
    return out;
}

void checkJsonNesting(const char* text, std::size_t size, const std::string& path)
{
    int depth = 0;
    std::size_t line = 1;
    bool inString = false;
    for (std::size_t i = 0; i < size; ++i) {
        const char c = text[i];
        if (c == '\n')
            ++line;
        if (inString) {
            if (c == '\\')
                ++i;  // the escaped character cannot end the string (a raw newline is invalid JSON anyway)
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw Error(cat(path, ": JSON nested deeper than ", kMaxJsonDepth, " levels (line ", line,
                                ", byte ", i, ")"));
        } else if (c == ']' || c == '}') {
            --depth;  // unbalanced text is the parser's to report
        }
    }
}

}  // namespace fen
