/* fen_render.h — device layout of everything the light-tracing wavefront reads and writes.
 *
 * One declaration for host and device (see fen_types.h). The wavefront (DESIGN.md §4) keeps a
 * pool of PathState slots; per iteration: emit_<strategy>.cl refills dead slots (the strategy
 * compiled into it: shared/fen_emission.h), intersect.cl finds each path's next hit, shade.cl
 * connects diffuse hits to the camera (a Connection per slot) and scatters, connect.cl traces the
 * connections and splats them into 128-bit fixed-point pixel accumulators (lib/accumulate.h) --
 * and, for a learning strategy, adds each connection's squared luminance to the emission cell the
 * path started in. camera_pass.cl adds what the camera sees of the sky directly.
 * Invariants: every struct is a multiple of 16 bytes, members ordered 16 -> 8 -> 4 bytes;
 * fen_u64 members sit at 8-byte offsets. All listed in fen_layout.h for the layout probe.
 */
#ifndef FEN_RENDER_H
#define FEN_RENDER_H

#include "shared/fen_bvh.h"
#include "shared/fen_types.h"

#define FEN_MATERIAL_DIFFUSE 0u
#define FEN_MATERIAL_GLASS 1u

/* PathState.flags */
#define FEN_PATH_ALIVE 1u
#define FEN_PATH_SPLIT 2u     /* branches of a split wait in the path's SplitState (lib/shade_path.h) */
#define FEN_PATH_BRANCHED 4u  /* past its first diffuse vertex (where the guide's record is made) */
#define FEN_PATH_REFLECTED 8u /* reflected by glass: no longer straight from the sky (lib/sensor.h's direct light) */
#define FEN_PATH_WAS_SPLIT 16u /* split once (at its first diffuse vertex or, by a weight window, later): never again */
#define FEN_PATH_MIXED 32u      /* its first diffuse vertex drew from the opening aim's mixture (lib/opening_aim.h) */
#define FEN_PATH_AIM_REGION 64u /* ... a direction where the aim's part of the density was the larger */
/* With the openings' walks (RenderParams.openings_share > 0, lib/opening_walk.h): a sun path whose light
   stays the light paths' even where it enters by a listed pane -- set at emission, cleared at its first
   diffuse vertex unless glass reflected it before (no walk's next-event ray finds the sun by a mirror) */
#define FEN_PATH_SUN_KEPT 128u
/* Bits FEN_PATH_PATCH_SHIFT to 23: the sky patch the path started from, in a daylight-coefficient
   run (lib/sky_patch.h; set at emission, kept by every later step, which only sets and clears the
   bits below); bits 24..31: the opening it entered by (shared/fen_openings.h) */
#define FEN_PATH_PATCH_SHIFT 8u
#define FEN_PATH_PATCH_MASK 0xffffu

/* Counters (fen_u64 each), read back after every iteration. */
#define FEN_CTR_NEXT_PATH 0        /* next path index to emit (the emit kernel's ticket) */
#define FEN_CTR_ALIVE 1            /* paths alive after shading (reset by the host) */
#define FEN_CTR_EXTENSION_RAYS 2
#define FEN_CTR_SHADOW_RAYS 3
#define FEN_CTR_CAMERA_RAYS 4
#define FEN_CTR_BAD_CONTRIBUTIONS 5 /* NaN/inf contributions dropped: must stay 0 */
#define FEN_CTR_OVERFLOWS 6        /* contributions beyond the 128-bit range: must stay 0 */
#define FEN_CTR_MAX_DEPTH 7        /* paths cut by --max-bounces (bias, reported) */
#define FEN_CTR_EMITTED 8          /* paths that started (a rejected portal candidate does not) */
#define FEN_CTR_CAMERA_GLASS_CUT 9 /* camera samples stopped after 16 glass sheets (bias, reported) */
#define FEN_CTR_STATS_OVERFLOWS 10 /* emission statistics beyond their 128-bit range (dropped) */
#define FEN_CTR_CUT_FLUX_LO 11     /* luminous flux of the paths --max-bounces cut (128-bit fixed */
#define FEN_CTR_CUT_FLUX_HI 12     /*   point at fixed_scale): the light the cap removed */
#define FEN_CTR_DIFFUSE_VERTICES 13 /* diffuse vertices the paths scattered at (split branches each count) */
#define FEN_CTR_GUIDED_VERTICES 14  /* ... and of them, those whose direction the guide drew */
#define FEN_CTR_SPLIT_BRANCHES 15   /* branches made by splitting (--split or weight windows) */
#define FEN_CTR_WINDOW_CULLS 16     /* paths a weight window's roulette ended */
#define FEN_CTR_OPENING_WALKS 17    /* path indices given to the openings' walks (lib/opening_walk.h) */
#define FEN_CTR_OPENING_WALK_RAYS 18 /* rays their walks outside traced (not in the extension rays) */
#define FEN_CTR_COUNT 19


