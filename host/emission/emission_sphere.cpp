// emission_sphere.cpp — the scene's bounding sphere, enlarged (emission_sphere.h).
#include "emission/emission_sphere.h"

namespace fen {

void emissionSphere(const Scene& scene, glm::dvec3* centre, double* radius_m)
{
    *centre = glm::dvec3(0.0);
    *radius_m = 0.0;
    const Aabb& b = scene.bounds;
    if (!b.empty()) {
        *centre = glm::dvec3(b.center());
        *radius_m = 0.5 * glm::length(glm::dvec3(b.extent()));
    }
    *radius_m = *radius_m * 1.001 + 1e-3;
}

}  // namespace fen
