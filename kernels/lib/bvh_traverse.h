/* bvh_traverse.h — closest-hit and any-hit traversal of a 2-, 4- or 8-wide BVH
 * (BvhNode2 / BvhNode4 / BvhNode8 of shared/fen_bvh.h), one work-item per ray.
 *
 * All children of a node are slab-tested at once with float2/4/8 operations (PoCL turns them
 * into SSE/AVX instructions; on a GPU they are plain scalar code). Robustness: the far distance is
 * scaled by 1 + 2*gamma(3) (Ize, "Robust BVH Ray Traversal", JCGT 2013), so rounding in the slab
 * test never culls a box that holds the hit -- a flat box around an axis-aligned wall included.
 * Closest hit visits children nearest first and keeps each pushed child's entry distance so a
 * subtree farther than the current hit is skipped when popped. The stack bound
 * FEN_BVH_STACK_SIZE is proven on the host for each tree (bvh/bvh_flat.cpp).
 * Requires FEN_BVH_WIDTH (2, 4 or 8) to be defined before inclusion.
 */
#ifndef FEN_BVH_TRAVERSE_H
#define FEN_BVH_TRAVERSE_H

#include "lib/tri_packet.h"

#if FEN_BVH_WIDTH == 8
typedef BvhNode8 BvhNode;
typedef float8 bvh_floatw;
typedef int8 bvh_intw;
#define BVH_LOADW vload8
#define BVH_STOREW vstore8
#define BVH_LANE_BITS_PORTABLE(m)                                                                 \
    ((uint)(((m).s0 & 1) | ((m).s1 & 2) | ((m).s2 & 4) | ((m).s3 & 8) | ((m).s4 & 16) |          \
            ((m).s5 & 32) | ((m).s6 & 64) | ((m).s7 & 128)))
#if defined(__clang__) && defined(__AVX__)
/* One vmovmskps instead of an 8-instruction OR reduction (measured: any-hit +15 % on PoCL). */
#define BVH_LANE_BITS(m) ((uint)__builtin_ia32_movmskps256(as_float8(m)))
#endif
#elif FEN_BVH_WIDTH == 4
typedef BvhNode4 BvhNode;
typedef float4 bvh_floatw;
typedef int4 bvh_intw;
#define BVH_LOADW vload4
#define BVH_STOREW vstore4
#define BVH_LANE_BITS_PORTABLE(m) ((uint)(((m).s0 & 1) | ((m).s1 & 2) | ((m).s2 & 4) | ((m).s3 & 8)))
#if defined(__clang__) && defined(__SSE__)
#define BVH_LANE_BITS(m) ((uint)__builtin_ia32_movmskps(as_float4(m)))
#endif
#elif FEN_BVH_WIDTH == 2
typedef BvhNode2 BvhNode;
typedef float2 bvh_floatw;
typedef int2 bvh_intw;
#define BVH_LOADW vload2
#define BVH_STOREW vstore2
#define BVH_LANE_BITS_PORTABLE(m) ((uint)(((m).s0 & 1) | ((m).s1 & 2)))
#else
#error "FEN_BVH_WIDTH must be 2, 4 or 8"
#endif
#ifndef BVH_LANE_BITS
#define BVH_LANE_BITS(m) BVH_LANE_BITS_PORTABLE(m)
#endif

/* max/min without NaN handling: operands here are finite or +-inf, never NaN (safe reciprocal,
   finite origins), and OpenCL's fmax/fmin cost three instructions each for NaN semantics we do
   not need, while max/min are undefined for infinities (OpenCL C 1.2 §6.12.4). */
#define BVH_VMAX(a, b) select((b), (a), (a) > (b))
#define BVH_VMIN(a, b) select((b), (a), (a) < (b))

/* 1 + 2*gamma(3), gamma(n) = n*eps/(1 - n*eps), eps = 2^-24 */
#define BVH_FAR_SCALE 1.0000003576278687f

static inline int bvh_lowest_bit(uint bits)
{
    return 31 - (int)clz(bits & (0u - bits));
}

/* Slab test of every child of node `n` against (r->tmin, tmax): bit k of the result is set when
   child k is hit; its entry distance is tnear[k]. */
