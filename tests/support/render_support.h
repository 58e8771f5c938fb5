// render_support.h — analytic test scenes built in code, and rendering them on the test device.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "scene/scene.h"
#include "sky/goniogram.h"

namespace fen { namespace test {

class SceneBuilder {
public:
    // Returns the material index.
    int material(const std::string& name, glm::vec3 albedo);
    int glass(const std::string& name, glm::vec3 transmission, float ior = 1.5f);
    // Adds triangles as one node (named `node`) of material `mat`; returns the node index.
    int add(const std::string& node, const std::vector<Triangle>& tris, int mat,
            PortalMark portal = PortalMark::None);
    // The sun at altitude/azimuth (degrees; DESIGN.md §1 convention), normal illuminance in lux.
    void sun(double altitudeDeg, double azimuthDeg, double lux, double angularRadiusDeg = 0.0);
    void uniformSky(double luminance);
    void cieSky(int type, double zenithLuminance, double sunAltitudeDeg, double sunAzimuthDeg);
    // A camera at `eye` looking at `target`; `up` is a hint.
    void camera(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up, double yfovDeg,
                const std::string& name = "camera");
    Scene build() const;

private:
    Scene scene_;
};

// Rectangle p, p+u, p+u+v, p+v as two triangles.
std::vector<Triangle> rect(glm::vec3 p, glm::vec3 u, glm::vec3 v);

// A table sky with strong variation and uneven nodes (theta 0, 10, 35, 60, 80, 90; phi 0, 45,
// 100, 180, 270, 360 degrees), coarse enough that each cell holds many samples; its cells from 45
// to 100 degrees of azimuth straddle the plane z = 0.
Goniogram unevenTableSky();

struct TestRender {
    RenderResult result;
    std::optional<Goniogram> sky;
};

// Renders with `paths` light paths in 16 batches (seed 1 unless given), tracking `rois`;
// `tweak` may change the other settings.
TestRender renderScene(ocl::Context& ctx, const Scene& scene, int width, int height,
                       std::uint64_t paths, std::vector<Roi> rois, std::uint32_t seed = 1,
                       int maxBounces = 1024, const std::function<void(RenderSettings&)>& tweak = {});

// Configuration factor from a differential horizontal element at `p` (facing +y) to the
// horizontal rectangle [x0,x1] x [z0,z1] at height y > p.y (Siegel & Howell's corner formula,
// superposed over the four corner rectangles).
double viewFactorToCeilingRect(glm::dvec3 p, double x0, double x1, double z0, double z1, double y);

// The world point a pixel centre sees on the plane y = planeY (camera from the scene).
glm::dvec3 pixelOnPlaneY(const CameraSpec& cam, int width, int height, double px, double py,
                         double planeY);

// The walls and ceiling of an S x S box of height h (x, z in [0, S]) whose ceiling has the
// opening [x0, x1] x [z0, z1]: the shell of the analytic "floor under an opening" scenes.
std::vector<Triangle> boxWithCeilingOpening(float S, float h, float x0, float x1, float z0, float z1);
// ... a square opening [o0, o1]^2.
inline std::vector<Triangle> boxWithCeilingOpening(float S, float h, float o0, float o1)
{
    return boxWithCeilingOpening(S, h, o0, o1, o0, o1);
}

// The mean over `roi` of the floor's exact luminance rho L F under that opening, lit by a uniform
// sky of luminance L, F each pixel's configuration factor to the opening.
double floorUnderOpeningMean(const CameraSpec& cam, int width, int height, const Roi& roi, double rho,
                             double skyL, float h, float o0, float o1);

} }  // namespace fen::test
