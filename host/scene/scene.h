// scene.h — a scene as the renderer sees it (DESIGN.md §1, §6): a triangle soup with a material
// and a source glTF node per triangle, the sun, the sky, the cameras. Loaded from glTF by
// gltf_load.h or built procedurally (host/bench/room_scene.h).
// Invariants: triangles, triangleNode and triangleMaterial have one entry per triangle;
// triangleMaterial indexes materials; triangleNode indexes nodeNames (and nodePortal).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry.h"

namespace fen {

// A base-colour texture (glTF texture = image + sampler), decoded to 8-bit sRGB texels. The albedo
// at a point is baseColorFactor times the texel's linear value (DESIGN.md §1, "Textures").
enum class TextureWrap : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };  // glTF 10497, 33071, 33648
struct Texture {
    std::string name;                  // "images[2] 'floor.png'", for messages
    int width = 0, height = 0;         // texels; row 0 is the image's top row (glTF's v = 0)
    std::vector<std::uint8_t> rgb;     // width * height * 3 bytes, sRGB-encoded as in the file
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    bool nearest = false;              // sampler magFilter NEAREST (9728); else bilinear
};

// Two-sided Lambertian, or thin glass (DESIGN.md §1).
struct Material {
    std::string name;
    glm::vec3 albedo{1.0f};        // glTF baseColorFactor RGB (linear); glTF's default is white
    int texture = -1;              // Scene::textures index of its baseColorTexture, -1: none
    int texCoord = 0;              // the TEXCOORD_n set the texture is read with
    bool glass = false;            // KHR_materials_transmission with transmissionFactor > 0
    glm::vec3 transmission{0.0f};  // glass: transmissionFactor * baseColorFactor
    float ior = 1.5f;              // KHR_materials_ior
};

// The sun: a KHR_lights_punctual directional light.
struct Sun {
    bool present = false;
    std::string nodeName;
    glm::dvec3 travelDirection{0.0, -1.0, 0.0};  // unit: the node's -z in world space
    glm::dvec3 illuminanceRgb_lux{0.0};          // intensity (lux, normal illuminance) * color
    double angularRadiusRad = 0.0;               // light.extras.angular_radius_deg; 0 = parallel
};

// scenes[i].extras.sky as written in the file; host/sky/sky_spec.h turns it into a goniogram.
struct SkySpec {
    enum class Type { None, Uniform, Cie, Table, Perez };
    Type type = Type::None;
    std::string where;  // "file: scenes[0].extras.sky", for errors found later
    double luminance_cd_m2 = 0.0;  // uniform
    int cieType = 0;               // cie
    double zenithLuminance_cd_m2 = 0.0, sunAltitudeDeg = 0.0, sunAzimuthDeg = 0.0;
    double perezEpsilon = 1.0, perezDelta = 0.0, diffuseHorizontal_lux = 0.0;  // perez (sun: as cie)
    bool illuminanceFromFile = true;  // perez: the weather file's lux, or its irradiance times an efficacy
    std::vector<double> zenithDeg, azimuthDeg;  // table
    std::vector<std::vector<double>> table_cd_m2;
    // Any type: the ground's albedo (0..1; 0: off, a black lower hemisphere). Below the horizon
    // the sky then glows uniformly at rho_g E_h / pi (Radiance gensky's ground), E_h the
    // horizontal illuminance of this sky and the scene's sun (sky/sky_spec.h).
    double groundAlbedo = 0.0;
};

// A glTF perspective camera placed by its node (looks along -z, +y up, +x right).
struct CameraSpec {
    std::string nodeName;
    std::string cameraName;
    glm::dvec3 position{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0}, up{0.0, 1.0, 0.0}, right{1.0, 0.0, 0.0};  // orthonormal
    double yfovRad = 0.0;
    double aspectRatio = 0.0;  // 0: not given in the file
};

enum class PortalMark { None, Panes, Hull };  // node.extras.portal: absent, true, "hull"

// A node marked `extras.sensor` (host/sensor/sensor_set.h): its triangles measure light and are
// not part of the scene's geometry (a sensor blocks nothing).
struct SensorMesh {
    std::string name;     // the node's name, or "node N"
    std::string source;   // "room.gltf: nodes[3] 'desk'", for messages
    double cell_m = 0.1;  // the side of its cells
    std::vector<Triangle> triangles;  // world space
};  // node.extras.portal: absent, true, "hull"

struct Scene {
    std::string source;                        // file path, or a name for procedural scenes
    std::vector<Triangle> triangles;           // world space, metres
    std::vector<std::uint32_t> triangleNode;   // glTF node index of each triangle
    std::vector<std::uint32_t> triangleMaterial;
    std::vector<std::string> nodeNames;        // per glTF node ("" when unnamed)
    std::vector<PortalMark> nodePortal;        // per glTF node
    std::vector<int> nodeParent;               // per glTF node; -1 for a root (or unknown)
    std::vector<Material> materials;           // never empty once loaded
    std::vector<Texture> textures;             // base-colour textures that some material uses
    // Texture coordinates (u, v) of each triangle's three vertices, when any material has a texture
    // (empty otherwise); zero for a triangle whose material has none.
    std::vector<std::array<glm::vec2, 3>> triangleUv;
    Sun sun;
    SkySpec sky;
    std::vector<CameraSpec> cameras;           // in scene traversal order
    std::vector<SensorMesh> sensorMeshes;      // nodes marked extras.sensor, in traversal order
    std::vector<std::string> warnings;         // ignored features worth telling the user
    std::vector<std::string> files;            // the files it was read from: the scene's, then its buffers' and images'
    Aabb bounds;
};

// The names of the nodes that carry triangles, sorted, quoted and comma-separated ("node N" for an
// unnamed one): what an error about a node name that is not there lists (gltf_load.cpp).
std::string nodesWithGeometry(const Scene& scene);

}  // namespace fen

