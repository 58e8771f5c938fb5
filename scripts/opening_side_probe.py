#!/usr/bin/env python3
"""A probe for guiding: kernels that estimate the light reflected outside from the openings' side.

Writes a copy of kernels/ (for FEN_KERNEL_DIR) in which adaptive emission's fused kernel splits the
light that reaches the image in two parts, each estimated by its own paths (docs/results/guiding.md,
"Light reflected outside, estimated from the openings' side"):

- *Through the openings* (a share S of the path indices): a point on one of the opening aim's
  panes (DESIGN.md §3.5; a triangle and side by area times the side's learned weight), a cosine
  direction outwards, and the radiance arriving there along it: the sky seen straight through the
  pane, or a path traced outwards whose every diffuse vertex takes the sun and the sky by
  next-event rays (glass blocks them and ends the walk; roulette from its second vertex). The path
  then goes in from the pane, through the glass's transmittance, as a light path that has bounced.
- *By light paths* (the rest, their weight over 1 - S): everything else -- the sun straight
  through glass, light through glass the aim does not list, light that glass reflected outside.
  A light path that crosses one of the listed pane sides as the first glass it meets, after a
  diffuse bounce or straight from the sky, ends there: that light is the other part's.

Both parts are unbiased and disjoint, so the image is; the opening aim's mixture is off (the light it
aims at is the other part's). Not something to ship: the share is fixed, the outward direction is
the cosine's, and only the fused kernel is edited (render with --kernels fused, the default on a
CPU). What it measures is how far an estimate from the openings' side could take the scenes lit by
light reflected outside.

    python3 scripts/opening_side_probe.py --share 0.9 --out out/probe/s90
    FEN_KERNEL_DIR=out/probe/s90 build/fenestra render scenes/courtyard.gltf --time 20 ...

--first-inside makes a path from a pane take its first vertex inside as a light path's first
vertex (the guide steers it, weight windows split it there) rather than as a later one.
--sky-through lines leaves the sky seen straight through a listed pane to the light paths (adaptive
emission's learned cells) instead of the openings' walk.
--part openings or lines keeps only that part's contributions (the other's paths are still traced,
their weight zero), to see which part the noise comes from. The edits anchor on lines of
kernels/lib/{shade_path,fused_kernel,emit_adaptive,connect_path}.h and kernels/emit_adaptive.cl; if
one changes, this script says which anchor it missed.
"""
import argparse
import os
import shutil
import sys

