/* scene_access.h — what a stage needs to know about the primitive a ray hit: its material and
 * geometric normal (ShadeTri, DevMaterial of shared/fen_render.h).
 */
#ifndef FEN_SCENE_ACCESS_H
#define FEN_SCENE_ACCESS_H

#include "shared/fen_render.h"

static inline uint tri_material(const global ShadeTri* tris, uint prim)
{
    return as_uint(tris[prim].p0.w);
}

/* Geometric normal, not normalised (its length is twice the triangle's area). */
static inline float3 tri_normal(const global ShadeTri* tris, uint prim)
{
    const float3 p0 = tris[prim].p0.xyz;
    return cross(tris[prim].p1.xyz - p0, tris[prim].p2.xyz - p0);
}

static inline int material_is_glass(const global DevMaterial* m)
{
    return as_uint(m->albedo.w) == FEN_MATERIAL_GLASS;
}

#endif /* FEN_SCENE_ACCESS_H */
