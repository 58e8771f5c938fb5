#!/usr/bin/env python3
"""A bound for guiding: kernels that aim at the openings the light must pass, told where they are.

Writes a copy of kernels/ (for FEN_KERNEL_DIR) in which every diffuse vertex inside a given region
scatters by a one-sample mixture of the cosine (share S) and a uniform point on one of the region's
target rectangles (the rest, each chosen by its solid angle from the vertex), the weight divided by
the mixture's density (docs/results/guiding.md, "Told where the openings are"). No learning is
needed and the aim is exact wherever the vertex is, so it measures how much better any learned
guide could aim there -- not something to ship: the targets are typed in from the scene's geometry
(scenes/README.md). Unbiased: the cosine share keeps every direction drawable.

    python3 scripts/aim_oracle.py --targets courtyard --vertices every --out out/oracle/courtyard
    FEN_KERNEL_DIR=out/oracle/courtyard build/fenestra render scenes/courtyard.gltf --adaptive-aim off --time 20 ...

Render with --adaptive-aim off: the learned opening aim (DESIGN.md §3.5) acts before the oracle's
edit where it has something to aim at, so with it on the oracle measures the learned aim instead.

--vertices first: only a path's first diffuse vertex (the learned guide's own vertex); every: every
diffuse vertex in a region; later: every vertex in a region but a path's first, which the learned
guide keeps. The guide's records at a first vertex stay as they are (its learning
goes on; its tables are not drawn from in a region). The edit is made by anchoring on lines of
kernels/lib/shade_path.h; if they change, this script says which anchor it missed.
"""
import argparse
import math
import os
import shutil
import sys

# Region: (lo, hi, inside): the vertex (moved 1 cm off its surface, on the side the light arrived
# at) lies inside the box (inside=1) or outside it (0). Rectangle: axis of its normal (0 x, 2 z),
# the plane's coordinate, the side its light comes from (+1/-1 along the axis), u range (x for
# axis z, z for axis x), y range.
HOUSE_BOX = ((0.0, 0.0, 0.0), (10.0, 5.6, 8.0), 0)
HOUSE_UPPER_WINDOWS = [  # the upper storey's windows into the south room and the camera's room
    (2, 8, 1, 1.0, 2.6, 3.7, 5.1), (2, 8, 1, 4.2, 5.8, 3.7, 5.1), (2, 8, 1, 7.4, 9.0, 3.7, 5.1),
    (2, 0, -1, 1.9, 3.1, 3.7, 5.1), (0, 10, 1, 5.4, 6.6, 3.7, 5.1), (0, 0, -1, 5.4, 6.6, 3.7, 5.1)]
HOUSE_OTHER_WINDOWS = [  # the ground floor's, and the upper north-east room's
    (2, 8, 1, 1.0, 2.6, 0.9, 2.3), (2, 8, 1, 4.2, 5.8, 0.9, 2.3), (2, 8, 1, 7.4, 9.0, 0.9, 2.3),
    (2, 0, -1, 1.9, 3.1, 0.9, 2.3), (2, 0, -1, 6.9, 8.1, 0.9, 2.3), (2, 0, -1, 6.9, 8.1, 3.7, 5.1),
    (0, 10, 1, 1.4, 2.6, 0.9, 2.3), (0, 10, 1, 5.4, 6.6, 0.9, 2.3), (0, 10, 1, 1.4, 2.6, 3.7, 5.1),
    (0, 0, -1, 5.4, 6.6, 0.9, 2.3)]
# the upper storey's doorway from the south room into the camera's (north-west) room
HOUSE_DOORWAY = (((0.0, 2.8, 4.0), (10.0, 5.6, 8.0), 1), [(2, 4, 1, 3.8, 4.7, 2.8, 4.9)])
TARGETS = {
    "courtyard": [(((0.0, 0.0, 0.0), (5.0, 2.8, 4.0), 0), [(2, 0, -1, 1.5, 3.5, 0.9, 2.4)])],
    "house-windows": [(HOUSE_BOX, HOUSE_UPPER_WINDOWS)],
    "house-all-windows": [(HOUSE_BOX, HOUSE_UPPER_WINDOWS + HOUSE_OTHER_WINDOWS)],
    "house-doorway": [HOUSE_DOORWAY],
    "house-windows+doorway": [(HOUSE_BOX, HOUSE_UPPER_WINDOWS), HOUSE_DOORWAY],
}

