// embree_tracer.h — Embree 3 as a yardstick for `fenestra bench` (never used to render).
//
// The same triangles and rays as the OpenCL kernels, traced with rtcIntersect1 / rtcOccluded1 on
// all CPU threads (one contiguous chunk of rays per thread), BVH quality MEDIUM (Embree's
// default). `robust`: RTC_SCENE_FLAG_ROBUST, the mode Embree offers against rays slipping
// between neighbouring triangles, the closest it comes to the watertight traversal fenestra gives
// (docs/bvh.md "Robustness"); without it, Embree's fastest. Compiled only when CMake finds
// libembree-dev (FEN_HAVE_EMBREE).
#pragma once

#ifdef FEN_HAVE_EMBREE

#include <memory>
#include <vector>

#include "geometry.h"
#include "shared/fen_bvh.h"

namespace fen {

class EmbreeTracer {
public:
    EmbreeTracer(const std::vector<Triangle>& tris, int threads, bool robust);
    ~EmbreeTracer();
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    double buildSeconds() const { return buildSeconds_; }
    std::string version() const;
    void closest(const std::vector<dev::Ray>& rays, std::vector<dev::Hit>& hits) const;
    void any(const std::vector<dev::Ray>& rays, std::vector<std::uint32_t>& occluded) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int threads_;
    double buildSeconds_ = 0.0;
};

}  // namespace fen

#endif
