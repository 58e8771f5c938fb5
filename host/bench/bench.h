// bench.h — `fenestra bench`: traversal throughput of the OpenCL kernels, against Embree.
#pragma once

#include <string>
#include <vector>

namespace fen {

struct BenchOptions {
    std::string scenePath;           // "" = the procedural room
    std::string device;              // --device
    std::vector<int> widths;         // BVH layouts to measure; empty = the device's default
    std::size_t rays = 1u << 22;
    int runs = 5;
    int warmup = 1;
    std::uint64_t seed = 1;
    bool embree = true;
    bool sweepQuality = false;       // also build the full-sweep SAH tree and compare costs
    bool json = false;
    bool render = false;             // also render the scene, interleaved, and compare rays/s
    std::uint64_t renderPaths = 0;   // 0: render for renderSeconds instead
    double renderSeconds = 20.0;     // long enough to be steady (batches, learning, caches)
    std::string renderMethod = "uniform";
    std::string kernels;             // "" = the device's default (renderer.h)
};

int runBench(const BenchOptions& opt);

}  // namespace fen
