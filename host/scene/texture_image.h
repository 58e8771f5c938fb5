// texture_image.h — a glTF image's bytes (PNG or JPEG, as glTF allows) decoded into a base-colour
// Texture's 8-bit sRGB texels (scene.h), with the bounds an untrusted file needs: the size is read
// from the header and checked before anything is decoded.
// Invariant: a returned texture has 1..kMaxTextureSide texels a side and width * height * 3 bytes.
#pragma once

#include <cstddef>
#include <string>

#include "scene/scene.h"

namespace fen {

constexpr int kMaxTextureSide = 16384;
// All textures of a scene together, in texels (4 bytes each on the device: 1 GiB).
constexpr std::size_t kMaxTextureTexels = std::size_t{1} << 28;

// Decodes `bytes` into texture->rgb, ->width, ->height; `texture->name` names the image in
// the one-line errors ("room.gltf: images[2] 'floor.png': not a PNG or JPEG image (...)").
void decodeTextureImage(const unsigned char* bytes, std::size_t size, const std::string& where, Texture* texture);

}  // namespace fen
