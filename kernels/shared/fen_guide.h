/* fen_guide.h — device layout of the first-bounce guide (DESIGN.md §3.4): a learned density for
 * the direction a path leaves its first diffuse vertex in, so that light which must bounce before
 * it can reach the camera (off the ground, off a facing wall, into a window) is sent where it was
 * seen to arrive.
 *
 * One declaration for host and device (fen_types.h). The directions at a vertex are drawn as the
 * cosine-weighted hemisphere is, from a point (u1, u2) of the unit square (lib/sampling.h
 * sample_cosine_hemisphere); the guide makes that point's density piecewise constant over an 8 x 8
 * grid of boxes instead of uniform. Since the map from the square to the hemisphere carries the
 * uniform density to cos(theta)/pi, a box's density d(b) = 64 P(b) in the square is d(b) cos/pi per
 * steradian, and the path's weight is divided by d(b): unbiased wherever d > 0, which the host
 * keeps by mixing every learned table with the uniform one (lib/guide.h).
 * Vertices share a table per slot: the voxel of the vertex (a lattice over the scene) and the side
 * its normal faces most (6), hashed into GuideParams.slots slots. A collision mixes two places'
 * tables: it costs precision, never correctness.
 * Statistics per slot and box, FEN_GUIDE_STATS_WORDS fen_u64 each: the sum, 128-bit fixed point
 * at GuideParams.stats_scale^2, of v^2 for every camera contribution a path made after leaving the
 * vertex through the box, v = the contribution over (the path's weight just after the vertex times
 * d(b)) -- v estimates what a unit of weight sent through the box delivers, per unit of the square
 * -- and how many such contributions there were. Times d(b) on the host, the sum of v^2 estimates
 * the box's integral of the squared delivery, which is what the variance under any other table
 * follows (host/scatter/first_bounce_guide.h).
 * Invariants: struct size a multiple of 16 bytes; listed in fen_layout.h for the layout probe.
 */
#ifndef FEN_GUIDE_H
#define FEN_GUIDE_H

#include "shared/fen_types.h"

#define FEN_GUIDE_SIDE 8         /* boxes per side of the unit square */
#define FEN_GUIDE_BINS 64        /* FEN_GUIDE_SIDE^2 boxes per slot; the alias table's columns */
#define FEN_GUIDE_SUMSQ_LO 0
#define FEN_GUIDE_SUMSQ_HI 1
#define FEN_GUIDE_CONNECTIONS 2
#define FEN_GUIDE_STATS_WORDS 3

/* The tables buffer (fen_u32 words): first a bitmap of the learned slots (bit s % 32 of word
   s / 32; an unlearned slot scatters as the cosine does, from the scatter's own random numbers,
   d = 1, no table read), then from uint4 GuideParams.entries on, per slot FEN_GUIDE_BINS alias
   columns of four words: (threshold, alias box, as_uint d(column's box), as_uint d(alias box)),
   so one 16-byte read gives the box and its density. */

FEN_NS_BEGIN

typedef struct {
    fen_float4 lattice;  /* xyz: a corner of the voxel lattice (m); w: voxels per metre */
    fen_u32 slots;       /* hash slots (a power of 2); 0: no guide (every vertex scatters as cosine) */
    fen_u32 alias_shift; /* each slot's alias table has 2^(32 - shift) = FEN_GUIDE_BINS columns */
    fen_f32 stats_scale; /* fixed-point units per unit of the statistic */
    fen_u32 entries;     /* where the boxes start in the tables buffer, in uint4s (see below) */
} GuideParams;
FEN_ASSERT_SIZE(GuideParams, 32);
FEN_ASSERT_OFFSET(GuideParams, slots, 16);

FEN_NS_END

#endif /* FEN_GUIDE_H */
