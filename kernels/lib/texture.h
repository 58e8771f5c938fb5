/* texture.h — the albedo at a point of a surface (DESIGN.md §1, "Textures"): the material's
 * baseColorFactor, times its base-colour texture when it has one, read at the point's texture
 * coordinates.
 *
 * Texture coordinates are affine over a triangle, so each textured primitive carries two planes
 * (prim_uv[2 prim], [2 prim + 1]) with u = dot(r0.xyz, x) + r0.w, v = dot(r1.xyz, x) + r1.w for a
 * point x on it (built on the host, render/device_scene.cpp): the hit point is all a stage needs,
 * nothing is added to the path state or the hit record. Texels are 8-bit sRGB as in the file,
 * decoded by the table at the head of the texel buffer (FEN_SRGB_TABLE), then filtered (bilinear,
 * or nearest) in linear values; wrap modes as glTF's sampler says (REPEAT, CLAMP_TO_EDGE,
 * MIRRORED_REPEAT), applied per texel index. Row 0 is the image's top row (glTF: v = 0 at the top).
 * Scenes without textures compile without any of it (FEN_HAS_TEXTURES), and shade the same bits.
 */
#ifndef FEN_TEXTURE_H
#define FEN_TEXTURE_H

#include "shared/fen_render.h"

/* What a stage needs to know about a hit surface's material (shade_path.h). */
typedef struct {
    global const uint* prim_material; /* material per primitive */
    global const DevMaterial* materials;
    global const float4* prim_uv;     /* two planes per primitive (placeholder without textures) */
    global const uint* texels;        /* decode table, then texels (placeholder without textures) */
} SurfaceMaterials;

#ifdef FEN_HAS_TEXTURES

/* Texel index i wrapped into [0, n) by glTF's wrap mode. */
static inline int texture_wrap(int i, int n, uint mode)
{
    if (mode == FEN_WRAP_CLAMP)
        return clamp(i, 0, n - 1);
    if (mode == FEN_WRAP_MIRROR) {
        const int k = ((i % (2 * n)) + 2 * n) % (2 * n);
        return k < n ? k : 2 * n - 1 - k;
    }
    return ((i % n) + n) % n;
}

/* A coordinate brought into a range where texel indices stay small: one period (two, mirrored)
   of a repeating texture; [-1, 2] for a clamped one (anything beyond reads the edge anyway). */
static inline float texture_fold(float t, uint mode)
{
    if (mode == FEN_WRAP_CLAMP)
        return clamp(t, -1.0f, 2.0f);
    const float period = mode == FEN_WRAP_MIRROR ? 2.0f : 1.0f;
    return t - period * floor(t / period);
}

static inline float3 texel_rgb(global const uint* texels, const global DevMaterial* m, int x, int y)
{
    const uint c = texels[FEN_SRGB_TABLE + m->tex_offset + (uint)y * m->tex_width + (uint)x];
    return (float3)(as_float(texels[c & 255u]), as_float(texels[(c >> 8) & 255u]),
                    as_float(texels[(c >> 16) & 255u]));
}

static inline float3 texture_sample(global const uint* texels, const global DevMaterial* m, float2 uv)
{
    const uint ws = (m->tex_flags >> FEN_TEX_WRAP_S_SHIFT) & 3u, wt = (m->tex_flags >> FEN_TEX_WRAP_T_SHIFT) & 3u;
    const int w = (int)m->tex_width, h = (int)m->tex_height;
    const float s = texture_fold(uv.x, ws) * (float)w, t = texture_fold(uv.y, wt) * (float)h;
    if (m->tex_flags & FEN_TEX_NEAREST)
        return texel_rgb(texels, m, texture_wrap((int)floor(s), w, ws), texture_wrap((int)floor(t), h, wt));
    const float sx = s - 0.5f, ty = t - 0.5f;
    const float fx = floor(sx), fy = floor(ty);
    const float ax = sx - fx, ay = ty - fy;
    const int x0 = texture_wrap((int)fx, w, ws), x1 = texture_wrap((int)fx + 1, w, ws);
    const int y0 = texture_wrap((int)fy, h, wt), y1 = texture_wrap((int)fy + 1, h, wt);
    const float3 top = texel_rgb(texels, m, x0, y0) * (1.0f - ax) + texel_rgb(texels, m, x1, y0) * ax;
    const float3 bottom = texel_rgb(texels, m, x0, y1) * (1.0f - ax) + texel_rgb(texels, m, x1, y1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

#endif /* FEN_HAS_TEXTURES */

/* The Lambertian albedo of primitive `prim` (material m) at point x on it. */
static inline float3 surface_albedo(const SurfaceMaterials* sm, const global DevMaterial* m, uint prim, float3 x)
{
#ifdef FEN_HAS_TEXTURES
    if (m->tex_flags & FEN_TEX_PRESENT) {
        const float4 r0 = sm->prim_uv[2u * prim], r1 = sm->prim_uv[2u * prim + 1u];
        const float2 uv = (float2)(dot(r0.xyz, x) + r0.w, dot(r1.xyz, x) + r1.w);
        return m->albedo.xyz * texture_sample(sm->texels, m, uv);
    }
#else
    (void)sm, (void)prim, (void)x;
#endif
    return m->albedo.xyz;
}

#endif /* FEN_TEXTURE_H */
