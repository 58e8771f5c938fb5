// embree_tracer.cpp — Embree 3 closest/any-hit over a ray buffer (embree_tracer.h).
#ifdef FEN_HAVE_EMBREE

#include "bench/embree_tracer.h"

#include <chrono>
#include <thread>

#include <embree3/rtcore.h>

#include "util/error.h"

namespace fen {

struct EmbreeTracer::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
};

EmbreeTracer::EmbreeTracer(const std::vector<Triangle>& tris, int threads, bool robust)
    : impl_(std::make_unique<Impl>()), threads_(threads)
{
    const std::string config = cat("threads=", threads);
    impl_->device = rtcNewDevice(config.c_str());
    if (!impl_->device)
        throw Error("Embree: cannot create a device");
    const auto t0 = std::chrono::steady_clock::now();
    impl_->scene = rtcNewScene(impl_->device);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_MEDIUM);
    if (robust)
        rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t n = tris.size();
    // Embree reads vertex buffers 16 bytes at a time: the buffer it allocates is padded.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                         RTC_FORMAT_FLOAT3, 12, 3 * n));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                              RTC_FORMAT_UINT3, 12, n));
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3* p[3] = {&tris[i].p0, &tris[i].p1, &tris[i].p2};
        for (int k = 0; k < 3; ++k) {
            v[9 * i + 3 * k + 0] = p[k]->x;
            v[9 * i + 3 * k + 1] = p[k]->y;
            v[9 * i + 3 * k + 2] = p[k]->z;
            idx[3 * i + k] = static_cast<unsigned>(3 * i + k);
        }
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(impl_->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(impl_->scene);
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeTracer::~EmbreeTracer()
{
    if (impl_->scene)
        rtcReleaseScene(impl_->scene);
    if (impl_->device)
        rtcReleaseDevice(impl_->device);
}

std::string EmbreeTracer::version() const
{
    return cat(RTC_VERSION_MAJOR, ".", RTC_VERSION_MINOR, ".", RTC_VERSION_PATCH);
}

namespace {

template <class F>
void parallelChunks(std::size_t n, int threads, F&& f)
{
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
        const std::size_t b = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
        const std::size_t e = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
        pool.emplace_back([&f, b, e] { f(b, e); });
    }
    for (auto& th : pool)
        th.join();
}

void toEmbree(const dev::Ray& in, RTCRay& r)
{
    r.org_x = in.org_tmin.x;
    r.org_y = in.org_tmin.y;
    r.org_z = in.org_tmin.z;
    r.tnear = in.org_tmin.w;
    r.dir_x = in.dir_tmax.x;
    r.dir_y = in.dir_tmax.y;
    r.dir_z = in.dir_tmax.z;
    r.tfar = in.dir_tmax.w;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
}

}  // namespace

void EmbreeTracer::closest(const std::vector<dev::Ray>& rays, std::vector<dev::Hit>& hits) const
{
    hits.resize(rays.size());
    RTCScene scene = impl_->scene;
    parallelChunks(rays.size(), threads_, [&](std::size_t b, std::size_t e) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (std::size_t i = b; i < e; ++i) {
            RTCRayHit rh;
            toEmbree(rays[i], rh.ray);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &ctx, &rh);
            dev::Hit& h = hits[i];
            h.t = rh.ray.tfar;
            h.u = rh.hit.u;
            h.v = rh.hit.v;
            h.prim = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? FEN_INVALID_ID : rh.hit.primID;
        }
    });
}

void EmbreeTracer::any(const std::vector<dev::Ray>& rays, std::vector<std::uint32_t>& occluded) const
{
    occluded.resize(rays.size());
    RTCScene scene = impl_->scene;
    parallelChunks(rays.size(), threads_, [&](std::size_t b, std::size_t e) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (std::size_t i = b; i < e; ++i) {
            RTCRay r;
            toEmbree(rays[i], r);
            rtcOccluded1(scene, &ctx, &r);
            occluded[i] = r.tfar < 0.0f ? 1u : 0u;  // Embree sets tfar = -inf on a hit
        }
    });
}

}  // namespace fen

#endif
