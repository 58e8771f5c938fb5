// render_cmd.h — `fenestra render`: runs a render with the options of render_options.h.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "render/render_options.h"

namespace fen {

namespace ocl {
class Context;
}
class DeviceSceneCache;
class Team;

// What a caller running many renders in one process (`fenestra batch`) shares with a render and
// learns from it. All optional.
struct RenderHooks {
    ocl::Context* context = nullptr;  // the device's context, made once (else the render makes its own)
    DeviceSceneCache* sceneCache = nullptr;  // device scenes of earlier renders on that context
    // Called once the inputs are read and before anything is rendered, with every file the render
    // read (scene, its buffers and textures, the reference, sensor points, weather, the checkpoint
    // it resumes) and its JSON output's path.
    std::function<void(const std::vector<std::string>& inputs, const std::string& jsonPath)> onInputs;
    // The members sharing the render (team/team.h); null: the process's (mpirun's ranks, or one).
    // A batch under mpirun renders each job on one rank: the team of one.
    Team* team = nullptr;
};

// Returns the exit status: 0, or 130 when a signal stopped the render early (its outputs are
// written, for the batches finished).
int runRender(const RenderOptions& opt, const RenderHooks& hooks = {});

}  // namespace fen
