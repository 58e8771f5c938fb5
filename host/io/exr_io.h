// exr_io.h — OpenEXR files of linear RGB, 32-bit float per channel (the render's output, and the
// --reference input). Errors are fen::Error naming the file.
#pragma once

#include <string>

#include "io/image.h"

namespace fen {

// The image as the bytes of an EXR file (written by io/output_files.h, atomically).
std::string encodeExr(const Image& image);
// Reads R, G, B (any pixel type; a luminance-only Y file gives grey). The data window's origin is
// ignored: pixel (0,0) is its top-left corner.
Image readExr(const std::string& path);

}  // namespace fen
