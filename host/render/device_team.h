// device_team.h — one render on several OpenCL devices of this process (`--device all` or a
// list; DESIGN.md §9): a thread per device, each running the render loop (renderer.h) on its own
// context as one member of a ThreadTeam (team/thread_team.h), sharing every pass's paths by
// measured speed. The result is member 0's, which holds the team's sums: the image one device
// gives when the devices compute alike.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "cl/context.h"
#include "render/renderer.h"

namespace fen {

// Renders on `devices` (two or more; member 0 first, which alone keeps `settings`' progress line,
// batch records, carry and scene cache). A member that fails ends the render: its error, naming
// its device, is thrown once every member has stopped.
RenderResult renderOnDevices(const std::vector<ocl::Context*>& devices, const Scene& scene,
                             const std::optional<Goniogram>& sky, const CameraSpec& camera, int width, int height,
                             const RenderSettings& settings);

}  // namespace fen
