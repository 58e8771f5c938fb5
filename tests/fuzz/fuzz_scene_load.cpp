// fuzz_scene_load.cpp — libFuzzer entry: any bytes, as a .gltf or a .glb, through the whole scene
// loader (GLB framing, nesting scan, JSON checks, URI resolution, tinygltf, the scene walk).
//
// The one acceptable outcome besides a scene is fen::Error (a one-line message naming the file):
// any other exception escapes and libFuzzer reports it, as it does a crash, a hang or a sanitizer
// report. External URIs resolve inside tests/fuzz/files/ (a .bin the seeds name, a folder, a
// symlink that leads out of it), so the refusals are exercised too. Usage: scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/gltf_load.h"
#include "fuzz_checks.h"
#include "util/error.h"

using fen::fuzz::requireOneLine;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        const fen::Scene scene = fen::loadGltfFromMemory(data, size, "fuzz.gltf", FEN_FUZZ_FILES);
        for (const std::string& w : scene.warnings)
            requireOneLine(w);
    } catch (const fen::Error& e) {
        requireOneLine(e.what());
    }
    return 0;
}
