// checkpoint.h — a render saved between two batches, to be continued later (README "Nothing
// lost"): `--checkpoint PATH` writes one, `--resume PATH` continues from it, and the image is
// bit-identical to a render that was never stopped.
//
// A checkpoint holds what the next batches depend on and nothing that can be recomputed: the
// index of the next path (random numbers are keyed by it), the batch statistics' sums, the
// counters, the emission strategy's learned state (emission/strategy.h saveState), and a piece of
// the caller's state (the progress records). Its header names the fenestra build that wrote it
// and a fingerprint of the render -- scene content, image, camera, seed, paths or time, method
// and every emission option, device, BVH layout -- and resuming under any other build or
// fingerprint is refused with one line naming the first difference. A checksum over the whole
// file turns a truncated or altered file into an error, not a wrong image.
//
// Layout: "FENESTRA CHECKPOINT 1\n", the header as one line of JSON, the payload's length
// (8 bytes, little-endian), the payload (io/state_io.h), an FNV-1a 64 checksum of all before it.
// Written like every output (io/output_files.h): temporary file, fsync, rename.
#pragma once

#include "io/state_io.h"
#include "render/path_loop.h"

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace fen {

// This build: the version and a hash of the running executable, so that a checkpoint is only
// ever continued by the code that started it.
std::string buildId();

// A hash of everything in the scene that light transport reads.
std::uint64_t sceneHash(const Scene& scene);
// ... of its geometry, materials and textures alone (what a DeviceScene holds; not its sun or sky).
std::uint64_t geometryHash(const Scene& scene);

void writeCheckpoint(const std::string& path, const nlohmann::json& fingerprint, const std::string& payload);

// The payload of the checkpoint at `path`, after checking its integrity, its build and that its
// fingerprint equals `fingerprint` (fen::Error naming the file and the first key that differs).
std::string readCheckpoint(const std::string& path, const nlohmann::json& fingerprint);
// The same from a checkpoint's bytes (also the checkpoint fuzz target's entry); `path` names it.
std::string checkpointPayload(const std::string& bytes, const std::string& path, const nlohmann::json& fingerprint);

// Whether `path` may receive a checkpoint: it does not exist, or it is a regular file that starts
// as a checkpoint does (never a scene, an image or anything else a typo names). Throws fen::Error
// naming `option` otherwise.
void requireCheckpointTarget(const std::string& path, const std::string& option);

// Where a render's batch loop stands: with the film's and the strategy's state, a checkpoint's
// payload (in this order: loop, film, strategy, carry).
struct LoopState {
    std::uint64_t base = 0, perBatch = 0;  // next path index; paths per batch
    int done = 0;                          // batches counted
    double renderSeconds = 0.0;            // counted batches, before this process
    double calibrationSeconds = 0.0;
    BatchCounts counts;
};

// What a render's settings require of a loop state: --paths (0 with --time) and the batches.
struct LoopRules {
    std::uint64_t paths = 0;
    int batches = 16;
};

void writeLoopState(StateWriter& w, const LoopState& l);
// Reads the loop state and checks it means something for this render (a checkpoint edited and
// checksummed again must not hang it or count what was not traced); fails through `in`.
void readLoopState(StateReader& in, const LoopRules& rules, LoopState* l);

}  // namespace fen
