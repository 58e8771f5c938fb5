// sky_spec.cpp — SkySpec to Goniogram, with the ground's glow (sky_spec.h).
#include "sky/sky_spec.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "io/image.h"
#include "sky/cie_sky.h"
#include "sky/perez_sky.h"
#include "util/error.h"

namespace fen {

namespace {

std::optional<Goniogram> skyAlone(const SkySpec& spec)
{
    switch (spec.type) {
    case SkySpec::Type::None:
        return std::nullopt;
    case SkySpec::Type::Uniform:
        return uniformSky(spec.luminance_cd_m2, spec.where);
    case SkySpec::Type::Cie:
        return cieSky(spec.cieType, spec.zenithLuminance_cd_m2, spec.sunAltitudeDeg,
                      spec.sunAzimuthDeg, spec.where);
    case SkySpec::Type::Table:
        return tableSky(spec.zenithDeg, spec.azimuthDeg, spec.table_cd_m2, spec.where);
    case SkySpec::Type::Perez:
        return perezSky({spec.perezEpsilon, spec.perezDelta}, spec.diffuseHorizontal_lux, spec.sunAltitudeDeg,
                        spec.sunAzimuthDeg, spec.where);
    }
    return std::nullopt;
}

}  // namespace

void checkGroundAlbedo(double albedo, const std::string& what)
{
    if (!(albedo >= 0.0 && albedo <= 1.0))
        throw Error(cat(what, ": ", albedo, " is outside [0, 1] (0: no ground glow)"));
}

double groundHorizontalIlluminance(const Goniogram& sky, const Sun& sun)
{
    double E = sky.illuminance(glm::dvec3(0.0, 1.0, 0.0));  // a ground's rows add nothing facing up
    if (sun.present && glm::length(sun.travelDirection) > 0.0) {
        // A disk sun's directions spread over its cone with the normal illuminance kept, so a
        // horizontal plane receives E_n times the sine of the axis's altitude (the cone's mean
        // direction is its axis).
        const glm::dvec3 e = sun.illuminanceRgb_lux;
        E += luminance(e.r, e.g, e.b) * std::max(0.0, -glm::normalize(sun.travelDirection).y);
    }
    return E;
}

std::optional<Goniogram> buildSky(const SkySpec& spec)
{
    if (spec.groundAlbedo != 0.0)
        throw Error(cat(spec.where, ".ground_albedo: the ground's glow needs the scene's sun (buildSky(scene))"));
    return skyAlone(spec);
}

std::optional<Goniogram> buildSky(const Scene& scene)
{
    const SkySpec& spec = scene.sky;
    std::optional<Goniogram> sky = skyAlone(spec);
    checkGroundAlbedo(spec.groundAlbedo, spec.where + ".ground_albedo");
    if (!sky || spec.groundAlbedo == 0.0)
        return sky;  // the table as it always was
    const double E = groundHorizontalIlluminance(*sky, scene.sun);
    return sky->withGround(spec.groundAlbedo * E / M_PI, spec.where + ".ground_albedo");
}

}  // namespace fen
