// trace_support.h — helpers for the traversal tests: build a scene for one BVH width, trace on
// the device, and compare with the CPU reference (bit for bit) and brute force (double).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bvh_build.h"
#include "bvh_traverse_ref.h"
#include "support/cl_fixture.h"
#include "support/test_scenes.h"
#include "trace/device_bvh.h"

namespace fen { namespace test {

struct TracedScene {
    std::vector<Triangle> tris;
    FlatBvh flat;
    std::unique_ptr<DeviceBvh> dev;
    std::unique_ptr<RayQueries> queries;

    TracedScene(ocl::Context& ctx, std::vector<Triangle> t, int width)
        : tris(std::move(t)), flat(flattenBvh(buildBinnedSah(tris), tris, width))
    {
        dev = std::make_unique<DeviceBvh>(ctx, flat);
        queries = std::make_unique<RayQueries>(ctx, *dev);
    }
};

// Number of rays whose device result differs from the reference in any bit (t, u, v, prim, and
// the any-hit flag); the first few differences go to the test log.
std::size_t deviceVsReference(TracedScene& s, const std::vector<RefRay>& rays);

// Compares device closest hits with brute force: hit/miss and distance (1e-5 relative). Rays
// passing within 1e-5 (barycentric) of an edge of the triangles involved are "borderline"
// and counted apart. Returns the number of real disagreements.
struct BruteComparison {
    std::size_t disagreements = 0;
    std::size_t borderline = 0;
};
BruteComparison deviceVsBruteForce(TracedScene& s, const std::vector<RefRay>& rays);

} }  // namespace fen::test
