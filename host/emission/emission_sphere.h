// emission_sphere.h — the sphere every emitted path starts outside of (DESIGN.md §3): the scene's
// bounding sphere, a little larger. Rays must start outside it (RenderParams.sphere), the
// adaptive strategy's emission disk must cover every triangle's projection, and the first-bounce
// guide's lattice covers it.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace fen {

void emissionSphere(const Scene& scene, glm::dvec3* centre, double* radius_m);

}  // namespace fen