HEADER = r"""/* opening_side.h -- written by scripts/opening_side_probe.py (a probe; not part of the renderer).
 * The light reflected outside, estimated from the openings' side (the script's docstring). */
#ifndef OSP_OPENING_SIDE_H
#define OSP_OPENING_SIDE_H

#include "lib/fresnel.h"
#include "lib/opening_aim.h"
#include "lib/ray_offset.h"
#include "lib/sampling.h"
#include "lib/surface_hit.h"
#include "lib/texture.h"

#ifdef OSP_PROBE
#define OSP_SHARE %(share)sf
#define OSP_KEEP_OPENINGS %(keep_openings)d
#define OSP_KEEP_LINES %(keep_lines)d
#define OSP_FIRST_INSIDE %(first_inside)d
#define OSP_SKY_THROUGH %(sky_through)d /* the sky seen straight through a listed pane is this part's */
#define OSP_MAX_VERTICES 16u
#define OSP_NO_PART 0x7fffffffu /* beta.w of a path through the openings: no emission cell */
/* PathState.flags, free while no annual study tags sky patches: */
#define OSP_PATH_GLASS_OUTSIDE 128u /* glass reflected it while it was outside */
#define OSP_SPLIT_GLASS_OUTSIDE (1u << 23) /* ... kept in SplitState.count for its branches */

/* Whether x, on glass that a path arriving along dir crosses, lies on a listed pane side. */
static inline int osp_listed(global const OpeningAim* aim, float3 x, float3 dir)
{
    for (uint i = 0u; i < aim->triangles; ++i) {
        const global AimTriangle* t = aim->tri + i;
        const float3 nt = t->normal.xyz;
        const float side_weight = dot(dir, nt) < 0.0f ? t->e1.w : t->e2.w;
        if (!(side_weight > 0.0f))
            continue;
        const float3 d = x - t->p0.xyz;
        if (fabs(dot(d, nt)) > 1e-4f * sqrt(t->p0.w) + 1e-5f)
            continue;
        const float3 e1 = t->e1.xyz, e2 = t->e2.xyz;
        const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), q1 = dot(d, e1), q2 = dot(d, e2);
        const float den = d11 * d22 - d12 * d12;
        const float a = (d22 * q1 - d12 * q2) / den, b = (d11 * q2 - d12 * q1) / den;
        if (a >= -1e-5f && b >= -1e-5f && a + b <= 1.0f + 1e-5f)
            return 1;
    }
    return 0;
}

static inline int osp_blocked(global const BvhNode* nodes, global const TriPacket4* packets, float3 o, float3 d)
{
    const RayPre r = ray_setup(o, d, 0.0f, INFINITY, FEN_BVH_WIDTH);
    return bvh_intersect_any(nodes, packets, &r);
}

/* Fills *p with a path that starts inside at a listed pane side; returns 0 when it carries nothing. */
static inline int osp_path(global const RenderParams* params, const Sky* sky, float3 sun_weight,
                           global const OpeningAim* aim, global const BvhNode* nodes,
                           global const TriPacket4* packets, const SurfaceMaterials* sm, ulong path, PathState* p,
                           RngBlock pick, ulong* rays)
{
    path_start(p, path);
    p->beta = (float4)(0.0f, 0.0f, 0.0f, as_float(OSP_NO_PART));
    float total = 0.0f;
    for (uint i = 0u; i < aim->triangles; ++i)
        total += aim->tri[i].p0.w * (fmax(aim->tri[i].e1.w, 0.0f) + fmax(aim->tri[i].e2.w, 0.0f));
    if (!(total > 0.0f))
        return 0;
    /* a triangle and side by area times the side's weight */
    float r = fen_u32_to_unit(pick.y) * total, chosen = 0.0f;
    uint k = 0u;
    int front = 1;
    for (uint i = 0u; i < aim->triangles; ++i) {
        const global AimTriangle* t = aim->tri + i;
        const float wf = t->p0.w * fmax(t->e1.w, 0.0f), wb = t->p0.w * fmax(t->e2.w, 0.0f);
        if (wf > 0.0f) {
            k = i; front = 1; chosen = wf;
            if (r < wf)
                break;
        }
        r -= wf;
        if (wb > 0.0f) {
            k = i; front = 0; chosen = wb;
            if (r < wb)
                break;
        }
        r -= wb;
    }
    const global AimTriangle* t = aim->tri + k;
    const RngBlock b = rng_path_bits(params->seed, p->path_lo, p->path_hi, 0, FEN_RNG_EMIT);
    const float su = sqrt(fen_u32_to_unit(b.x)), v2 = fen_u32_to_unit(b.y);
    const float3 w = t->p0.xyz + (su * (1.0f - v2)) * t->e1.xyz + (su * v2) * t->e2.xyz;
    const float3 n_out = front ? t->normal.xyz : -t->normal.xyz;
    const float3 wo = sample_cosine_hemisphere(n_out, fen_u32_to_unit(b.z), fen_u32_to_unit(b.w));
    /* the pane's glass (its transmittance), met from a millimetre inside along its normal */
    *rays += 1;
    const SurfaceHit g = closest_surface(nodes, packets, w - n_out * 1e-3f, n_out);
    if (as_uint(g.normal.w) == FEN_INVALID_ID)
        return 0;
    const global DevMaterial* gm = sm->materials + sm->prim_material[as_uint(g.normal.w)];
    if (!material_is_glass(gm))
        return 0;
    /* the radiance arriving at the pane along -wo: the sky straight through it, or what a path traced
       outwards finds, the sun and the sky by next-event rays at each diffuse vertex */
    float3 L = (float3)(0.0f), throughput = (float3)(1.0f);
    float3 o = offset_ray_origin(g.pos.xyz, g.pos.w, g.normal.xyz, wo), d = wo;
    for (uint i = 0u; i < OSP_MAX_VERTICES; ++i) {
        *rays += 1;
        const SurfaceHit h = closest_surface(nodes, packets, o, d);
        if (as_uint(h.normal.w) == FEN_INVALID_ID) {
            if (i == 0u && OSP_SKY_THROUGH)
                L += (float3)(sky_eval(sky, d)); /* the sky's (the sun's disk stays the light paths') */
            break; /* past the first vertex the sky came by its next-event ray */
        }
        const uint prim = as_uint(h.normal.w);
        const global DevMaterial* m = sm->materials + sm->prim_material[prim];
        if (material_is_glass(m))
            break;
        const float3 y = h.pos.xyz;
        const float3 n = dot(d, h.normal.xyz) < 0.0f ? h.normal.xyz : -h.normal.xyz;
        const float3 albedo = surface_albedo(sm, m, prim, y);
        const RngBlock a = rng_path_bits(params->seed, p->path_lo, p->path_hi, i, FEN_RNG_DIRECT_SUN);
        const RngBlock c = rng_path_bits(params->seed, p->path_lo, p->path_hi, i, FEN_RNG_EMIT_PORTAL);
        float3 E = (float3)(0.0f);
        const float3 to_sun = -sun_direction(params, fen_u32_to_unit(a.x), fen_u32_to_unit(a.y));
        const float cs = dot(n, to_sun);
        if (cs > 0.0f && (sun_weight.x > 0.0f || sun_weight.y > 0.0f || sun_weight.z > 0.0f)) {
            *rays += 1;
            if (!osp_blocked(nodes, packets, offset_ray_origin(y, h.pos.w, h.normal.xyz, to_sun), to_sun))
                E += sun_weight * cs;
        }
        const float3 ds = sample_cosine_hemisphere(n, fen_u32_to_unit(a.z), fen_u32_to_unit(a.w));
        const float Ls = sky_eval(sky, ds);
        if (Ls > 0.0f) {
            *rays += 1;
            if (!osp_blocked(nodes, packets, offset_ray_origin(y, h.pos.w, h.normal.xyz, ds), ds))
                E += (float3)(Ls * FEN_PI);
        }
        throughput *= albedo;
        L += throughput * E * (1.0f / FEN_PI);
        if (i >= 1u) {
            const float q = fmax(albedo.x, fmax(albedo.y, albedo.z));
            if (!(fen_u32_to_unit(c.z) < q))
                break;
            throughput /= q;
        }
        d = sample_cosine_hemisphere(n, fen_u32_to_unit(c.x), fen_u32_to_unit(c.y));
        o = offset_ray_origin(y, h.pos.w, h.normal.xyz, d);
    }
    if (!(L.x > 0.0f || L.y > 0.0f || L.z > 0.0f))
        return 0;
    const float3 in = -wo;
    const float3 trans = gm->transmission.xyz * (1.0f - fresnel_dielectric(dot(in, g.normal.xyz), gm->transmission.w));
    /* L cos / (density of the point, chosen / (total A_t), times cos / pi) */
    const float3 beta = L * (FEN_PI * t->p0.w * total / chosen) * trans * (OSP_KEEP_OPENINGS / OSP_SHARE);
    p->org = (float4)(offset_ray_origin(g.pos.xyz, g.pos.w, g.normal.xyz, in), 0.0f);
    p->dir = (float4)(in, 0.0f);
    p->beta = (float4)(beta, as_float(OSP_NO_PART));
    p->depth = 2; /* as a light path that bounced once outside */
    /* --first-inside: its first vertex inside is a first vertex (the guide steers it, weight windows
       split it); else a later one */
    p->flags |= (OSP_FIRST_INSIDE ? 0u : FEN_PATH_BRANCHED) | (FEN_PATH_OPENING_OTHER << FEN_PATH_OPENING_SHIFT);
    return 1;
}
#define OSP_AIM_OFF 1
#else
#define OSP_AIM_OFF 0
#endif /* OSP_PROBE */
#endif /* OSP_OPENING_SIDE_H */
"""

