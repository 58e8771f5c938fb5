/* fen_emission.h — device layout of the emission strategies' own parameters (DESIGN.md §3).
 *
 * One declaration for host and device (fen_types.h). Each strategy's kernel half reads these
 * from its own buffers (kernels/lib/emit_*.h), its host half fills them (host/emission/):
 *   - SourceParams: the source table of `uniform` and `portal` (the sun, or one sky cell, from
 *     32 random bits) and the source's part of a path weight;
 *   - PortalParams: the portal set of `portal` (and of `adaptive` over a portal base);
 *   - AdaptiveParams, AdaptiveCell, PortalFrame: the learned emission grid of `adaptive`
 *     (DESIGN.md §3.3).
 * Invariants: every struct is a multiple of 16 bytes, members ordered 16 -> 4 bytes; all listed in
 * fen_layout.h for the layout probe.
 */
#ifndef FEN_EMISSION_H
#define FEN_EMISSION_H

#include "shared/fen_types.h"

/* PortalParams.overlap */
#define FEN_OVERLAP_REJECT 0u
#define FEN_OVERLAP_WEIGHT 1u
#define FEN_OVERLAP_NONE 2u

/* A path's beta.w part with this bit set only feeds the statistics: connect.cl does not add it to
   the image (the portal strategy's estimate of the light its portals miss). */
#define FEN_PART_ESTIMATE_ONLY 0x80000000u
/* The paths that start on an opening's pane (lib/opening_walk.h) have no emission cell: their
   contributions go to FEN_WALK_PARTS parts of their own past the cells' (AdaptiveParams.walk_part,
   spread by the path index's low bits so that no one 128-bit sum takes every walk's atomics), which
   no cell learns from. The host reads their squares to weigh the walks against the light paths
   (DESIGN.md §3.6, the share raced). */
#define FEN_WALK_PARTS 16

/* AdaptiveCell.region: the emission disk, or 1 + g for portal plane g. */
#define FEN_REGION_DISK 0u

/* Emission cell statistics (learning strategies): per sixteenth of a cell (cell * 16 + 4 * vq + xq,
   xq the quarter of its origin box and vq of its direction box, so the host sees where inside a
   cell the light was before it splits it, either way), FEN_CELL_STATS_WORDS fen_u64; the sums
   are over the luminance Y of every contribution that reached the camera, each 128-bit fixed
   point (lib/accumulate.h): Y at RenderParams.fixed_scale, Y^2 at .stats_scale. */
#define FEN_CELL_PARTS 16
#define FEN_CELL_SUM_LO 0
#define FEN_CELL_SUM_HI 1
#define FEN_CELL_SUMSQ_LO 2
#define FEN_CELL_SUMSQ_HI 3
#define FEN_CELL_CONNECTIONS 4 /* contributions that reached the camera */
#define FEN_CELL_STATS_WORDS 5
/* The paths drawn from a part are not counted on the device: the host knows how many paths a
   pass ran and each part's probability, P(cell) / 16 exactly (16-bit uniforms split their halves
   evenly), so it uses that expectation -- an atomic per path cost a quarter of the emission. */

FEN_NS_BEGIN

typedef struct {
    fen_float4 sun_weight; /* rgb: weight of a sun path, E / P(sun); the strategy multiplies in its
                              geometric part (for `uniform` the silhouette area below) */
    fen_float4 box_min;    /* `uniform`: the emission box's lowest corner (m), w 0 ... */
    fen_float4 box_size;   /* ... and its extent (m), w 0: paths enter it uniformly over its
                              silhouette (lib/emit_source.h box_line_origin); zero for a table
                              that starts no uniform path */
    fen_u32 alias_shift;   /* the source alias table has 2^(32 - shift) columns */
    fen_u32 pad0;
    fen_u32 pad1;
    fen_u32 pad2;
} SourceParams;
FEN_ASSERT_SIZE(SourceParams, 64);
FEN_ASSERT_OFFSET(SourceParams, box_size, 32);
FEN_ASSERT_OFFSET(SourceParams, alias_shift, 48);

typedef struct {
    fen_u32 groups;      /* portal plane groups */
    fen_u32 overlap;     /* FEN_OVERLAP_* */
    fen_f32 complement;  /* share of paths that estimate the light no portal passes (0: none) */
    fen_u32 group_alias_shift; /* each direction bin's group table has 2^(32 - shift) columns */
} PortalParams;
FEN_ASSERT_SIZE(PortalParams, 16);

/* One cell of the learned grid over emitted rays (x, v): a box of directions times a box of the
   2D parametrisation of the origin in a region (the emission disk, or one portal plane's frame).
   Directions: the sun (its cone), or a box of (s, t) in [0,1)^2 with cos(theta) = 1 - s and
   phi = 2 pi t -- equal areas of (s, t) are equal solid angles, so a box spans 2 pi ds dt sr; with
   the ground's glow also boxes of s in [1, 2), the lower hemisphere (none straddles s = 1). A
   path picks a cell with probability P(cell), its direction uniformly in the box (or in the sun's
   cone) and its origin uniformly in the origin box. */
typedef struct {
    fen_float4 box;   /* origin: x, y the box's low corner in the region's unit square; z, w its size */
    fen_float4 dirs;  /* directions: s, t low corner, z, w size; z = 0: the sun */
    fen_u32 region;   /* FEN_REGION_DISK, or 1 + g: portal plane g */
    fen_f32 weight;   /* the region's area (pi R^2, or the plane's frame) x box area x the box's
                         solid angle (sky) / P(cell) */
    fen_u32 pad0;
    fen_u32 pad1;
} AdaptiveCell;
FEN_ASSERT_SIZE(AdaptiveCell, 48);
FEN_ASSERT_OFFSET(AdaptiveCell, dirs, 16);
FEN_ASSERT_OFFSET(AdaptiveCell, weight, 36);

/* A portal plane as a unit square: x = origin + s * axis_s + t * axis_t, s, t in [0, 1). */
typedef struct {
    fen_float4 origin;  /* xyz (m); w: area of the frame (m^2) */
    fen_float4 axis_s;  /* xyz: the frame's first side (m) */
    fen_float4 axis_t;  /* xyz: its second side (m) */
    fen_float4 normal;  /* xyz: unit normal of the plane; w: as_uint first portal triangle */
    fen_u32 triangles;  /* the group's portal triangles: [first, first + triangles) */
    fen_u32 pad0;
    fen_u32 pad1;
    fen_u32 pad2;
} PortalFrame;
FEN_ASSERT_SIZE(PortalFrame, 80);
FEN_ASSERT_OFFSET(PortalFrame, triangles, 64);

typedef struct {
    fen_float4 sun_weight;    /* rgb: E times the cone factor -- a sun path's weight per unit cell weight */
    fen_u32 cell_alias_shift; /* the cell alias table has 2^(32 - shift) columns */
    fen_u32 cells;
    fen_u32 portal_base;      /* 1: disk paths whose line crosses a portal are rejected (the portals' own cells emit them) */
    fen_u32 walk_part;        /* the first of the openings' walks' FEN_WALK_PARTS statistics parts: FEN_CELL_PARTS x cells */
} AdaptiveParams;
FEN_ASSERT_SIZE(AdaptiveParams, 32);
FEN_ASSERT_OFFSET(AdaptiveParams, cell_alias_shift, 16);
FEN_ASSERT_OFFSET(AdaptiveParams, portal_base, 24);
FEN_ASSERT_OFFSET(AdaptiveParams, walk_part, 28);

FEN_NS_END

#endif /* FEN_EMISSION_H */
