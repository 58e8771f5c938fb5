// emit_probe.h — an emission strategy's emitter run alone, for the kernel-level sampling tests
// (tests/kernels/*_sampling_test.cpp): the per-batch parameters emission reads, and a probe kernel
// of the shape (params, beta, org, dir, n, the strategy's arguments) launched over n paths.
#pragma once

#include <cstdint>
#include <vector>

#include "cl/context.h"
#include "sky/sky_tables.h"
#include "emission/strategy.h"
#include "scene/scene.h"
#include "shared/fen_render.h"

namespace fen { namespace test {

// What emission reads of RenderParams for `scene`: its bounding sphere, a parallel sun's
// direction, the sky's node counts and the seed; no table-pick lattice (each path's own bits).
dev::RenderParams emissionParams(const Scene& scene, const SkyTables& sky, std::uint32_t seed);

struct EmittedPaths {
    std::vector<cl_float4> beta, org, dir;  // per path, as the probe wrote them
};

// Runs `kernel` (named `name`) over paths 0..n-1 with `strategy`'s arguments bound after the five
// of the probe.
EmittedPaths runEmitProbe(ocl::Context& ctx, cl::Kernel& kernel, const char* name, EmissionStrategy& strategy,
                          const dev::RenderParams& params, std::uint32_t n);

} }  // namespace fen::test
