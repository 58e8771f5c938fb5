// sky_tables.h — the scene's sky as tables (DESIGN.md §3.1): the goniogram's node angles,
// luminances and cell integrals on the host, and its nodes and luminances on the device
// (kernels/lib/sky.h), which the camera pass reads for the sky seen directly and the emission
// strategies for the sky they sample.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "cl/context.h"
#include "sky/goniogram.h"

namespace fen {

// A goniogram as the device reads it. With no sky: nodes counts 0, arrays hold one zero each
// (OpenCL buffers cannot be empty).
struct SkyTables {
    // theta, phi: each axis's node angles (rad; thetaNodes, phiNodes of them), then its search
    // buckets (kernels/shared/fen_render.h FEN_SKY_SEARCH_*); values: the luminances (cd/m^2)
    std::vector<float> theta, phi, values;
    std::vector<double> cellSin, cellFlat;  // per cell: ∫∫ g sin(theta), ∫∫ g (d theta d phi)
    std::uint32_t thetaNodes = 0, phiNodes = 0, cells = 0;
    double integral_cd_m2_sr = 0.0;         // ∫ g dω over the table (the ground's glow included)
    double maxLuminance_cd_m2 = 0.0;
};
SkyTables makeSkyTables(const std::optional<Goniogram>& sky);

// Appends to an axis's node angles (n >= 2, non-decreasing, from 0) the buckets that bound
// lib/sky.h's search (FEN_SKY_SEARCH_*): bucketsPerNode n of them over
// [0, the last node], each holding the search's answers at its ends, widened by a margin far
// beyond float rounding, so that every x the device files under the bucket has its answer inside.
void appendSkySearch(std::vector<float>& nodes, std::uint32_t bucketsPerNode = 4);

// The node angles and luminances of a SkyTables on the device (lib/sky.h), shared by the camera
// pass and the strategies that sample the scene's sky.
struct DeviceSky {
    DeviceSky(ocl::Context& ctx, const SkyTables& t);
    cl::Buffer theta, phi, values;
};

}  // namespace fen