# (file, anchor, replacement): each anchor must occur exactly once in its file
EDITS = [
    ("emit_adaptive.cl", '#include "lib/emit_adaptive.h"\n',
     '#define OSP_PROBE 1\n#include "lib/emit_adaptive.h"\n'),
    # a sun path is marked, so that the sky straight through a listed pane can be the openings' part
    ("lib/emit_adaptive.h", """    p->beta = (float4)(weight, as_float(part));
    return 1;""", """    p->beta = (float4)(weight, as_float(part));
#ifdef OSP_PROBE
    if (dirs.z == 0.0f)
        p->flags |= OSP_PATH_SUN;
#endif
    return 1;"""),
    ("lib/emit_adaptive.h", '#include "lib/emit_source.h"\n',
     '#include "lib/emit_source.h"\n#define OSP_PATH_SUN (1u << 22) /* PathState.flags: a sun path (no annual study) */\n'),
    ("lib/shade_path.h", '#include "lib/texture.h"\n', '#include "lib/texture.h"\n#include "lib/opening_side.h"\n'),
    # the opening aim's mixture is off: the light it aims at is the openings' part
    ("lib/shade_path.h", """    global const OpeningAim* aim = guide->aim;
    if (aim->triangles == 0u || path_opening(p->flags) != 0u)
        return -1;""", """    global const OpeningAim* aim = guide->aim;
    if (OSP_AIM_OFF || aim->triangles == 0u || path_opening(p->flags) != 0u)
        return -1;"""),
    ("lib/shade_path.h", """            next = dir - 2.0f * cos_i * ng;
            p->flags |= FEN_PATH_REFLECTED;""", """            next = dir - 2.0f * cos_i * ng;
            p->flags |= FEN_PATH_REFLECTED;
#ifdef OSP_PROBE
            if (path_opening(p->flags) == 0u)
                p->flags |= OSP_PATH_GLASS_OUTSIDE;
#endif"""),
    ("lib/shade_path.h", """            p->flags = opening_enter(guide->aim, guide->opening_prims, guide->opening_stats, p->flags, prim, dir, ng,
                                     p->beta.xyz, window_units(params, cam));""", """#ifdef OSP_PROBE
            /* the openings' part: a light path's first glass a listed pane side, after a bounce or
               straight from the sky, and no glass reflected it outside */
            if (path_opening(p->flags) == 0u &&
                ((p->flags & FEN_PATH_BRANCHED) || (OSP_SKY_THROUGH && !(p->flags & OSP_PATH_SUN))) &&
                !(p->flags & OSP_PATH_GLASS_OUTSIDE) && osp_listed(guide->aim, x, dir))
                alive = 0;
            else
#endif
            p->flags = opening_enter(guide->aim, guide->opening_prims, guide->opening_stats, p->flags, prim, dir, ng,
                                     p->beta.xyz, window_units(params, cam));"""),
    ("lib/shade_path.h", """    s->count = k | (p->flags & ~FEN_SPLIT_COUNT_MASK); /* the opening code (FEN_PATH_OPENING_SHIFT) */""",
     """    s->count = k | (p->flags & ~FEN_SPLIT_COUNT_MASK); /* the opening code (FEN_PATH_OPENING_SHIFT) */
#ifdef OSP_PROBE
    s->count |= (p->flags & OSP_PATH_GLASS_OUTSIDE) ? OSP_SPLIT_GLASS_OUTSIDE : 0u;
#endif"""),
    ("lib/shade_path.h", """        if (s->next >= (s->count & FEN_SPLIT_COUNT_MASK))""",
     """#ifdef OSP_PROBE
        if (s->next >= (s->count & FEN_SPLIT_COUNT_MASK & ~OSP_SPLIT_GLASS_OUTSIDE))
#else
        if (s->next >= (s->count & FEN_SPLIT_COUNT_MASK))
#endif"""),
    ("lib/shade_path.h", """        p->flags = (p->flags & FEN_SPLIT_COUNT_MASK) | (s->count & ~FEN_SPLIT_COUNT_MASK);""",
     """        p->flags = (p->flags & FEN_SPLIT_COUNT_MASK) | (s->count & ~FEN_SPLIT_COUNT_MASK);
#ifdef OSP_PROBE
        p->flags = (p->flags & ~OSP_PATH_GLASS_OUTSIDE) |
                   ((s->count & OSP_SPLIT_GLASS_OUTSIDE) ? OSP_PATH_GLASS_OUTSIDE : 0u);
#endif"""),
    ("lib/connect_path.h", '#include "lib/transmittance.h"\n',
     '#include "lib/transmittance.h"\n#include "lib/opening_side.h"\n'),
    # a path through the openings has no emission cell to teach
    ("lib/connect_path.h", """        cell_stats_add(cell_stats, part & ~FEN_PART_ESTIMATE_ONLY, steer, params->fixed_scale,
                       params->stats_scale, counters);""", """#ifdef OSP_PROBE
        if (part != OSP_NO_PART)
#endif
        cell_stats_add(cell_stats, part & ~FEN_PART_ESTIMATE_ONLY, steer, params->fixed_scale,
                       params->stats_scale, counters);"""),
    ("lib/fused_kernel.h", """#if FEN_EMITTER_REJECTS
            if (!FEN_EMITTER_EMIT(params, &emitter, path, &p))
                continue;
#else""", """#if defined(OSP_PROBE)
            const RngBlock pick = rng_path_bits(params->seed, (uint)path, (uint)(path >> 32), 0, FEN_RNG_WINDOW);
            if (opening_aim->triangles && fen_u32_to_unit(pick.x) < OSP_SHARE) {
                if (!osp_path(params, &emitter.sky, emitter.params->sun_weight.xyz, opening_aim, nodes, packets, &sm,
                              path, &p, pick, &extension))
                    continue;
            } else {
                if (!FEN_EMITTER_EMIT(params, &emitter, path, &p))
                    continue;
                if (opening_aim->triangles)
                    p.beta.xyz *= OSP_KEEP_LINES / (1.0f - OSP_SHARE);
            }
#elif FEN_EMITTER_REJECTS
            if (!FEN_EMITTER_EMIT(params, &emitter, path, &p))
                continue;
#else"""),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--share", type=float, default=0.9,
                    help="the share of path indices that start at the openings, (0, 1) (default 0.9)")
    ap.add_argument("--part", choices=("both", "openings", "lines"), default="both",
                    help="whose contributions to keep (default both: the image)")
    ap.add_argument("--first-inside", action="store_true",
                    help="a path from a pane makes its first vertex inside a first vertex: the guide steers it "
                         "and weight windows split it there (default: a later vertex, as a light path's after a bounce)")
    ap.add_argument("--sky-through", choices=("openings", "lines"), default="openings",
                    help="whose is the sky seen straight through a listed pane (default openings: the walk's "
                         "first look; lines: the light paths keep it, adaptive emission's learned cells)")
    ap.add_argument("--kernels", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "kernels"))
    ap.add_argument("--out", required=True, help="the kernel folder to write (replaced)")
    a = ap.parse_args()
    if not 0.0 < a.share < 1.0:
        sys.exit(f"opening_side_probe.py: --share {a.share} is not in (0, 1)")
    header = HEADER % {"share": repr(a.share), "keep_openings": int(a.part != "lines"),
                       "keep_lines": int(a.part != "openings"), "first_inside": int(a.first_inside),
                       "sky_through": int(a.sky_through == "openings")}
    if os.path.exists(a.out):
        shutil.rmtree(a.out)
    shutil.copytree(a.kernels, a.out)
    sources = {}
    for name, old, new in EDITS:
        path = os.path.join(a.out, name)
        src = sources.get(path) or open(path).read()
        if src.count(old) != 1:
            sys.exit(f"opening_side_probe.py: {path}: expected one '{old.splitlines()[0].strip()}', "
                     f"found {src.count(old)}")
        sources[path] = src.replace(old, new)
    for path, src in sources.items():
        open(path, "w").write(src)
    open(os.path.join(a.out, "lib", "opening_side.h"), "w").write(header)
    print(f"wrote {a.out}: share {a.share} of the paths start at the openings"
          f"{', their first vertex inside a first vertex' if a.first_inside else ''}; the sky seen straight through "
          f"a pane: the {a.sky_through}' part; keeping {a.part}")


if __name__ == "__main__":
    main()
