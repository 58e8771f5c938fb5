/* guide.h — the first-bounce guide on the device (DESIGN.md §3.4; layout and statistics:
 * shared/fen_guide.h; learning: host/scatter/first_bounce_guide.h).
 *
 * At its first diffuse vertex a path finds its slot (spatial leaf and facing side), draws a leaf b
 * of its quadtree over the square from the slot's alias table (density d(b) = P(b) / area(b) there,
 * the host's mixture of what was learned with the uniform table), a point uniformly in the leaf,
 * and scatters through it as the cosine hemisphere does; the weight is divided by d(b). The path then
 * carries g = stats_scale A_pix / (Y(beta) d(b)) and the global leaf in org.w and dir.w, and every
 * camera contribution C it makes afterwards adds (C g)^2 to that leaf's statistics: C / (Y(beta)
 * d(b)) estimates what a unit of weight sent through the leaf delivers, over the leaf's density, and
 * its square (times d(b), on the host) the leaf's share of the second moment the next table is
 * fitted to. A_pix (the camera's pixel area at unit distance) only brings the numbers near 1. A slot not learned yet draws
 * nothing extra: the scatter's own point, d = 1, and the leaf it lies in for the record.
 * Invariant: a slot's table sums to 1 with every d(b) > 0, so every direction the cosine lobe
 * reaches can still be drawn, and the weight uses the d(b) of the leaf drawn: unbiased.
 */
#ifndef FEN_GUIDE_LIB_H
#define FEN_GUIDE_LIB_H

#include "shared/fen_guide.h"
#include "shared/fen_openings.h"
#include "lib/accumulate.h"
#include "lib/rng.h"
#include "lib/sampling.h"

/* The weight windows' arrivals a work-item holds before adding them to window_stats (guide_arrive):
   every path's first diffuse vertex adds one, and where most paths land on a few slots (the ground
   around a house) two cores adding to the same words take turns on their cache lines (the house:
   8 % of a profile's samples waited on those atomics; held, 3 % more paths a second,
   docs/performance.md). Direct-mapped by slot; an entry is added to memory when
   another slot takes its place and when the work-item ends (guide_arrivals_flush): the same
   integer sums, so the same bytes. */
#define FEN_GUIDE_HELD_SLOTS 8
typedef struct {
    uint slot[FEN_GUIDE_HELD_SLOTS]; /* FEN_INVALID_ID: empty */
    ulong visits[FEN_GUIDE_HELD_SLOTS];
    Fixed128 arrived[FEN_GUIDE_HELD_SLOTS];
} HeldArrivals;

/* Empties entry i. */
static inline void held_arrival_clear(HeldArrivals* h, int i)
{
    h->slot[i] = FEN_INVALID_ID;
    h->visits[i] = 0ul;
    h->arrived[i].lo = h->arrived[i].hi = 0ul;
}

static inline void held_arrivals_init(HeldArrivals* h)
{
    for (int i = 0; i < FEN_GUIDE_HELD_SLOTS; ++i)
        held_arrival_clear(h, i);
}

typedef struct {
    global const GuideParams* params;
    global const uint* tables;  /* slot records, nodes, leaves, alias columns (fen_guide.h) */
    volatile global ulong* window_stats; /* per slot (fen_guide.h): the weight windows' sums */
    HeldArrivals* held;                  /* the work-item's own, or 0: arrivals go to memory at once */
    /* the opening aim (lib/opening_aim.h), learned beside the guide: where paths still outside are
       aimed, which glass is an opening, and the openings' statistics */
    global const OpeningAim* aim;
    global const uint2* opening_prims;
    volatile global ulong* opening_stats;
} Guide;

/* The slot of a vertex at x whose light arrived on side n (unit): the spatial leaf x lies in and
   the axis-aligned side n faces most. The voxel comes from arithmetic; only a voxel the host has
   split reads nodes, halving the voxel along x, y, z in turn (exact in floating point). Points
   outside the cube (none in the scene) take the nearest voxel. */
static inline uint guide_slot(const Guide* g, float3 x, float3 n)
{
    global const GuideParams* gp = g->params;
    const float3 a = fabs(n);
    const uint axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
    const float na = axis == 0u ? n.x : (axis == 1u ? n.y : n.z);
    const uint side = 2u * axis + (na < 0.0f ? 1u : 0u);
    const float cells = (float)gp->cells;
    const float3 p = fmin(fmax((x - gp->lattice.xyz) * gp->lattice.w * cells, (float3)(0.0f)),
                          (float3)(cells * 0x1.fffffep-1f));
    const uint3 v = convert_uint3_rtz(p);
    float3 q = p - convert_float3(v); /* where x lies in its voxel, [0, 1)^3 */
    uint word = g->tables[gp->voxels_at + v.x + gp->cells * (v.y + gp->cells * v.z)];
    for (uint depth = 0u; !(word & FEN_GUIDE_LEAF) && depth < 64u; ++depth) {
        const uint k = depth % 3u;
        const float c = k == 0u ? q.x : (k == 1u ? q.y : q.z);
        const uint up = c >= 0.5f;
        const float c2 = c * 2.0f - (float)up;
        q = k == 0u ? (float3)(c2, q.y, q.z) : (k == 1u ? (float3)(q.x, c2, q.z) : (float3)(q.x, q.y, c2));
        word = g->tables[gp->spatial_at + 2u * word + up];
    }
    return FEN_GUIDE_SIDES * (word & ~FEN_GUIDE_LEAF) + side;
}