static inline uint bvh_wide_test(const global BvhNode* n, const RayPre* r, float tmax,
                                 float* tnear)
{
    const global float* b = n->bounds;
    const bvh_floatw tnx = (BVH_LOADW(0, b + r->near_x) - r->org.x) * r->idir.x;
    const bvh_floatw tny = (BVH_LOADW(0, b + r->near_y) - r->org.y) * r->idir.y;
    const bvh_floatw tnz = (BVH_LOADW(0, b + r->near_z) - r->org.z) * r->idir.z;
    const bvh_floatw tfx = (BVH_LOADW(0, b + r->far_x) - r->org.x) * r->idir.x;
    const bvh_floatw tfy = (BVH_LOADW(0, b + r->far_y) - r->org.y) * r->idir.y;
    const bvh_floatw tfz = (BVH_LOADW(0, b + r->far_z) - r->org.z) * r->idir.z;
    const bvh_floatw tn = BVH_VMAX(BVH_VMAX(tnx, tny), BVH_VMAX(tnz, (bvh_floatw)(r->tmin)));
    const bvh_floatw tf =
        BVH_VMIN(BVH_VMIN(BVH_VMIN(tfx, tfy), tfz) * BVH_FAR_SCALE, (bvh_floatw)(tmax));
    BVH_STOREW(tn, 0, tnear);
    const bvh_intw m = tn <= tf;
    return BVH_LANE_BITS(m);
}

/* Closest hit along the ray, or hit.prim == FEN_INVALID_ID. *packet_lane = packet index * 4 + lane
   of the hit, so a caller can read the triangle's vertices from the packet it just tested (in
   cache) instead of a per-primitive array (a cache miss). */
static inline Hit bvh_intersect_closest_at(const global BvhNode* nodes,
                                           const global TriPacket4* packets, const RayPre* r,
                                           uint* packet_lane)
{
    Hit hit;
    hit.t = r->tmax;
    hit.u = 0.0f;
    hit.v = 0.0f;
    hit.prim = FEN_INVALID_ID;

    uint stack_ref[FEN_BVH_STACK_SIZE];
    float stack_t[FEN_BVH_STACK_SIZE];
    int sp = 0;
    uint cur = 0;
    float tnear[FEN_BVH_WIDTH];

    for (;;) {
        if (!(cur & FEN_LEAF_BIT)) {
            const global BvhNode* n = nodes + cur;
            uint bits = bvh_wide_test(n, r, hit.t, tnear);
            if (bits != 0) {
                int k = bvh_lowest_bit(bits);
                bits &= bits - 1;
                uint c0 = n->child[k];
                float d0 = tnear[k];
                if (bits == 0) {
                    cur = c0;
                    continue;
                }
                k = bvh_lowest_bit(bits);
                bits &= bits - 1;
                uint c1 = n->child[k];
                float d1 = tnear[k];
                if (bits == 0) {
                    if (d1 < d0) {
                        stack_ref[sp] = c0;
                        stack_t[sp] = d0;
                        cur = c1;
                    } else {
                        stack_ref[sp] = c1;
                        stack_t[sp] = d1;
                        cur = c0;
                    }
                    ++sp;
                    continue;
                }
                /* three or more: push all, sort the new entries far to near, take the nearest */
                const int base = sp;
                stack_ref[sp] = c0;
                stack_t[sp++] = d0;
                stack_ref[sp] = c1;
                stack_t[sp++] = d1;
                while (bits != 0) {
                    k = bvh_lowest_bit(bits);
                    bits &= bits - 1;
                    stack_ref[sp] = n->child[k];
                    stack_t[sp++] = tnear[k];
                }
                for (int i = base + 1; i < sp; ++i) {
                    const uint ci = stack_ref[i];
                    const float di = stack_t[i];
                    int j = i - 1;
                    while (j >= base && stack_t[j] < di) {
                        stack_ref[j + 1] = stack_ref[j];
                        stack_t[j + 1] = stack_t[j];
                        --j;
                    }
                    stack_ref[j + 1] = ci;
                    stack_t[j + 1] = di;
                }
                cur = stack_ref[--sp];
                continue;
            }
        } else {
            float4 b1, b2;
            const global TriPacket4* p = packets + (cur & ~FEN_LEAF_BIT);
            const float4 t = tri_packet_intersect(p, r, hit.t, &b1, &b2);
            const float tm = tri_packet_min(t);
            if (tm < hit.t) {
                const int lane = (t.s0 == tm) ? 0 : ((t.s1 == tm) ? 1 : ((t.s2 == tm) ? 2 : 3));
                hit.t = tm;
                hit.u = fen_lane(b1, (uint)lane);
                hit.v = fen_lane(b2, (uint)lane);
                hit.prim = p->prim[lane];
                *packet_lane = ((cur & ~FEN_LEAF_BIT) << 2) | (uint)lane;
            }
        }
        /* pop the nearest pending subtree that can still hold a closer hit */
        for (;;) {
            if (sp == 0)
                return hit;
            --sp;
            if (stack_t[sp] <= hit.t) {
                cur = stack_ref[sp];
                break;
            }
        }
    }
}

