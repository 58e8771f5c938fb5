// sky_tables.cpp — the sky's host and device tables (sky_tables.h).
#include "sky/sky_tables.h"

#include <algorithm>

namespace fen {

SkyTables makeSkyTables(const std::optional<Goniogram>& sky)
{
    SkyTables t;
    if (!sky || sky->integral() <= 0.0) {
        t.theta = t.phi = t.values = {0.0f};
        return t;
    }
    const Goniogram& g = *sky;
    t.thetaNodes = static_cast<std::uint32_t>(g.thetaCount());
    t.phiNodes = static_cast<std::uint32_t>(g.phiCount());
    t.cells = (t.thetaNodes - 1) * (t.phiNodes - 1);
    for (double th : g.theta())
        t.theta.push_back(static_cast<float>(th));
    for (double ph : g.phi())
        t.phi.push_back(static_cast<float>(ph));
    for (double v : g.values()) {
        t.values.push_back(static_cast<float>(v));
        t.maxLuminance_cd_m2 = std::max(t.maxLuminance_cd_m2, v);
    }
    for (std::uint32_t i = 0; i + 1 < t.thetaNodes; ++i)
        for (std::uint32_t j = 0; j + 1 < t.phiNodes; ++j) {
            t.cellSin.push_back(g.cellIntegralSin(i, j));
            t.cellFlat.push_back(g.cellIntegralFlat(i, j));
            t.integral_cd_m2_sr += t.cellSin.back();
        }
    return t;
}

DeviceSky::DeviceSky(ocl::Context& ctx, const SkyTables& t)
    : theta(ctx.buffer(CL_MEM_READ_ONLY, t.theta.size() * 4, "sky nodes", t.theta.data())),
      phi(ctx.buffer(CL_MEM_READ_ONLY, t.phi.size() * 4, "sky nodes", t.phi.data())),
      values(ctx.buffer(CL_MEM_READ_ONLY, t.values.size() * 4, "sky luminances", t.values.data()))
{
}

}  // namespace fen
