// bvh_traverse_ref.cpp — the kernels' traversal, re-expressed in scalar C++ (bvh_traverse_ref.h).
// Compiled with -ffp-contract=off (top-level CMakeLists.txt): no fused multiply-add, like the
// kernels' FP_CONTRACT OFF.
#include "bvh_traverse_ref.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fen {

namespace {

constexpr float kFarScale = 1.0000003576278687f;  // 1 + 2*gamma(3), as BVH_FAR_SCALE

struct Pre {
    float org[3];
    float idir[3];
    float tmin, tmax;
    int nearOff[3], farOff[3];
    int kx, ky, kz;
    float sx, sy, sz;
};

float safeRcp(float x)
{
    const float tiny = 1e-30f;
    return 1.0f / (std::fabs(x) > tiny ? x : std::copysign(tiny, x));
}

Pre setup(const RefRay& r, int w)
{
    Pre p;
    const float d[3] = {r.dir.x, r.dir.y, r.dir.z};
    for (int a = 0; a < 3; ++a) {
        p.org[a] = r.org[a];
        p.idir[a] = safeRcp(d[a]);
        const int neg = std::signbit(p.idir[a]) ? 1 : 0;
        p.nearOff[a] = (2 * a + neg) * w;
        p.farOff[a] = (2 * a + 1 - neg) * w;
    }
    p.tmin = r.tmin;
    p.tmax = r.tmax;
    const float ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
    const int kz = (ax >= ay) ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0.0f)
        std::swap(kx, ky);
    p.kx = kx;
    p.ky = ky;
    p.kz = kz;
    p.sx = d[kx] / d[kz];
    p.sy = d[ky] / d[kz];
    p.sz = 1.0f / d[kz];
    return p;
}

// One lane of tri_packet_intersect: t, or +inf on a miss.
float triLane(const dev::TriPacket4& pk, int lane, const Pre& r, float tmax, float* b1, float* b2)
{
    auto V = [&](int vtx, int axis) { return pk.v[(3 * vtx + axis) * 4 + lane]; };
    const float ox = r.org[r.kx], oy = r.org[r.ky], oz = r.org[r.kz];
    const float az = V(0, r.kz) - oz, bz = V(1, r.kz) - oz, cz = V(2, r.kz) - oz;
    const float ax = (V(0, r.kx) - ox) - r.sx * az;
    const float ay = (V(0, r.ky) - oy) - r.sy * az;
    const float bx = (V(1, r.kx) - ox) - r.sx * bz;
    const float by = (V(1, r.ky) - oy) - r.sy * bz;
    const float cx = (V(2, r.kx) - ox) - r.sx * cz;
    const float cy = (V(2, r.ky) - oy) - r.sy * cz;
    const float u = cx * by - cy * bx;
    const float w = bx * ay - by * ax;
    const float v = ax * cy - ay * cx;
    const bool neg = u < 0.0f || v < 0.0f || w < 0.0f;
    const bool pos = u > 0.0f || v > 0.0f || w > 0.0f;
    const float det = u + v + w;
    const float tsc = u * (r.sz * az) + v * (r.sz * bz) + w * (r.sz * cz);
    const float rcp = 1.0f / det;
    const float t = tsc * rcp;
    *b1 = v * rcp;
    *b2 = w * rcp;
    const bool ok = !(neg && pos) && det != 0.0f && t > r.tmin && t < tmax;
    return ok ? t : std::numeric_limits<float>::infinity();
}

// Slab test of all children; returns the hit mask, fills tnear.
unsigned slabTest(const FlatBvh& bvh, std::uint32_t node, const Pre& r, float tmax, float* tnear)
{
    const int w = bvh.width;
    const float* b = bvh.bounds(node);
    unsigned bits = 0;
    for (int k = 0; k < w; ++k) {
        float tn[3], tf[3];
        for (int a = 0; a < 3; ++a) {
            tn[a] = (b[r.nearOff[a] + k] - r.org[a]) * r.idir[a];
            tf[a] = (b[r.farOff[a] + k] - r.org[a]) * r.idir[a];
        }
        const float n = std::fmax(std::fmax(tn[0], tn[1]), std::fmax(tn[2], r.tmin));
        const float f = std::fmin(std::fmin(std::fmin(tf[0], tf[1]), tf[2]) * kFarScale, tmax);
        tnear[k] = n;
        if (n <= f)
            bits |= 1u << k;
    }
    return bits;
}

int lowestBit(unsigned bits) { return __builtin_ctz(bits); }

}  // namespace

