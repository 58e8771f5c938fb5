// scene_files.cpp — reading a scene's bytes and checking their framing (scene_files.h).
#include "scene/scene_files.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

}  // namespace

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

}  // namespace fen
