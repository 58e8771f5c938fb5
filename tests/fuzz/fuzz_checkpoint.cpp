// fuzz_checkpoint.cpp — libFuzzer entry: any bytes as a checkpoint to --resume, through what reads
// one before the device is involved: the framing (magic, header line, length, checksum), the
// header's build and fingerprint (render/checkpoint.h), then the payload's loop state, with its
// checks against the render's settings, the film's statistics (render/film.h) and the camera
// pass's samples (render/camera_sampler.h), then the caller's carried JSON.
//
// The checksum is made right for every input before it is read, as an edit whose checksum was
// recomputed would be: so the mutations reach the payload, which is the point. The first byte
// chooses: even, the input is a whole checkpoint file; odd, it is the payload alone, framed here
// with this build's header and the fingerprint below. Acceptable outcomes: a state that passes,
// or a one-line fen::Error. Usage: scripts/fuzz.sh --target checkpoint.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "io/state_io.h"
#include "render/camera_sampler.h"
#include "render/checkpoint.h"
#include "render/film.h"
#include "fuzz_checks.h"
#include "util/error.h"

namespace {

using fen::fuzz::requireOneLine;

std::string le64(std::uint64_t v)
{
    std::string s(8, '\0');
    for (int i = 0; i < 8; ++i)
        s[static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xffu);
    return s;
}

std::uint64_t fnv(const std::string& b, std::size_t n)
{
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = 0; i < n; ++i)
        h = (h ^ static_cast<unsigned char>(b[i])) * 1099511628211ull;
    return h;
}

const nlohmann::json& fingerprint()
{
    static const nlohmann::json f = {{"scene", "0123456789abcdef"}, {"width", 8}, {"height", 6}, {"seed", 1},
                                     {"paths", 4096}, {"batches", 4}, {"method", "uniform"}};
    return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 1 || size > (1u << 20))
        return 0;
    std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    if (data[0] & 1u) {
        const nlohmann::json header = {{"build", fen::buildId()}, {"fingerprint", fingerprint()}};
        bytes = "FENESTRA CHECKPOINT 1\n" + header.dump() + "\n" + le64(bytes.size()) + bytes;
        bytes += le64(fnv(bytes, bytes.size()));
    } else if (bytes.size() >= 8) {
        bytes.replace(bytes.size() - 8, 8, le64(fnv(bytes, bytes.size() - 8)));
    }
    try {
        const std::string payload = fen::checkpointPayload(bytes, "fuzz.ckpt", fingerprint());
        fen::StateReader in(payload, "fuzz.ckpt");
        fen::LoopState loop;
        fen::readLoopState(in, {4096, 4}, &loop);
        fen::BatchStatistics stats(8, 6, {fen::Roi{0, 0, 8, 6}});
        stats.load(in);
        if (stats.batches() != loop.done)
            in.fail("film.batches", "does not match loop.done");
        fen::CameraSampler camera(8 * 6, 1, fen::CameraPassMode::Balanced);
        camera.load(in);
        // (the strategy's state comes next: it needs the strategy, and the strategy a device)
    } catch (const fen::Error& e) {
        requireOneLine(e.what());
    }
    return 0;
}
