/* fen_guide.h — device layout of the first-bounce guide (DESIGN.md §3.4): a learned density for
 * the direction a path leaves its first diffuse vertex in, so that light which must bounce before
 * it can reach the camera (off the ground, off a facing wall, into a window) is sent where it was
 * seen to arrive.
 *
 * One declaration for host and device (fen_types.h). The directions at a vertex are drawn as the
 * cosine-weighted hemisphere is, from a point (u1, u2) of the unit square (lib/sampling.h
 * sample_cosine_hemisphere); the guide makes that point's density piecewise constant over the
 * leaves of a quadtree over the square instead of uniform. Since the map from the square to the
 * hemisphere carries the uniform density to cos(theta)/pi, a leaf's density d in the square is
 * d cos/pi per steradian, and the path's weight is divided by d: unbiased wherever d > 0, which the
 * host keeps by mixing every learned table with the uniform one -- the one-sample mixture of the
 * cosine (the BSDF's own sampling) and the learned density (host/scatter/first_bounce_guide.h).
 * The quadtree's resolution follows the learned density: a leaf holding much of it is split on the
 * next pass, down to FEN_GUIDE_MAX_DEPTH (cells of 2^-12 of the square's side), so that a window a
 * few thousandths of a steradian wide, seen from far outside, gets leaves of its own.
 * Vertices share a tree per slot: the spatial leaf the vertex lies in and the side its normal faces
 * most (6), slot = 6 leaf + side. The spatial leaves refine a lattice of voxels over the scene's
 * bounding cube: each voxel is the root of a binary tree that halves it along x, y, z in turn, split
 * on the host where a pass's contributions accumulate, so that the ground right in front of a
 * window gets directions of its own, not those averaged over metres of it.
 * Statistics per leaf (the global leaf index is the key), FEN_GUIDE_STATS_WORDS fen_u64 each: the
 * sum, 128-bit fixed point at GuideParams.stats_scale^2, of v^2 for every camera contribution a
 * path made after leaving the vertex through the leaf, v = the contribution over (the path's weight
 * just after the vertex times d) -- v estimates what a unit of weight sent through the leaf
 * delivers, per unit of the square -- and how many such contributions there were. Times d on the
 * host, the sum of v^2 estimates the leaf's integral of the squared delivery, which is what the
 * variance under any other table follows.
 * Invariants: struct size a multiple of 16 bytes; listed in fen_layout.h for the layout probe.
 */
#ifndef FEN_GUIDE_H
#define FEN_GUIDE_H

#include "shared/fen_types.h"

#define FEN_GUIDE_INITIAL_DEPTH 3  /* every slot's tree starts as 8 x 8 leaves */
#define FEN_GUIDE_MAX_DEPTH 12     /* leaves down to 2^-12 of the square's side */
#define FEN_GUIDE_SIDES 6          /* slots per spatial leaf: the side a vertex's normal faces most */
#define FEN_GUIDE_SUMSQ_LO 0
#define FEN_GUIDE_SUMSQ_HI 1
#define FEN_GUIDE_CONNECTIONS 2
#define FEN_GUIDE_STATS_WORDS 3
/* With weight windows (GuideParams.windows_at > 0), a second buffer of sums per slot (the windows
   only ever use them per slot: a few hundred kB, where per leaf they were megabytes that every
   connection's atomics missed the cache on), the window statistics, FEN_GUIDE_WINDOW_WORDS fen_u64
   each, 128-bit fixed point at FEN_GUIDE_WINDOW_SCALE times the film's RenderParams.fixed_scale,
   each value raised to GuideParams.window_power (1: rule `mean`, 2: rule `moment`, the squares at
   the scale's square): 2^-20 leaves room for the square of a contribution 2^43 times the film's
   reference luminance, and still registers one of 2^-20 of it in the plain sums. Only the power
   the rule uses is summed: half the atomics of summing both. */
#define FEN_GUIDE_WINDOW_SCALE 0x1p-20f
#define FEN_GUIDE_DELIVERED_LO 0    /* the luminance C of each camera contribution a path made after */
#define FEN_GUIDE_DELIVERED_HI 1    /*   leaving a first diffuse vertex in the slot, to the power */
#define FEN_GUIDE_ARRIVED_LO 2      /* the luminance of the weight each path that left a vertex there */
#define FEN_GUIDE_ARRIVED_HI 3      /*   arrived with, over A_pix (the camera's): a number of C's
                                       magnitude, to the power */
#define FEN_GUIDE_VISITS 4          /* paths (or branches) that left a vertex there */
/* The opening aim's share statistics (GuideParams.aim_sums; what the host learns the aim's cosine
   share from, host/scatter/opening_aim.cpp learnShare), squares whatever the rule: */
#define FEN_GUIDE_MIXED_SQ_LO 5     /* the square of the luminance C of each camera contribution made */
#define FEN_GUIDE_MIXED_SQ_HI 6     /*   after leaving a first diffuse vertex there by the aim's mixture */
#define FEN_GUIDE_AIMED_SQ_LO 7     /* ... of those, by a path that left in a direction where the aim's */
#define FEN_GUIDE_AIMED_SQ_HI 8     /*   part of the mixture's density was the larger */
#define FEN_GUIDE_WINDOW_WORDS 9
/* Connection.guide.w with weight windows: the slot of the path's first diffuse vertex, with this
   bit set when the window statistics sum squares (window_power 2) */