static inline Hit bvh_intersect_closest(const global BvhNode* nodes,
                                        const global TriPacket4* packets, const RayPre* r)
{
    uint packet_lane;
    return bvh_intersect_closest_at(nodes, packets, r, &packet_lane);
}

/* Any-order traversal as an iterator over the leaves the ray's interval reaches: the queries that
   need no nearest-first order (any hit, counting hits, transmittance through glass) are loops over
   bvh_walk_next. Children are visited in whatever order the mask gives. */
typedef struct {
    uint stack[FEN_BVH_STACK_SIZE];
    int sp;
    uint cur;  /* next reference to look at; FEN_INVALID_ID when done */
} BvhWalk;

static inline void bvh_walk_begin(BvhWalk* w)
{
    w->sp = 0;
    w->cur = 0;
}

/* The next leaf's packet index, or FEN_INVALID_ID when the walk is over. */
static inline uint bvh_walk_next(BvhWalk* w, const global BvhNode* nodes, const RayPre* r)
{
    float tnear[FEN_BVH_WIDTH];
    for (;;) {
        const uint cur = w->cur;
        if (cur == FEN_INVALID_ID)
            return FEN_INVALID_ID;
        if (cur & FEN_LEAF_BIT) {
            w->cur = w->sp > 0 ? w->stack[--w->sp] : FEN_INVALID_ID;
            return cur & ~FEN_LEAF_BIT;
        }
        const global BvhNode* n = nodes + cur;
        uint bits = bvh_wide_test(n, r, r->tmax, tnear);
        if (bits == 0) {
            w->cur = w->sp > 0 ? w->stack[--w->sp] : FEN_INVALID_ID;
            continue;
        }
        int k = bvh_lowest_bit(bits);
        bits &= bits - 1;
        w->cur = n->child[k];
        while (bits != 0) {
            k = bvh_lowest_bit(bits);
            bits &= bits - 1;
            w->stack[w->sp++] = n->child[k];
        }
    }
}

/* Is anything hit in (tmin, tmax)? The first hit ends it. */
static inline int bvh_intersect_any(const global BvhNode* nodes, const global TriPacket4* packets,
                                    const RayPre* r)
{
    BvhWalk w;
    bvh_walk_begin(&w);
    for (uint leaf; (leaf = bvh_walk_next(&w, nodes, r)) != FEN_INVALID_ID;) {
        float4 b1, b2;
        if (tri_packet_min(tri_packet_intersect(packets + leaf, r, r->tmax, &b1, &b2)) < INFINITY)
            return 1;
    }
    return 0;
}

/* How many distinct triangles the ray crosses in (tmin, tmax): a packet's repeated last triangle
   counts once. (Portal emission's N(x, v).) */
static inline uint bvh_count_hits(const global BvhNode* nodes, const global TriPacket4* packets,
                                  const RayPre* r)
{
    BvhWalk w;
    bvh_walk_begin(&w);
    uint count = 0;
    for (uint leaf; (leaf = bvh_walk_next(&w, nodes, r)) != FEN_INVALID_ID;) {
        float4 b1, b2;
        const global TriPacket4* p = packets + leaf;
        const float4 t = tri_packet_intersect(p, r, r->tmax, &b1, &b2);
        count += (t.s0 < INFINITY) + (t.s1 < INFINITY && p->prim[1] != p->prim[0]) +
                 (t.s2 < INFINITY && p->prim[2] != p->prim[1]) +
                 (t.s3 < INFINITY && p->prim[3] != p->prim[2]);
    }
    return count;
}

#endif /* FEN_BVH_TRAVERSE_H */
