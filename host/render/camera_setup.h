// camera_setup.h — image size and the device camera (DESIGN.md §1 "Camera", §6).
//
// Size: --width/--height win; with one given, the other follows the camera's aspectRatio (4:3
// when the file gives none); with neither, width 640. Pixels are square: the vertical field of
// view is the camera's yfov, the horizontal one follows from width / height.
#pragma once

#include "scene/scene.h"
#include "shared/fen_render.h"

namespace fen {

// width/height: 0 = not given. Errors name --width / --height.
void resolveImageSize(const CameraSpec& cam, int width, int height, int* outWidth, int* outHeight);

dev::DevCamera makeDevCamera(const CameraSpec& cam, int width, int height);

}  // namespace fen