#define FEN_GUIDE_WINDOW_SQUARED 0x80000000u
/* ... and this bit when the aim's share statistics are summed (GuideParams.aim_sums) */
#define FEN_GUIDE_WINDOW_AIM 0x40000000u
#define FEN_GUIDE_WINDOW_SLOT 0x3fffffffu

/* A child word of a node: FEN_GUIDE_LEAF | global leaf index, or the global index of a node. */
#define FEN_GUIDE_LEAF 0x80000000u
/* A slot record's w: FEN_GUIDE_LEARNED | the alias shift of its columns, or 0 (the cosine); and
   FEN_GUIDE_INITIAL while the slot's tree is the initial full one, whose leaf for a point the device
   computes without reading the nodes (most slots, never refined: a first vertex there costs no
   more than a fixed grid's). */
#define FEN_GUIDE_LEARNED 0x80000000u
#define FEN_GUIDE_INITIAL 0x40000000u

/* The tables buffer (fen_u32 words), six sections from the word offsets in GuideParams:
 *  - slot records, uint4 per slot: (root node, first leaf, first alias column, w above);
 *  - voxels, one word per voxel of the lattice (x fastest): FEN_GUIDE_LEAF | its spatial leaf, or
 *    the spatial node its tree starts at;
 *  - spatial nodes, uint2 each: the children for the lower and the upper half along the axis of
 *    the node's depth below its voxel (x, y, z, x, ...), each FEN_GUIDE_LEAF | spatial leaf or a
 *    spatial node;
 *  - nodes, uint4 per node: its four children, quadrant q = (u1 >= 1/2) + 2 (u2 >= 1/2);
 *  - leaves, uint2 per leaf: (as_uint d, the leaf's place: x0 | y0 << 14 | depth << 28, x0 and y0
 *    its corner in units of 2^-FEN_GUIDE_MAX_DEPTH);
 *  - alias columns of a learned slot, uint2 each: (threshold, alias leaf, counted from the slot's
 *    first leaf); column j gives leaf j to the values below the threshold, its alias to the rest
 *    (host/util/integer_cdf.h);
 *  - with weight windows, one float per slot: the window weight, a luminance over A_pix at the
 *    window statistics' scale (FEN_GUIDE_WINDOW_SCALE fixed_scale), at which
 *    a path's expected contribution from this vertex on (rule `mean`), or the root of its second
 *    moment (rule `moment`), is the target's; 0 where the slot has not been seen enough, FLT_MAX
 *    where it was seen and never delivered (lib/guide.h guide_window);
 *  - with weight windows, one word per leaf: the slot whose tree holds it (a connection finds the
 *    window statistics of the path's first vertex from the leaf its record names). */

FEN_NS_BEGIN

typedef struct {
    fen_float4 lattice;   /* xyz: the lattice cube's lowest corner (m); w: 1 / its side (1/m) */
    fen_u32 slots;        /* slots in use (6 per spatial leaf); 0: no guide (the cosine everywhere) */
    fen_u32 nodes_at;     /* word offsets of the sections of the tables buffer (above) */
    fen_u32 leaves_at;
    fen_u32 columns_at;
    fen_f32 stats_scale;  /* fixed-point units per unit of the statistic */
    fen_u32 voxels_at;
    fen_u32 spatial_at;
    fen_u32 cells;        /* voxels along each side of the cube (a power of 2) */
    fen_u32 every_vertex; /* 1: a path is guided at every diffuse vertex whose slot is learned; 0: at
                             its first only. Learning is the same either way (the first vertex's record) */
    fen_u32 windows_at;   /* weight windows: word offset of the per-slot window weights; 0: none */
    fen_f32 window_min_survival; /* a culled path survives with at least this probability */
    fen_u32 window_split_max;    /* a path splits into at most this many branches */
    fen_u32 window_power;        /* the power of the values the window statistics sum: 1 (rule
                                    `mean`) or 2 (rule `moment`) */
    fen_u32 leaf_slots_at;       /* word offset of the leaves' slots (above); 0 without windows */
    fen_f32 window_later;        /* > 0: a path not split yet may split at any later diffuse vertex whose
                                    slot has a window, its ratio to it times this there (windows lower
                                    past the first vertex); 0: at its first only (culling: the first only) */
    fen_f32 window_min;          /* the smallest window of any slot (0: none): a path whose weight is
                                    under twice it splits nowhere, so a later vertex need not find
                                    its slot to know */
    fen_u32 aim_sums;            /* 1: sum the opening aim's share statistics (above; needs weight
                                    windows); 0: not */
    fen_u32 pad0, pad1, pad2;
} GuideParams;
FEN_ASSERT_SIZE(GuideParams, 96);
FEN_ASSERT_OFFSET(GuideParams, slots, 16);
FEN_ASSERT_OFFSET(GuideParams, stats_scale, 32);
FEN_ASSERT_OFFSET(GuideParams, every_vertex, 48);
FEN_ASSERT_OFFSET(GuideParams, windows_at, 52);
FEN_ASSERT_OFFSET(GuideParams, window_split_max, 60);
FEN_ASSERT_OFFSET(GuideParams, leaf_slots_at, 68);
FEN_ASSERT_OFFSET(GuideParams, window_later, 72);
FEN_ASSERT_OFFSET(GuideParams, window_min, 76);
FEN_ASSERT_OFFSET(GuideParams, aim_sums, 80);

FEN_NS_END

#endif /* FEN_GUIDE_H */
