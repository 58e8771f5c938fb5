/* fen_layout.h — the list of every struct shared by host and device, for the layout probe.
 *
 * FEN_SHARED_LAYOUT(X) expands X(struct, member) for each struct and the members whose offsets
 * matter. kernels/test_probes.cl writes sizeof/offsetof as the device compiler sees them;
 * tests/kernels/probes_test.cpp compares with the host compiler. A struct added to a shared header
 * is added here too.
 */
#ifndef FEN_LAYOUT_H
#define FEN_LAYOUT_H

#include "shared/fen_bvh.h"
#include "shared/fen_emission.h"
#include "shared/fen_guide.h"
#include "shared/fen_openings.h"
#include "shared/fen_render.h"
#include "shared/fen_sensor.h"
#include "shared/fen_sun.h"

#define FEN_SHARED_LAYOUT(X) \
    X(Ray, org_tmin)         \
    X(Ray, dir_tmax)         \
    X(Hit, t)                \
    X(Hit, prim)             \
    X(BvhNode2, bounds)      \
    X(BvhNode2, child)       \
    X(BvhNode4, child)       \
    X(BvhNode8, child)       \
    X(TriPacket4, v)         \
    X(TriPacket4, prim)      \
    X(DevMaterial, transmission) \
    X(DevMaterial, tex_offset)   \
    X(DevMaterial, tex_flags)    \
    X(DevCamera, up)         \
    X(DevCamera, width)      \
    X(SurfaceHit, normal)    \
    X(PathState, beta)       \
    X(PathState, path_lo)    \
    X(PathState, flags)      \
    X(Connection, value)     \
    X(Connection, guide)     \
    X(GuideParams, slots)    \
    X(GuideParams, stats_scale) \
    X(GuideParams, every_vertex) \
    X(GuideParams, windows_at) \
    X(GuideParams, window_split_max) \
    X(GuideParams, leaf_slots_at) \
    X(GuideParams, aim_sums) \
    X(AimTriangle, normal)   \
    X(OpeningAim, cosine_share) \
    X(OpeningAim, first_share) \
    X(OpeningAim, tri)       \
    X(RenderParams, sun_dir) \
    X(RenderParams, path_end) \
    X(RenderParams, seed)    \
    X(RenderParams, openings_share) \
    X(RenderParams, fixed_scale) \
    X(RenderParams, stats_scale) \
    X(RenderParams, batch)   \
    X(RenderParams, rr_depth) \
    X(RenderParams, split_weight) \
    X(RenderParams, split_max) \
    X(RenderParams, pick_step) \
    X(SplitState, normal)    \
    X(DevSensorPlane, normal) \
    X(DevSensorPlane, bucket_first) \
    X(DevSensorPlane, rows)  \
    X(DevSensorCell, inv_area) \
    X(DevSensorInfo, fixed_scale) \
    X(SplitState, depth)     \
    X(SplitState, path_hi)   \
    X(SourceParams, box_size) \
    X(SourceParams, alias_shift) \
    X(PortalParams, overlap) \
    X(PortalParams, complement) \
    X(PortalParams, group_alias_shift) \
    X(AdaptiveCell, box)     \
    X(AdaptiveCell, dirs)    \
    X(AdaptiveCell, weight)  \
    X(PortalFrame, normal)   \
    X(PortalFrame, triangles) \
    X(AdaptiveParams, cell_alias_shift) \
    X(AdaptiveParams, portal_base) \
    X(AdaptiveParams, walk_part) \
    X(DevSunCell, normal)    \
    X(DevSunHour, dir)       \
    X(DevSunParams, cos_radius)

#endif /* FEN_LAYOUT_H */
