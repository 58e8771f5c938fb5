// sky_tables.cpp — the sky's host and device tables (sky_tables.h).
#include "sky/sky_tables.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "shared/fen_render.h"
#include "util/error.h"

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
    appendSkySearch(t.theta);
    appendSkySearch(t.phi);
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

void appendSkySearch(std::vector<float>& nodes, std::uint32_t bucketsPerNode)
{
    const std::size_t n = nodes.size();
    if (n < 2)
        throw Error(cat("appendSkySearch: an axis of ", n, " nodes (a sky table has at least 2)"));
    // lib/sky.h sky_node_search's answer for a real x: the largest i < n - 1 with nodes[i] <= x
    // (0 when there is none)
    const auto answer = [&](double x) {
        const auto above = std::upper_bound(nodes.begin(), nodes.end(), x,
                                            [](double v, float node) { return v < static_cast<double>(node); });
        const std::size_t atOrBelow = static_cast<std::size_t>(above - nodes.begin());
        return static_cast<std::uint32_t>(std::min(atOrBelow == 0 ? 0 : atOrBelow - 1, n - 2));
    };
    const double last = nodes.back();
    const std::uint32_t buckets = bucketsPerNode * static_cast<std::uint32_t>(n);
    const float scale = static_cast<float>(buckets / last);
    // the device's bucket of x comes from x * scale in float: off from the exact one by rounding
    // (a few 1e-7 of x), far inside this margin
    const double margin = 1e-4 * last / buckets + 1e-6 * last;
    std::vector<std::uint32_t> search(FEN_SKY_SEARCH_HINTS + 2 * std::size_t{buckets});
    std::memcpy(&search[FEN_SKY_SEARCH_SCALE], &scale, 4);
    search[FEN_SKY_SEARCH_BUCKETS] = buckets;
    for (std::uint32_t b = 0; b < buckets; ++b) {
        const double x0 = b / static_cast<double>(scale) - margin;
        const double x1 = b + 1 == buckets ? std::numeric_limits<double>::infinity()
                                           : (b + 1) / static_cast<double>(scale) + margin;
        search[FEN_SKY_SEARCH_HINTS + 2 * b] = answer(x0);
        search[FEN_SKY_SEARCH_HINTS + 2 * b + 1] = std::min(answer(x1) + 1, static_cast<std::uint32_t>(n - 1));
    }
    const std::size_t at = nodes.size();
    nodes.resize(at + search.size());
    std::memcpy(&nodes[at], search.data(), search.size() * 4);
}

DeviceSky::DeviceSky(ocl::Context& ctx, const SkyTables& t)
    : theta(ctx.buffer(CL_MEM_READ_ONLY, t.theta.size() * 4, "sky nodes", t.theta.data())),
      phi(ctx.buffer(CL_MEM_READ_ONLY, t.phi.size() * 4, "sky nodes", t.phi.data())),
      values(ctx.buffer(CL_MEM_READ_ONLY, t.values.size() * 4, "sky luminances", t.values.data()))
{
}

}  // namespace fen
