/* fen_bvh.h — device layout of the scene's acceleration structure and of rays and hits.
 *
 * One declaration for host and device (see fen_types.h). The host builds a binary SAH tree
 * (bvh/bvh_build.cpp), collapses it to 2, 4 or 8 children per node (bvh/bvh_flat.cpp) and
 * stores it in these rows; the traversal kernels (kernels/lib/bvh_traverse_*.h) read them.
 * Invariants:
 *   - node 0 is the root and is always an inner node (an empty scene has a root whose child
 *     boxes are all empty), so traversal needs no special case;
 *   - child boxes are stored structure-of-arrays so one vector op tests every child on an axis;
 *     an unused child slot has an empty box (lo = +inf, hi = -inf) that no ray can hit;
 *   - a child reference with FEN_LEAF_BIT set names one TriPacket4 (a leaf holds 1..4
 *     triangles); otherwise it is a node index;
 *   - triangles are stored as raw vertices, never as edges, so that the watertight test sees the
 *     same numbers for a vertex shared by neighbours (no false misses along shared edges).
 */
#ifndef FEN_BVH_H
#define FEN_BVH_H

#include "shared/fen_types.h"

#define FEN_LEAF_BIT   0x80000000u
#define FEN_INVALID_ID 0xFFFFFFFFu
/* Largest traversal stack the kernels carry; the host rejects a tree that could need more. */
#define FEN_BVH_STACK_SIZE 128

FEN_NS_BEGIN

/* A ray with its parametric interval: points o + t d for tmin < t < tmax. */
typedef struct {
    fen_float4 org_tmin;  /* xyz: origin (m); w: tmin */
    fen_float4 dir_tmax;  /* xyz: direction (need not be unit length); w: tmax */
} Ray;
FEN_ASSERT_SIZE(Ray, 32);
FEN_ASSERT_OFFSET(Ray, dir_tmax, 16);

/* The closest hit: p = (1-u-v) v0 + u v1 + v v2 of triangle `prim`; prim = FEN_INVALID_ID on
   a miss (t is then the ray's tmax). */
typedef struct {
    fen_f32 t;
    fen_f32 u;
    fen_f32 v;
    fen_u32 prim;
} Hit;
FEN_ASSERT_SIZE(Hit, 16);
FEN_ASSERT_OFFSET(Hit, prim, 12);

/* 2-wide node, 64 bytes: bounds = lo_x[2] hi_x[2] lo_y[2] hi_y[2] lo_z[2] hi_z[2], i.e. both
   children's boxes in one row (32 bytes per child, the Aila-Laine idea). */
typedef struct {
    fen_f32 bounds[12];
    fen_u32 child[2];
    fen_u32 pad[2];
} BvhNode2;
FEN_ASSERT_SIZE(BvhNode2, 64);
FEN_ASSERT_OFFSET(BvhNode2, child, 48);

/* 4-wide node, 128 bytes: bounds = lo_x[4] hi_x[4] lo_y[4] hi_y[4] lo_z[4] hi_z[4]. */
typedef struct {
    fen_f32 bounds[24];
    fen_u32 child[4];
    fen_u32 pad[4];
} BvhNode4;
FEN_ASSERT_SIZE(BvhNode4, 128);
FEN_ASSERT_OFFSET(BvhNode4, child, 96);

/* 8-wide node, 256 bytes: bounds = lo_x[8] hi_x[8] lo_y[8] hi_y[8] lo_z[8] hi_z[8]. */
typedef struct {
    fen_f32 bounds[48];
    fen_u32 child[8];
    fen_u32 pad[8];
} BvhNode8;
FEN_ASSERT_SIZE(BvhNode8, 256);
FEN_ASSERT_OFFSET(BvhNode8, child, 192);

/* Up to four triangles, structure of arrays: v[(3*k + axis)*4 + lane] is vertex k (0..2),
   coordinate axis (0..2) of triangle `lane`. Unused lanes repeat the last triangle, so they
   can only report a hit that lane 0..n-1 already reports. */
typedef struct {
    fen_f32 v[36];
    fen_u32 prim[4];
} TriPacket4;
FEN_ASSERT_SIZE(TriPacket4, 160);
FEN_ASSERT_OFFSET(TriPacket4, prim, 144);

FEN_NS_END

#endif /* FEN_BVH_H */
