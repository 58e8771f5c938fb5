// texture_image.cpp — decoding a texture's image with stb_image (texture_image.h).
#include "scene/texture_image.h"

#include <climits>
#include <cstdint>
#include <cstring>
#include <memory>

#include <stb/stb_image.h>

#include "util/error.h"

namespace fen {

void decodeTextureImage(const unsigned char* bytes, std::size_t size, const std::string& where, Texture* texture)
{
    if (size == 0 || size > static_cast<std::size_t>(INT_MAX))
        throw Error(cat(where, ": the image is empty or larger than 2 GiB"));
    const bool png = size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
    const bool jpeg = size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
    if (!png && !jpeg)
        throw Error(cat(where, ": not a PNG or JPEG image (glTF's two image formats)"));
    int w = 0, h = 0, channels = 0;
    const int n = static_cast<int>(size);
    // A PNG's size is in its IHDR chunk, read here: stb_image's own check would refuse a large one
    // only as "unknown image type".
    if (png && size >= 24 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
        const auto be32 = [&](std::size_t at) {
            return std::uint32_t{bytes[at]} << 24 | std::uint32_t{bytes[at + 1]} << 16 |
                   std::uint32_t{bytes[at + 2]} << 8 | std::uint32_t{bytes[at + 3]};
        };
        const std::uint32_t pw = be32(16), ph = be32(20);
        if (pw < 1 || ph < 1 || pw > kMaxTextureSide || ph > kMaxTextureSide)
            throw Error(cat(where, ": ", pw, " x ", ph, " texels; a texture may have 1 to ", kMaxTextureSide,
                            " a side"));
    }
    if (!stbi_info_from_memory(bytes, n, &w, &h, &channels))
        throw Error(cat(where, ": unreadable ", png ? "PNG" : "JPEG", " image (", stbi_failure_reason(), ")"));
    if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide)
        throw Error(cat(where, ": ", w, " x ", h, " texels; a texture may have 1 to ", kMaxTextureSide,
                        " a side"));
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load_from_memory(bytes, n, &w, &h, &channels, 3),
                                                           stbi_image_free);
    if (!pixels)
        throw Error(cat(where, ": unreadable ", png ? "PNG" : "JPEG", " image (", stbi_failure_reason(), ")"));
    texture->width = w;
    texture->height = h;
    texture->rgb.assign(pixels.get(), pixels.get() + std::size_t(w) * std::size_t(h) * 3);
}

}  // namespace fen