/* The slot's record (shared/fen_guide.h): root node, first leaf, first column, learned | shift. */
static inline uint4 guide_record_of(const Guide* g, uint slot)
{
    return vload4(slot, g->tables);
}

/* The global leaf of the slot's tree (record r) that point sq of the square lies in: a descent
   from the root, each level halving the square (exact in floating point). */
static inline uint guide_leaf(const Guide* g, uint4 r, float2 sq)
{
    if (r.w & FEN_GUIDE_INITIAL) {
        /* the initial full tree: its leaves in depth-first order are the Morton order of the
           8 x 8 boxes, quadrant bit 0 from x, bit 1 from y at every level */
        const uint i = min((uint)(sq.x * 8.0f), 7u), j = min((uint)(sq.y * 8.0f), 7u);
        const uint morton = (i & 1u) | ((j & 1u) << 1) | ((i & 2u) << 1) | ((j & 2u) << 2) | ((i & 4u) << 2) |
                            ((j & 4u) << 3);
        return r.y + morton;
    }
    uint node = r.x;
    for (int level = 0; level < FEN_GUIDE_MAX_DEPTH; ++level) {
        const int right = sq.x >= 0.5f, up = sq.y >= 0.5f;
        const uint child = g->tables[g->params->nodes_at + 4u * node + (uint)right + 2u * (uint)up];
        if (child & FEN_GUIDE_LEAF)
            return child & ~FEN_GUIDE_LEAF;
        node = child;
        sq = sq * 2.0f - (float2)((float)right, (float)up);
    }
    return r.y; /* unreachable for the host's trees: no deeper than FEN_GUIDE_MAX_DEPTH */
}

/* The density d(b) the slot's current table draws global leaf `key` with (1: the cosine's). */
static inline float guide_leaf_density(const Guide* g, uint key)
{
    return as_float(g->tables[g->params->leaves_at + 2u * key]);
}

/* Draws the point of the unit square for learned slot record r from 96 random bits: *key = the
   global leaf drawn, *d = its density. The point stays inside the leaf (its far edge belongs to
   the next). */
static inline float2 guide_sample(const Guide* g, uint4 r, RngBlock bits, uint* key, float* d)
{
    const uint shift = r.w & 31u;
    const uint j = bits.x >> shift;
    const uint2 col = vload2(r.z + j, g->tables + g->params->columns_at);
    const uint leaf = r.y + ((bits.x & ((1u << shift) - 1u)) < col.x ? j : col.y);
    const uint2 e = vload2(leaf, g->tables + g->params->leaves_at);
    *key = leaf;
    *d = as_float(e.x);
    const float size = as_float((127u - (e.y >> 28)) << 23); /* 2^-depth, exactly */
    const float2 corner = (float2)((float)(e.y & 0x3fffu), (float)((e.y >> 14) & 0x3fffu)) *
                          (1.0f / (float)(1 << FEN_GUIDE_MAX_DEPTH));
    const float2 in_leaf = (float2)(fen_u32_to_unit(bits.y), fen_u32_to_unit(bits.z));
    /* corner + size is exact (multiples of 2^-12 up to 1, positive); rounding may reach it, so the
       point is kept one float below it: inside the leaf, below 1 */
    const float2 end = corner + size;
    return fmin(corner + in_leaf * size, (float2)(as_float(as_uint(end.x) - 1u), as_float(as_uint(end.y) - 1u)));
}

/* Adds a camera contribution of luminance y, made after the path left a guided vertex (its record
   g, key), to that leaf's statistics: (y g)^2, g already holding the fixed-point scale; and with
   weight windows (delivered_scale > 0: the window statistics' scale) y at that scale, or its square
   (window & FEN_GUIDE_WINDOW_SQUARED), to the window statistics of the vertex's slot (the rest of
   window), for the adjoint the windows follow; with the aim's share statistics
   (window & FEN_GUIDE_WINDOW_AIM), where the vertex drew from the aim's mixture, the square of y
   at that scale to the slot's mixed sum, and where it drew a direction in the aim's region to its
   aimed sum too (`opening`: the connection's word, lib/opening_aim.h). */
