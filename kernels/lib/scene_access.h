/* scene_access.h — what a stage needs to know about a triangle it hit: its material (one uint per
 * primitive, shared/fen_render.h) and its geometry, read from the BVH packet that was just tested
 * (in cache) rather than from a separate per-primitive array.
 */
#ifndef FEN_SCENE_ACCESS_H
#define FEN_SCENE_ACCESS_H

#include "shared/fen_bvh.h"
#include "shared/fen_render.h"

/* Vertex k (0..2) of lane `lane` of a packet. */
static inline float3 packet_vertex(const global TriPacket4* p, uint lane, int k)
{
    const global float* v = p->v + 12 * k;
    return (float3)(v[lane], v[4 + lane], v[8 + lane]);
}

/* Unit geometric normal of lane `lane`. */
static inline float3 packet_normal(const global TriPacket4* p, uint lane)
{
    const float3 p0 = packet_vertex(p, lane, 0);
    return normalize(cross(packet_vertex(p, lane, 1) - p0, packet_vertex(p, lane, 2) - p0));
}

static inline int material_is_glass(const global DevMaterial* m)
{
    return as_uint(m->albedo.w) == FEN_MATERIAL_GLASS;
}

#endif /* FEN_SCENE_ACCESS_H */