FEN_NS_BEGIN

/* DevMaterial.tex_flags: a base-colour texture (lib/texture.h) and how it is sampled */
#define FEN_TEX_PRESENT 1u
#define FEN_TEX_NEAREST 2u      /* magFilter NEAREST; else bilinear */
#define FEN_TEX_WRAP_S_SHIFT 2u /* 2 bits each: FEN_WRAP_* */
#define FEN_TEX_WRAP_T_SHIFT 4u
#define FEN_WRAP_REPEAT 0u
#define FEN_WRAP_CLAMP 1u
#define FEN_WRAP_MIRROR 2u
/* The texel buffer starts with the sRGB decode table: FEN_SRGB_TABLE floats (as uint), the linear
   value of each 8-bit code; the texels (r | g << 8 | b << 16, sRGB-encoded) follow. */
#define FEN_SRGB_TABLE 256u

typedef struct {
    fen_float4 albedo;        /* rgb: Lambertian albedo (the factor, with a texture); w: as_uint kind (FEN_MATERIAL_*) */
    fen_float4 transmission;  /* rgb: glass transmittance T; w: index of refraction */
    fen_u32 tex_offset;       /* first texel in the texel buffer (after the decode table) */
    fen_u32 tex_width;
    fen_u32 tex_height;
    fen_u32 tex_flags;        /* FEN_TEX_*; 0: no texture */
} DevMaterial;
FEN_ASSERT_SIZE(DevMaterial, 48);
FEN_ASSERT_OFFSET(DevMaterial, transmission, 16);
FEN_ASSERT_OFFSET(DevMaterial, tex_offset, 32);
FEN_ASSERT_OFFSET(DevMaterial, tex_flags, 44);

/* Pinhole camera, box pixel filter. Image plane at unit distance along `forward`. */
typedef struct {
    fen_float4 position;  /* xyz (m) */
    fen_float4 forward;   /* xyz unit; w: tan(horizontal fov / 2) */
    fen_float4 right;     /* xyz unit; w: tan(vertical fov / 2) */
    fen_float4 up;        /* xyz unit; w: pixel area on the image plane at unit distance */
    fen_u32 width;
    fen_u32 height;
    fen_u32 pad0;
    fen_u32 pad1;
} DevCamera;
FEN_ASSERT_SIZE(DevCamera, 80);
FEN_ASSERT_OFFSET(DevCamera, width, 64);

/* What intersect.cl tells shade.cl about a path's next surface. */
typedef struct {
    fen_float4 pos;     /* xyz: hit point (m); w: how far a ray leaving it must start off the surface */
    fen_float4 normal;  /* xyz: unit geometric normal; w: as_uint primitive, FEN_INVALID_ID = miss */
} SurfaceHit;
FEN_ASSERT_SIZE(SurfaceHit, 32);

typedef struct {
    fen_float4 org;   /* xyz: ray origin (m); w: the first-bounce guide's factor g for what the path
                         delivers from now on, 0 before its first diffuse vertex or without a guide */
    fen_float4 dir;   /* xyz: unit direction of travel; w: as_uint the guide's slot and box it left
                         that vertex through (lib/guide.h) */
    fen_float4 beta;  /* rgb: path weight (flux per path, in lm with luminance-valued channels);
                         w: as_uint emission cell the path started in (learning strategies) */
    fen_u32 path_lo;  /* path index, 64-bit: the RNG counter of the path */
    fen_u32 path_hi;
    fen_u32 depth;    /* surface interactions so far */
    fen_u32 flags;    /* FEN_PATH_* */
} PathState;
FEN_ASSERT_SIZE(PathState, 64);
FEN_ASSERT_OFFSET(PathState, path_lo, 48);

/* A path split at a diffuse vertex (lib/shade_path.h; its first, or a later one by a weight window):
   where the branches still to run start from. Kept beside the path (a slot's own buffer in the
   wavefront, registers in the fused kernel), read only when a branch ends. */
typedef struct {
    fen_float4 pos;     /* xyz: the vertex (m); w: how far a ray leaving it must start off the surface */
    fen_float4 normal;  /* xyz: unit normal on the side the light arrived at; w: as_uint primitive */
    fen_float4 beta;    /* rgb: each branch's weight on arrival; w: as_uint the vertex's guide slot
                           (first vertex), or FEN_SPLIT_LATER */
    fen_u32 depth;      /* interactions before the vertex */
    fen_u32 next;       /* the next branch to start */
    fen_u32 count;      /* branches in all (bits 0..23, FEN_SPLIT_COUNT_MASK); bits 24..31: the path's
                           opening code at the split (shared/fen_openings.h), which every branch
                           starts from */
    fen_u32 path_hi;    /* the path's own path_hi; branch b puts b in its top byte (its random numbers) */
} SplitState;
FEN_ASSERT_SIZE(SplitState, 64);
/* SplitState.beta.w of a split at a later vertex: its branches scatter as later vertices do and keep
   the path's first-vertex guide record (no slot is a valid index this large) */
