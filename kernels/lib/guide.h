/* guide.h — the first-bounce guide on the device (DESIGN.md §3.4; layout and statistics:
 * shared/fen_guide.h; learning: host/scatter/first_bounce_guide.h).
 *
 * At its first diffuse vertex a path finds its slot (voxel and facing side, hashed), draws a box b
 * of the 8 x 8 grid over the square from the slot's alias table (density d(b) = 64 P(b) there, the
 * host's mixture of what was learned with the uniform table), a point uniformly in the box, and
 * scatters through it as the cosine hemisphere does; the weight is divided by d(b). The path then
 * carries g = stats_scale A_pix / (Y(beta) d(b)) and the slot's box in org.w and dir.w, and every
 * camera contribution C it makes afterwards adds (C g)^2 to that box's statistics: C / (Y(beta)
 * d(b)) estimates what a unit of weight sent through the box delivers, over the box's density, and
 * its square (times d(b), on the host) the box's share of the second moment the next table is
 * fitted to. A_pix (the camera's pixel area at unit distance) only brings the numbers near 1. A slot not learned yet draws
 * nothing extra: the scatter's own point, d = 1, only the record (cheap where most vertices are).
 * Invariant: a slot's table sums to 1 with every d(b) > 0, so every direction the cosine lobe
 * reaches can still be drawn, and the weight uses the d(b) of the box drawn: unbiased.
 */
#ifndef FEN_GUIDE_LIB_H
#define FEN_GUIDE_LIB_H

#include "shared/fen_guide.h"
#include "lib/accumulate.h"
#include "lib/rng.h"
#include "lib/sampling.h"

typedef struct {
    global const GuideParams* params;
    global const uint* tables;  /* the learned-slot bitmap, then the alias columns (fen_guide.h) */
} Guide;

/* The slot of a vertex at x whose light arrived on side n (unit): its voxel and the axis-aligned
   side n faces most, hashed. Coordinates saturate far outside the lattice (all one slot there). */
static inline uint guide_slot(global const GuideParams* gp, float3 x, float3 n)
{
    const int3 v = convert_int3_sat_rtn((x - gp->lattice.xyz) * gp->lattice.w);
    const float3 a = fabs(n);
    const uint axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
    const float na = axis == 0u ? n.x : (axis == 1u ? n.y : n.z);
    const uint side = 2u * axis + (na < 0.0f ? 1u : 0u);
    uint h = (uint)v.x * 73856093u ^ (uint)v.y * 19349663u ^ (uint)v.z * 83492791u ^ side * 2654435761u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    return h & (gp->slots - 1u);
}

/* Whether slot `slot` has a learned table (else its vertices scatter as the cosine does). */
static inline int guide_learned(const Guide* g, uint slot)
{
    return (g->tables[slot >> 5] >> (slot & 31u)) & 1u;
}

/* The box of the square a point lies in. */
static inline uint guide_box(float2 sq)
{
    const uint i = min((uint)(sq.x * FEN_GUIDE_SIDE), (uint)(FEN_GUIDE_SIDE - 1));
    const uint j = min((uint)(sq.y * FEN_GUIDE_SIDE), (uint)(FEN_GUIDE_SIDE - 1));
    return j * FEN_GUIDE_SIDE + i;
}

/* Draws the point of the unit square for learned slot `slot` from 96 random bits: *key = the
   slot's box, *d = its density. The point stays below 1 (a box's far edge belongs to the next). */
static inline float2 guide_sample(const Guide* g, uint slot, RngBlock bits, uint* key, float* d)
{
    const uint shift = g->params->alias_shift;
    const uint j = bits.x >> shift;
    const uint4 e = vload4(g->params->entries + slot * FEN_GUIDE_BINS + j, g->tables);
    const int keep = (bits.x & ((1u << shift) - 1u)) < e.x;
    const uint b = keep ? j : e.y;
    *key = slot * FEN_GUIDE_BINS + b;
    *d = as_float(keep ? e.z : e.w);
    const float2 in_box = (float2)(fen_u32_to_unit(bits.y), fen_u32_to_unit(bits.z));
    const float2 corner = (float2)((float)(b % FEN_GUIDE_SIDE), (float)(b / FEN_GUIDE_SIDE));
    return fmin((corner + in_box) * (1.0f / FEN_GUIDE_SIDE), (float2)(0x1.fffffep-1f));
}

/* Adds a camera contribution of luminance y, made after the path left a guided vertex (its record
   g, key), to that box's statistics: (y g)^2, g already holding the fixed-point scale. */
static inline void guide_record(volatile global ulong* guide_stats, float g, uint key, float y,
                                volatile global ulong* counters)
{
    volatile global ulong* s = guide_stats + FEN_GUIDE_STATS_WORDS * (ulong)key;
    const float v = y * g;
    if (!fixed_add128(s + FEN_GUIDE_SUMSQ_LO, v * v)) {
        counter_add(counters, FEN_CTR_STATS_OVERFLOWS, 1);
        return;
    }
    atom_inc(s + FEN_GUIDE_CONNECTIONS);
}

#endif /* FEN_GUIDE_LIB_H */
