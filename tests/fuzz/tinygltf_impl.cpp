// tinygltf_impl.cpp — tinygltf's implementation, compiled into the fuzz target from Debian's
// tiny_gltf.h so that it is instrumented like the rest (tests/fuzz/CMakeLists.txt).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