#define FEN_SPLIT_LATER 0xffffffffu
/* The most branches one split makes (--split, --adaptive-window-split): a branch's number is the top
   byte of its path_hi, so branch 256 would draw branch 0's random numbers */
#define FEN_MAX_BRANCHES 255
#define FEN_SPLIT_COUNT_MASK 0xffffffu
FEN_ASSERT_OFFSET(SplitState, depth, 48);

typedef struct {
    fen_float4 org;     /* xyz: shadow-ray origin (offset off the surface); w: as_uint pixel or FEN_INVALID_ID */
    fen_float4 to_cam;  /* xyz: camera position - org, the segment t in (0, 1); w: as_uint the path's
                           opening word (lib/opening_aim.h opening_connection_word) */
    fen_float4 value;   /* rgb: contribution to the pixel (cd/m^2 x paths) if nothing blocks it;
                           w: the path's beta.w (its emission cell) */
    fen_float4 guide;   /* the path's first-bounce guide record (PathState org.w, dir.w): x the
                           factor g (0: none), y as_uint the global leaf (fen_guide.h); with
                           weight windows z their statistics' scale (else 0), w as_uint the first
                           vertex's slot | FEN_GUIDE_WINDOW_SQUARED (lib/guide.h guide_window_word) */
} Connection;
FEN_ASSERT_SIZE(Connection, 64);
FEN_ASSERT_OFFSET(Connection, guide, 48);

/* The sky's node arrays on the device (host/sky/sky_tables.h, lib/sky.h): each axis's buffer holds
   its n node angles, then, from word n on, what lets a lookup skip most of a binary search over
   them: the buckets' scale (float, buckets per radian), their count B (uint), and B pairs of
   uints (lo, hi), bucket b = floor(x * scale) (clamped to B - 1) -- the search for any x in it
   needs only [lo, hi). */
#define FEN_SKY_SEARCH_SCALE 0
#define FEN_SKY_SEARCH_BUCKETS 1
#define FEN_SKY_SEARCH_HINTS 2

/* Per-batch parameters of the wavefront, in a one-element buffer (never a by-value struct
   argument). What an emission strategy needs beyond the scene lives in its own buffer
   (shared/fen_emission.h). */
typedef struct {
    fen_float4 sphere;       /* xyz: centre of the scene's bounding sphere; w: its radius (m) */
    fen_float4 sun_dir;      /* xyz: direction the sunlight travels (unit); w: cos(angular radius) */
    fen_u64 path_end;        /* one past the last path index of this batch */
    fen_u32 seed;
    fen_u32 max_depth;
    fen_f32 fixed_scale;     /* pixel accumulators hold round(value * fixed_scale), 128-bit */
    fen_f32 stats_scale;     /* cell statistics hold round(Y^2 * stats_scale), 128-bit; 0: none */
    fen_u32 sky_theta_nodes; /* the scene's sky, as the camera pass reads it */
    fen_u32 sky_phi_nodes;
    fen_u32 pool_size;
    fen_f32 openings_share;  /* the share of path indices that start on the opening aim's panes
                                (lib/opening_walk.h, adaptive only); 0: none */
    fen_u32 batch;           /* batch number, for the camera pass's random numbers */
    fen_u32 rr_depth;        /* Russian roulette from this surface interaction on (lib/shade_path.h) */
    fen_f32 split_weight;    /* a path splits at its first diffuse vertex into floor(Y(beta) / this) */
    fen_u32 split_max;       /* ... branches, at most this many (1: never) */
    fen_u32 pick_offset;     /* the emission table pick of path i: pick_offset + i pick_step (mod 2^32), */
    fen_u32 pick_step;       /*   a lattice over the batch (lib/emit_source.h); pick_step 0: random bits */
} RenderParams;
FEN_ASSERT_SIZE(RenderParams, 96);
FEN_ASSERT_OFFSET(RenderParams, path_end, 32);
FEN_ASSERT_OFFSET(RenderParams, seed, 40);
FEN_ASSERT_OFFSET(RenderParams, batch, 72);
FEN_ASSERT_OFFSET(RenderParams, rr_depth, 76);
FEN_ASSERT_OFFSET(RenderParams, split_weight, 80);
FEN_ASSERT_OFFSET(RenderParams, pick_step, 92);

FEN_NS_END

#endif /* FEN_RENDER_H */
