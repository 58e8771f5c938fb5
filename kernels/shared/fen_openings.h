/* fen_openings.h — device layout of the opening aim (DESIGN.md §3.5; device half: lib/opening_aim.h,
 * learning: host/scatter/opening_aim.h).
 *
 * The scene's openings are its glass (thin glass, or an IOR-1 "opening" material), grouped into
 * panes of connected, coplanar triangles. A path remembers in its flags the first glass it went
 * through (FEN_PATH_OPENING_SHIFT): 0 while it has crossed none -- outside -- then 2 j + side + 1
 * if it entered opening j from that side (0: from where the pane's normal, its first triangle's,
 * points; 1: from the other) after a diffuse bounce, else FEN_PATH_OPENING_OTHER (glass that is no
 * learned opening, or a path straight from the sky: what the aim does not change). The branches of
 * a split start from the code the path had at the split (SplitState.count). Each opening side sums,
 * in 128-bit fixed point, the weight's luminance of the bounced paths that entered through it and
 * the luminance of the camera contributions they made afterwards; their ratio is what a unit of
 * light sent in there from outside brings to the image, and the host aims at the openings by it.
 *
 * The aim: at every diffuse vertex of a path still outside, one sample of a mixture -- the cosine
 * with probability cosine_share, else a uniform point on one of the aim's triangles, chosen in
 * proportion to its weight from the vertex's side times the solid angle it subtends there (by its
 * centroid) -- the weight divided by the mixture's density, which sums every triangle the direction
 * passes through. Unbiased wherever the cosine is non-zero.
 * Invariants: OpeningAim.triangles <= FEN_AIM_MAX_TRIS; opening_prims sorted by primitive; a code
 * fits the 8 bits above the sky patch's 16 (FEN_PATH_PATCH_SHIFT).
 */
#ifndef FEN_OPENINGS_H
#define FEN_OPENINGS_H

#include "shared/fen_types.h"

#define FEN_AIM_MAX_TRIS 32         /* triangles the aim can hold: each costs every outside vertex a test */
#define FEN_OPENING_MAX 127         /* openings learned; 2 j + side + 1 <= 254 */
#define FEN_PATH_OPENING_SHIFT 24u  /* PathState.flags bits 24..31: the opening side entered */
#define FEN_PATH_OPENING_OTHER 255u /* entered through glass that is not a learned opening */
/* Connection.to_cam.w: the path's opening code, with these bits where its first diffuse vertex drew
   from the aim's mixture (FEN_PATH_MIXED) and drew a direction where the aim's part of the density
   was the larger (FEN_PATH_AIM_REGION) -- what the aim's share is learned from */
#define FEN_OPENING_CONNECTION_AIM_REGION 0x100u
#define FEN_OPENING_CONNECTION_MIXED 0x200u

/* Statistics per opening side, fen_u64 words, 128-bit fixed point at FEN_GUIDE_WINDOW_SCALE times
   RenderParams.fixed_scale (the weight windows' units, lib/shade_path.h window_units) */
#define FEN_OPENING_DELIVERED_LO 0 /* luminance of the camera contributions made after entering */
#define FEN_OPENING_ENTERED_LO 2   /* luminance of the weight on entering, over A_pix */
#define FEN_OPENING_ENTRIES 4      /* paths (or branches) that entered */
#define FEN_OPENING_STATS_WORDS 5

FEN_NS_BEGIN

typedef struct {
    fen_float4 p0;     /* xyz: a corner (m); w: the triangle's area (m^2) */
    fen_float4 e1;     /* xyz: p1 - p0; w: the aim's weight seen from the front (where normal points) */
    fen_float4 e2;     /* xyz: p2 - p0; w: ... from the back */
    fen_float4 normal; /* xyz: unit, along cross(e1, e2) as lib/surface_hit.h's; w: the glass primitive's
                          index, as bits (fen_as_float) */
} AimTriangle;
FEN_ASSERT_SIZE(AimTriangle, 64);
FEN_ASSERT_OFFSET(AimTriangle, normal, 48);

typedef struct {
    fen_u32 triangles;     /* in tri[]; 0: no aim (every vertex scatters as without it) */
    fen_u32 prims;         /* (primitive, opening) pairs in opening_prims; 0: nothing is learned */
    fen_f32 cosine_share;  /* the cosine's share of the mixture past a path's first diffuse vertex, in (0, 1) */
    fen_f32 first_share;   /* ... at its first: the same, or learned by the host (host/scatter/opening_aim.cpp
                              learnShare) */
    AimTriangle tri[FEN_AIM_MAX_TRIS];
} OpeningAim;
FEN_ASSERT_SIZE(OpeningAim, 16 + 64 * FEN_AIM_MAX_TRIS);
FEN_ASSERT_OFFSET(OpeningAim, cosine_share, 8);
FEN_ASSERT_OFFSET(OpeningAim, first_share, 12);
FEN_ASSERT_OFFSET(OpeningAim, tri, 16);

FEN_NS_END

#endif /* FEN_OPENINGS_H */
