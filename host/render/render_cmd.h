// render_cmd.h — `fenestra render`: runs a render with the options of render_options.h.
#pragma once

#include "render/render_options.h"

namespace fen {

// Returns the exit status: 0, or 130 when a signal stopped the render early (its outputs are
// written, for the batches finished).
int runRender(const RenderOptions& opt);

}  // namespace fen