HEADER = """/* oracle.h -- written by scripts/aim_oracle.py (a bound for guiding; not part of the renderer) */
#define ORC_SHARE %(share)sf
#define ORC_GROUPS %(groups)d
#define ORC_N %(n)d
constant float orc_box[ORC_GROUPS][7] = {%(boxes)s};
constant int orc_first[ORC_GROUPS + 1] = {%(first)s};
constant float orc[ORC_N][7] = {%(rects)s};
constant float orc_imp[ORC_N] = {%(imp)s}; /* each rectangle's weight beside its solid angle (--weights) */

static inline float orc_comp(float3 v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }
static inline float3 orc_point(int i, float u, float v)
{
    const float uu = mix(orc[i][3], orc[i][4], u), vv = mix(orc[i][5], orc[i][6], v);
    return (int)orc[i][0] == 2 ? (float3)(uu, vv, orc[i][1]) : (float3)(orc[i][1], vv, uu);
}
/* the first group whose region holds x (side n), or -1 */
static inline int orc_group(float3 x, float3 n)
{
    const float3 p = x + 0.01f * n;
    for (int g = 0; g < ORC_GROUPS; ++g) {
        const int in = p.x > orc_box[g][0] && p.x < orc_box[g][3] && p.y > orc_box[g][1] && p.y < orc_box[g][4] &&
                       p.z > orc_box[g][2] && p.z < orc_box[g][5];
        if (in == (orc_box[g][6] != 0.0f))
            return g;
    }
    return -1;
}
/* each of the group's rectangles' weight seen from x on side n (its solid angle, roughly, times its
   --weights entry; 0 if it faces away or lies behind the surface); returns their sum */
static inline float orc_weights(int g, float3 x, float3 n, float* w)
{
    float W = 0.0f;
    for (int i = orc_first[g]; i < orc_first[g + 1]; ++i) {
        const int a = (int)orc[i][0];
        const float h = orc[i][2] * (orc_comp(x, a) - orc[i][1]);
        const float3 d = orc_point(i, 0.5f, 0.5f) - x;
        const float d2 = dot(d, d);
        const float area = (orc[i][4] - orc[i][3]) * (orc[i][6] - orc[i][5]);
        w[i - orc_first[g]] = h > 0.0f && dot(n, d) > 0.0f ? orc_imp[i] * area * h / (d2 * sqrt(d2)) : 0.0f;
        W += w[i - orc_first[g]];
    }
    return W;
}
/* the density (per sr) with which the rectangles' part draws direction v from x */
static inline float orc_pdf(int g, float3 x, float3 v, const float* w, float W)
{
    float p = 0.0f;
    for (int i = orc_first[g]; i < orc_first[g + 1]; ++i) {
        const float wi = w[i - orc_first[g]];
        const int a = (int)orc[i][0];
        const float va = orc_comp(v, a);
        if (!(wi > 0.0f) || va == 0.0f)
            continue;
        const float t = (orc[i][1] - orc_comp(x, a)) / va;
        const float3 y = x + t * v;
        const float uu = a == 2 ? y.x : y.z;
        if (t > 0.0f && uu >= orc[i][3] && uu <= orc[i][4] && y.y >= orc[i][5] && y.y <= orc[i][6])
            p += (wi / W) * t * t / ((orc[i][4] - orc[i][3]) * (orc[i][6] - orc[i][5]) * fabs(va));
    }
    return p;
}
/* The mixture's scatter at x (side n) in group g: returns alive, *next and the weight as
   scatter_diffuse() would, the weight times cos/pi over the mixture's density. */
static inline int orc_scatter(global const RenderParams* params, PathState* p, float3 albedo, float3 n, float4 u,
                              float3 x, int g, float3* next, VertexTally* t)
{
    float w[ORC_N];
    const float W = orc_weights(g, x, n, w);
    const int alive = scatter_diffuse(params, p, albedo, n, u, next);
    if (!(W > 0.0f))
        return alive;
    const RngBlock bits = rng_path_bits(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_GUIDE);
    float3 v = *next;
    if (alive && fen_u32_to_unit(bits.x) >= ORC_SHARE) {
        float r = fen_u32_to_unit(bits.w) * W;
        int k = orc_first[g + 1] - 1;
        for (int i = orc_first[g]; i < orc_first[g + 1]; ++i) {
            const float wi = w[i - orc_first[g]];
            if (wi > 0.0f && r < wi) {
                k = i;
                break;
            }
            r -= wi;
        }
        while (!(w[k - orc_first[g]] > 0.0f))
            --k;
        v = normalize(orc_point(k, fen_u32_to_unit(bits.y), fen_u32_to_unit(bits.z)) - x);
        t->guided += 1;
    }
    const float c = dot(v, n);
    const float pc = fmax(c, 0.0f) / FEN_PI;
    const float pm = ORC_SHARE * pc + (1.0f - ORC_SHARE) * orc_pdf(g, x, v, w, W);
    if (!(c > 0.0f) || !(pm > 0.0f))
        return 0;
    *next = v;
    p->beta.xyz *= pc / pm;
    return alive;
}
"""