static inline void guide_record(volatile global ulong* guide_stats, volatile global ulong* window_stats, float g,
                                uint key, float y, float delivered_scale, uint window, uint opening,
                                volatile global ulong* counters)
{
    volatile global ulong* s = guide_stats + FEN_GUIDE_STATS_WORDS * (ulong)key;
    const float v = y * g;
    volatile global ulong* w =
        window_stats + FEN_GUIDE_WINDOW_WORDS * (ulong)(window & FEN_GUIDE_WINDOW_SLOT);
    const float c = y * delivered_scale;
    if (!fixed_add128(s + FEN_GUIDE_SUMSQ_LO, v * v) ||
        (delivered_scale > 0.0f &&
         !fixed_add128(w + FEN_GUIDE_DELIVERED_LO, (window & FEN_GUIDE_WINDOW_SQUARED) ? c * c : c))) {
        counter_add(counters, FEN_CTR_STATS_OVERFLOWS, 1);
        return;
    }
    atom_inc(s + FEN_GUIDE_CONNECTIONS);
    if (delivered_scale > 0.0f && (window & FEN_GUIDE_WINDOW_AIM) && (opening & FEN_OPENING_CONNECTION_MIXED)) {
        if (!fixed_add128(w + FEN_GUIDE_MIXED_SQ_LO, c * c) ||
            ((opening & FEN_OPENING_CONNECTION_AIM_REGION) && !fixed_add128(w + FEN_GUIDE_AIMED_SQ_LO, c * c)))
            counter_add(counters, FEN_CTR_STATS_OVERFLOWS, 1);
    }
}

/* Weight windows (DESIGN.md §3.4): the window weight of a slot -- the luminance of weight over A_pix
   that is expected to deliver the target from a vertex there on (host/scatter/first_bounce_guide.cpp
   rebuildWindows) -- or 0 where there is none (no windows, or the slot not seen enough; the fixed
   rules then apply). */
static inline float guide_window(const Guide* g, uint slot)
{
    return g->params->windows_at ? as_float(g->tables[g->params->windows_at + slot]) : 0.0f;
}

/* With weight windows: the word a connection carries in Connection.guide.w for a path whose first
   diffuse vertex left through leaf key: the leaf's slot, and whether the sums are of squares. */
static inline uint guide_window_word(const Guide* g, uint key)
{
    return g->tables[g->params->leaf_slots_at + key] | (g->params->window_power == 2u ? FEN_GUIDE_WINDOW_SQUARED : 0u) |
           (g->params->aim_sums ? FEN_GUIDE_WINDOW_AIM : 0u);
}

/* Adds held entry i to window_stats and empties it. */
static inline void guide_arrival_flush(const Guide* g, int i)
{
    HeldArrivals* h = g->held;
    if (h->slot[i] == FEN_INVALID_ID)
        return;
    volatile global ulong* s = g->window_stats + FEN_GUIDE_WINDOW_WORDS * (ulong)h->slot[i];
    fixed_add_parts(s + FEN_GUIDE_ARRIVED_LO, h->arrived[i].hi, h->arrived[i].lo);
    if (h->visits[i] != 0ul)
        atom_add(s + FEN_GUIDE_VISITS, h->visits[i]);
    held_arrival_clear(h, i);
}

/* Adds what the work-item holds to window_stats: before it ends, and before anything reads them. */
static inline void guide_arrivals_flush(const Guide* g)
{
    if (!g->held)
        return;
    for (int i = 0; i < FEN_GUIDE_HELD_SLOTS; ++i)
        guide_arrival_flush(g, i);
}

/* With weight windows: a path (or branch) whose weight arrived with luminance over A_pix a (at the
   window statistics' scale) leaves its first diffuse vertex in slot `slot` -- the denominators of
   the adjoint (delivered / arrived, or its second moment, delivered^2 / arrived^2: a to the power
   the rule sums) and of the target (per visit). */
static inline void guide_arrive(const Guide* g, uint slot, float a, volatile global ulong* counters)
{
    const float v = g->params->window_power == 2u ? a * a : a;
    HeldArrivals* h = g->held;
    if (!h) {
        volatile global ulong* s = g->window_stats + FEN_GUIDE_WINDOW_WORDS * (ulong)slot;
        if (!fixed_add128(s + FEN_GUIDE_ARRIVED_LO, v)) {
            counter_add(counters, FEN_CTR_STATS_OVERFLOWS, 1);
            return;
        }
        atom_inc(s + FEN_GUIDE_VISITS);
        return;
    }
    const int i = (int)(slot % FEN_GUIDE_HELD_SLOTS);
    if (h->slot[i] != slot) {
        guide_arrival_flush(g, i);
        h->slot[i] = slot;
    }
    if (!fixed_add_held(&h->arrived[i], v)) {
        counter_add(counters, FEN_CTR_STATS_OVERFLOWS, 1);
        return;
    }
    ++h->visits[i];
}

#endif /* FEN_GUIDE_LIB_H */