dev::Hit traceClosestRef(const FlatBvh& bvh, const RefRay& ray)
{
    const Pre r = setup(ray, bvh.width);
    dev::Hit hit{r.tmax, 0.0f, 0.0f, FEN_INVALID_ID};
    std::uint32_t stackRef[FEN_BVH_STACK_SIZE];
    float stackT[FEN_BVH_STACK_SIZE];
    int sp = 0;
    std::uint32_t cur = 0;
    float tnear[8];
    for (;;) {
        if (!(cur & FEN_LEAF_BIT)) {
            unsigned bits = slabTest(bvh, cur, r, hit.t, tnear);
            const std::uint32_t* child = bvh.child(cur);
            if (bits != 0) {
                int k = lowestBit(bits);
                bits &= bits - 1;
                const std::uint32_t c0 = child[k];
                const float d0 = tnear[k];
                if (bits == 0) {
                    cur = c0;
                    continue;
                }
                k = lowestBit(bits);
                bits &= bits - 1;
                const std::uint32_t c1 = child[k];
                const float d1 = tnear[k];
                if (bits == 0) {
                    if (d1 < d0) {
                        stackRef[sp] = c0;
                        stackT[sp] = d0;
                        cur = c1;
                    } else {
                        stackRef[sp] = c1;
                        stackT[sp] = d1;
                        cur = c0;
                    }
                    ++sp;
                    continue;
                }
                const int base = sp;
                stackRef[sp] = c0;
                stackT[sp++] = d0;
                stackRef[sp] = c1;
                stackT[sp++] = d1;
                while (bits != 0) {
                    k = lowestBit(bits);
                    bits &= bits - 1;
                    stackRef[sp] = child[k];
                    stackT[sp++] = tnear[k];
                }
                for (int i = base + 1; i < sp; ++i) {
                    const std::uint32_t ci = stackRef[i];
                    const float di = stackT[i];
                    int j = i - 1;
                    while (j >= base && stackT[j] < di) {
                        stackRef[j + 1] = stackRef[j];
                        stackT[j + 1] = stackT[j];
                        --j;
                    }
                    stackRef[j + 1] = ci;
                    stackT[j + 1] = di;
                }
                cur = stackRef[--sp];
                continue;
            }
        } else {
            const dev::TriPacket4& p = bvh.packets[cur & ~FEN_LEAF_BIT];
            float t[4], b1[4], b2[4];
            for (int l = 0; l < 4; ++l)
                t[l] = triLane(p, l, r, hit.t, &b1[l], &b2[l]);
            const float tm = std::fmin(std::fmin(t[0], t[1]), std::fmin(t[2], t[3]));
            if (tm < hit.t) {
                int lane = 0;
                while (t[lane] != tm)
                    ++lane;
                hit.t = tm;
                hit.u = b1[lane];
                hit.v = b2[lane];
                hit.prim = p.prim[lane];
            }
        }
        for (;;) {
            if (sp == 0)
                return hit;
            --sp;
            if (stackT[sp] <= hit.t) {
                cur = stackRef[sp];
                break;
            }
        }
    }
}

bool traceAnyRef(const FlatBvh& bvh, const RefRay& ray)
{
    const Pre r = setup(ray, bvh.width);
    std::uint32_t stack[FEN_BVH_STACK_SIZE];
    int sp = 0;
    std::uint32_t cur = 0;
    float tnear[8];
    for (;;) {
        if (!(cur & FEN_LEAF_BIT)) {
            unsigned bits = slabTest(bvh, cur, r, r.tmax, tnear);
            const std::uint32_t* child = bvh.child(cur);
            if (bits != 0) {
                int k = lowestBit(bits);
                bits &= bits - 1;
                cur = child[k];
                while (bits != 0) {
                    k = lowestBit(bits);
                    bits &= bits - 1;
                    stack[sp++] = child[k];
                }
                continue;
            }
        } else {
            const dev::TriPacket4& p = bvh.packets[cur & ~FEN_LEAF_BIT];
            for (int l = 0; l < 4; ++l) {
                float b1, b2;
                if (triLane(p, l, r, r.tmax, &b1, &b2) < std::numeric_limits<float>::infinity())
                    return true;
            }
        }
        if (sp == 0)
            return false;
        cur = stack[--sp];
    }
}

BruteHit bruteForceClosest(const std::vector<Triangle>& tris, const RefRay& ray)
{
    BruteHit best;
    best.t = ray.tmax;
    const glm::dvec3 o(ray.org), d(ray.dir);
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const glm::dvec3 p0(tris[i].p0), p1(tris[i].p1), p2(tris[i].p2);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        if (glm::length(glm::cross(e1, e2)) == 0.0)
            continue;
        const glm::dvec3 pv = glm::cross(d, e2);
        const double det = glm::dot(e1, pv);
        if (det == 0.0)
            continue;
        const glm::dvec3 tv = o - p0;
        const double u = glm::dot(tv, pv) / det;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double v = glm::dot(d, qv) / det;
        const double t = glm::dot(e2, qv) / det;
        if (u < 0.0 || v < 0.0 || u + v > 1.0)
            continue;
        if (t > ray.tmin && t < best.t) {
            best.t = t;
            best.prim = static_cast<std::uint32_t>(i);
        }
    }
    return best;
}

}  // namespace fen
