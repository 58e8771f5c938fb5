// stb_image_impl.cpp — stb_image's implementation compiled into the fuzz target, instrumented like
// the rest, so that the fuzzer reaches into the decoding of a scene's textures
// (host/scene/texture_image.cpp) rather than stopping at Debian's uninstrumented libstb.
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
