/* transmittance.h — how much of a connection to the camera gets through (DESIGN.md §2: "a glass
 * sheet on the segment multiplies it by its directional transmittance T (1 - R(theta))").
 *
 * Any-hit traversal over the segment that does not stop at glass: an opaque hit returns 0 at once;
 * every glass triangle crossed multiplies the result. A leaf's packet repeats its last triangle in
 * unused lanes; repeats are skipped so no pane counts twice. Without glass in the scene
 * (FEN_HAS_GLASS undefined) this is the plain any-hit query.
 * Requires bvh_traverse.h (FEN_BVH_WIDTH) to be included first.
 */
#ifndef FEN_TRANSMITTANCE_H
#define FEN_TRANSMITTANCE_H

#include "lib/fresnel.h"
#include "lib/scene_access.h"

static inline float3 segment_transmittance(const global BvhNode* nodes,
                                           const global TriPacket4* packets,
                                           const global uint* prim_material,
                                           const global DevMaterial* materials, const RayPre* r,
                                           float3 dir_unit)
{
#ifndef FEN_HAS_GLASS
    return bvh_intersect_any(nodes, packets, r) ? (float3)(0.0f) : (float3)(1.0f);
#else
    float3 trans = (float3)(1.0f);
    BvhWalk w;
    bvh_walk_begin(&w);
    for (uint leaf; (leaf = bvh_walk_next(&w, nodes, r)) != FEN_INVALID_ID;) {
        float4 b1, b2;
        const global TriPacket4* p = packets + leaf;
        const float4 t = tri_packet_intersect(p, r, r->tmax, &b1, &b2);
        const float tv[4] = {t.s0, t.s1, t.s2, t.s3};
        uint last = FEN_INVALID_ID;
        for (int lane = 0; lane < 4; ++lane) {
            const uint prim = p->prim[lane];
            if (prim == last)
                continue;
            last = prim;
            if (!(tv[lane] < INFINITY))
                continue;
            const global DevMaterial* m = materials + prim_material[prim];
            if (!material_is_glass(m))
                return (float3)(0.0f);
            const float cos_i = dot(packet_normal(p, (uint)lane), dir_unit);
            trans *= m->transmission.xyz * (1.0f - fresnel_dielectric(cos_i, m->transmission.w));
        }
    }
    return trans;
#endif
}

#endif /* FEN_TRANSMITTANCE_H */