# (anchor, replacement) pairs applied to kernels/lib/shade_path.h, each anchor exactly once
FIRST = """    uint key;
    float d = 1.0f;
    const uint4 r = guide_record_of(guide, slot);
"""
FIRST_NEW = """    const int og = ORC_FIRST ? orc_group(x, n) : -1;
    if (og >= 0) {
        /* the path's record as an unguided first vertex makes it: the guide keeps learning */
        const uint key = guide_leaf(guide, guide_record_of(guide, slot), u.yz);
        if (guide->params->windows_at)
            guide_arrive(guide, slot, rgb_luminance(p->beta.xyz) * window_units(params, cam), counters);
        const int alive = orc_scatter(params, p, albedo, n, u, x, og, next, t);
        const float y = rgb_luminance(p->beta.xyz);
        p->org.w = alive && y > 0.0f ? guide->params->stats_scale * cam->up.w / y : 0.0f;
        p->dir.w = as_float(key);
        return alive;
    }
""" + FIRST
LATER = """    if (guide->params->every_vertex && guide->params->slots) {"""
LATER_NEW = """    if (ORC_EVERY && guide->params->slots != 0u) {
        const int og = orc_group(x, n);
        if (og >= 0)
            return orc_scatter(params, p, albedo, n, u, x, og, next, t);
    }
""" + LATER
INCLUDE = '#include "lib/texture.h"\n'
HELPERS_BEFORE = "/* The diffuse scatter at a path's first diffuse vertex"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--targets", required=True, choices=sorted(TARGETS))
    ap.add_argument("--vertices", choices=("first", "every", "later"), default="every")
    ap.add_argument("--share", type=float, default=0.5, help="the cosine's share of the mixture, (0, 1) (default 0.5)")
    ap.add_argument("--weights", default=None,
                    help="a weight >= 0 per target rectangle, comma-separated in the targets' order, times its "
                         "solid angle (default: 1 each)")
    ap.add_argument("--kernels", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "kernels"))
    ap.add_argument("--out", required=True, help="the kernel folder to write (replaced)")
    a = ap.parse_args()
    if not 0.0 < a.share < 1.0:
        sys.exit(f"aim_oracle.py: --share {a.share} is not in (0, 1)")
    groups = TARGETS[a.targets]
    boxes, first, rects = [], [0], []
    for (lo, hi, inside), rs in groups:
        boxes.append("{%s}" % ", ".join(f"{float(v)!r}f" for v in (*lo, *hi, inside)))
        rects += ["{%s}" % ", ".join(f"{float(v)!r}f" for v in r) for r in rs]
        first.append(len(rects))
    imp = [1.0] * len(rects)
    if a.weights is not None:
        try:
            imp = [float(v) for v in a.weights.split(",")]
        except ValueError:
            sys.exit(f"aim_oracle.py: --weights '{a.weights}' is not a list of numbers")
        if len(imp) != len(rects) or not all(math.isfinite(v) and v >= 0.0 for v in imp) or max(imp) <= 0.0:
            sys.exit(f"aim_oracle.py: --weights needs one number per target rectangle ({len(rects)} for --targets "
                     f"{a.targets}), each >= 0, not all 0")
    header = HEADER % {"imp": ", ".join(f"{v!r}f" for v in imp), "share": repr(a.share), "groups": len(groups),
                       "n": len(rects), "boxes": ", ".join(boxes), "first": ", ".join(map(str, first)),
                       "rects": ", ".join(rects)}
    if os.path.exists(a.out):
        shutil.rmtree(a.out)
    shutil.copytree(a.kernels, a.out)
    path = os.path.join(a.out, "lib", "shade_path.h")
    src = open(path).read()
    edits = [(INCLUDE, INCLUDE + "#define ORC_EVERY %d\n#define ORC_FIRST %d\n" % (a.vertices != "first", a.vertices != "later")),
             (FIRST, FIRST_NEW), (LATER, LATER_NEW)]
    # the oracle's functions need scatter_diffuse(), so they go after it, before scatter_first()
    edits.append((HELPERS_BEFORE, header + "\n" + HELPERS_BEFORE))
    for old, new in edits:
        if src.count(old) != 1:
            sys.exit(f"aim_oracle.py: {path}: expected one '{old.splitlines()[0].strip()}', found {src.count(old)}")
        src = src.replace(old, new)
    open(path, "w").write(src)
    print(f"wrote {a.out}: {len(rects)} target rectangles in {len(groups)} region(s), {a.vertices} vertices, "
          f"cosine share {a.share}")


if __name__ == "__main__":
    main()
