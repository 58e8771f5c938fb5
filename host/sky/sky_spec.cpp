// sky_spec.cpp — SkySpec to Goniogram (sky_spec.h).
#include "sky/sky_spec.h"

#include "sky/cie_sky.h"

namespace fen {

std::optional<Goniogram> buildSky(const SkySpec& spec)
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
    }
    return std::nullopt;
}

}  // namespace fen
