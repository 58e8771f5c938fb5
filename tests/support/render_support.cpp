// render_support.cpp — analytic scenes and test renders (render_support.h).
#include "support/render_support.h"

#include <cmath>
#include <cstdlib>

#include "render/camera_setup.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"

namespace fen { namespace test {

int SceneBuilder::material(const std::string& name, glm::vec3 albedo)
{
    Material m;
    m.name = name;
    m.albedo = albedo;
    scene_.materials.push_back(m);
    return static_cast<int>(scene_.materials.size() - 1);
}

int SceneBuilder::glass(const std::string& name, glm::vec3 transmission, float ior)
{
    Material m;
    m.name = name;
    m.glass = true;
    m.transmission = transmission;
    m.ior = ior;
    scene_.materials.push_back(m);
    return static_cast<int>(scene_.materials.size() - 1);
}

int SceneBuilder::add(const std::string& node, const std::vector<Triangle>& tris, int mat,
                      PortalMark portal)
{
    const auto idx = static_cast<std::uint32_t>(scene_.nodeNames.size());
    scene_.nodeNames.push_back(node);
    scene_.nodePortal.push_back(portal);
    for (const auto& t : tris) {
        scene_.triangles.push_back(t);
        scene_.triangleNode.push_back(idx);
        scene_.triangleMaterial.push_back(static_cast<std::uint32_t>(mat));
    }
    return static_cast<int>(idx);
}

void SceneBuilder::sun(double altitudeDeg, double azimuthDeg, double lux, double angularRadiusDeg)
{
    scene_.sun.present = true;
    scene_.sun.nodeName = "sun";
    scene_.sun.travelDirection = -skyDirection((90.0 - altitudeDeg) * M_PI / 180.0, azimuthDeg * M_PI / 180.0);
    scene_.sun.illuminanceRgb_lux = glm::dvec3(lux);
    scene_.sun.angularRadiusRad = angularRadiusDeg * M_PI / 180.0;
}

void SceneBuilder::uniformSky(double luminance)
{
    scene_.sky = SkySpec();
    scene_.sky.type = SkySpec::Type::Uniform;
    scene_.sky.where = "test sky";
    scene_.sky.luminance_cd_m2 = luminance;
}

void SceneBuilder::cieSky(int type, double zenithLuminance, double sunAltitudeDeg, double sunAzimuthDeg)
{
    scene_.sky = SkySpec();
    scene_.sky.type = SkySpec::Type::Cie;
    scene_.sky.where = "test sky";
    scene_.sky.cieType = type;
    scene_.sky.zenithLuminance_cd_m2 = zenithLuminance;
    scene_.sky.sunAltitudeDeg = sunAltitudeDeg;
    scene_.sky.sunAzimuthDeg = sunAzimuthDeg;
}

void SceneBuilder::camera(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up, double yfovDeg,
                          const std::string& name)
{
    CameraSpec c;
    c.nodeName = name;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    c.right = glm::normalize(glm::cross(c.forward, up));
    c.up = glm::cross(c.right, c.forward);
    c.yfovRad = yfovDeg * M_PI / 180.0;
    scene_.cameras.push_back(c);
}

Scene SceneBuilder::build() const
{
    Scene s = scene_;
    s.source = "test scene";
    s.bounds = Aabb();
    for (const auto& t : s.triangles) {
        s.bounds.grow(t.p0);
        s.bounds.grow(t.p1);
        s.bounds.grow(t.p2);
    }
    return s;
}

std::vector<Triangle> rect(glm::vec3 p, glm::vec3 u, glm::vec3 v)
{
    return {{p, p + u, p + u + v}, {p, p + u + v, p + v}};
}

Goniogram unevenTableSky()
{
    std::vector<double> th = {0, 10, 35, 60, 80, 90}, az = {0, 45, 100, 180, 270, 360};
    std::vector<std::vector<double>> lum;
    for (std::size_t i = 0; i < th.size(); ++i) {
        std::vector<double> row;
        for (std::size_t j = 0; j < az.size(); ++j)
            row.push_back(i == 0 ? 500.0 : 200.0 + 400.0 * ((i * 7 + (j % 5) * 3) % 5) + 100.0 * i);
        lum.push_back(row);
    }
    return tableSky(th, az, lum, "test table");
}

TestRender renderScene(ocl::Context& ctx, const Scene& scene, int width, int height,
                       std::uint64_t paths, std::vector<Roi> rois, std::uint32_t seed, int maxBounces,
                       const std::function<void(RenderSettings&)>& tweak)
{
    TestRender t;
    t.sky = buildSky(scene);
    RenderSettings s;
    s.paths = paths;
    s.batches = 16;
    // FEN_TEST_SEED adds to every test's seed: the tolerances must hold for any seed, and running
    // a few seeds separates a bias from noise that all tests share through one seed.
    if (const char* e = std::getenv("FEN_TEST_SEED"))
        seed += static_cast<std::uint32_t>(std::strtoul(e, nullptr, 10));
    s.seed = seed;
    s.maxBounces = maxBounces;
    s.rois = std::move(rois);
    if (tweak)
        tweak(s);
    Renderer r(ctx, scene, t.sky, scene.cameras.at(0), width, height, s);
    t.result = r.render();
    return t;
}

namespace {

// Corner formula: element below one corner of an a x b rectangle at distance c.
double cornerFactor(double a, double b, double c)
{
    if (a == 0.0 || b == 0.0)
        return 0.0;
    const double sa = std::copysign(1.0, a), sb = std::copysign(1.0, b);
    a = std::fabs(a) / c;
    b = std::fabs(b) / c;
    const double A = std::sqrt(1.0 + a * a), B = std::sqrt(1.0 + b * b);
    return sa * sb / (2.0 * M_PI) * (a / A * std::atan(b / A) + b / B * std::atan(a / B));
}

}  // namespace

std::vector<Triangle> boxWithCeilingOpening(float S, float h, float x0, float x1, float z0, float z1)
{
    std::vector<Triangle> w;
    for (const auto& r : {rect({0, 0, 0}, {S, 0, 0}, {0, h, 0}), rect({0, 0, S}, {S, 0, 0}, {0, h, 0}),
                          rect({0, 0, 0}, {0, 0, S}, {0, h, 0}), rect({S, 0, 0}, {0, 0, S}, {0, h, 0}),
                          // the ceiling around the opening
                          rect({0, h, 0}, {S, 0, 0}, {0, 0, z0}), rect({0, h, z1}, {S, 0, 0}, {0, 0, S - z1}),
                          rect({0, h, z0}, {x0, 0, 0}, {0, 0, z1 - z0}),
                          rect({x1, h, z0}, {S - x1, 0, 0}, {0, 0, z1 - z0})})
        w.insert(w.end(), r.begin(), r.end());
    return w;
}

double floorUnderOpeningMean(const CameraSpec& cam, int width, int height, const Roi& roi, double rho,
                             double skyL, float h, float o0, float o1)
{
    double sum = 0.0;
    for (int y = roi.y0; y < roi.y1; ++y)
        for (int x = roi.x0; x < roi.x1; ++x) {
            const glm::dvec3 p = pixelOnPlaneY(cam, width, height, x + 0.5, y + 0.5, 0.0);
            sum += rho * skyL * viewFactorToCeilingRect(p, o0, o1, o0, o1, h);
        }
    return sum / static_cast<double>(roi.pixels());
}

double viewFactorToCeilingRect(glm::dvec3 p, double x0, double x1, double z0, double z1, double y)
{
    const double c = y - p.y;
    const double ax0 = x0 - p.x, ax1 = x1 - p.x, az0 = z0 - p.z, az1 = z1 - p.z;
    // Signed superposition of the four rectangles with a corner above p.
    return cornerFactor(ax1, az1, c) - cornerFactor(ax0, az1, c) - cornerFactor(ax1, az0, c) +
           cornerFactor(ax0, az0, c);
}

glm::dvec3 pixelOnPlaneY(const CameraSpec& cam, int width, int height, double px, double py,
                         double planeY)
{
    const double tanY = std::tan(0.5 * cam.yfovRad), tanX = tanY * width / height;
    const double sx = (2.0 * px / width - 1.0) * tanX, sy = (1.0 - 2.0 * py / height) * tanY;
    const glm::dvec3 d = cam.forward + sx * cam.right + sy * cam.up;
    const double t = (planeY - cam.position.y) / d.y;
    return cam.position + t * d;
}

} }  // namespace fen::test
