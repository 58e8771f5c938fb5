/* direct_sun.cl — the sun's direct light on the sensor cells, hour by hour: the five-phase
 * method's direct-sun matrix, for an annual study (DESIGN.md §8 "The sun apart from the sky").
 *
 * Work-item = (cell, hour), cell-major: out[(cell - first_cell) * hours + hour] is the mean over the
 * cell's square of the illuminance the sun's disc gives it by light that comes straight through
 * nothing but glass, in lux:
 *   S = E_n (1/N) sum_i max(0, n . d_i) T(x_i, d_i)
 * with E_n the hour's direct normal illuminance, x_i one jittered point in each of points x points
 * strata of the square, d_i a uniform direction within the sun's disc, and T the glass panes'
 * transmittance along the ray (lib/transmittance.h: 0 at anything opaque). Unbiased for the
 * square's mean over the disc; each (cell, hour) draws its own numbers (its own counter), so the
 * quadrature error of one hour is independent of the next and averages out over a year. The ray
 * starts on the cell (t > 0), as a light path's segment counts a crossing at t > 0 (lib/sensor.h).
 * No atomics: every work-item writes its own value.
 */
#include "lib/bvh_traverse.h"
#include "lib/accumulate.h"
#include "lib/rng.h"
#include "lib/sampling.h"
#include "lib/transmittance.h"
#include "shared/fen_sun.h"

kernel void direct_sun(global const DevSunParams* params, global const DevSunCell* cells,
                       global const DevSunHour* hours, global const BvhNode* nodes,
                       global const TriPacket4* packets, global const uint* prim_material,
                       global const DevMaterial* materials, global float* out)
{
    const uint i = get_global_id(0);
    const uint H = params->hours;
    if (i >= params->cells * H)
        return;
    const uint c = params->first_cell + i / H, h = i % H;
    const DevSunCell cell = cells[c];
    const float4 sun = hours[h].dir;
    if (!(sun.w > 0.0f)) {
        out[i] = 0.0f; /* no sun this hour: no rays */
        return;
    }
    const float3 n = cell.normal.xyz;
    const uint k = params->points;
    const float side = cell.centre.w;
    float sum = 0.0f;
    for (uint j = 0; j < k * k; ++j) {
        const float4 u = rng_floats(params->seed, FEN_RNG_STREAM_DIRECT_SUN, c, h, j, FEN_RNG_DIRECT_SUN);
        const float3 d = sample_cone(sun.xyz, params->cos_radius, u.z, u.w);
        const float cos_n = dot(n, d);
        if (!(cos_n > 0.0f))
            continue;
        const float su = (((float)(j % k) + u.x) / (float)k - 0.5f) * side;
        const float sv = (((float)(j / k) + u.y) / (float)k - 0.5f) * side;
        const float3 x = cell.centre.xyz + su * cell.u_axis.xyz + sv * cell.v_axis.xyz;
        const RayPre r = ray_setup(x, d, 0.0f, INFINITY, FEN_BVH_WIDTH);
        sum += cos_n * rgb_luminance(segment_transmittance(nodes, packets, prim_material, materials, &r, d));
    }
    out[i] = sun.w * sum / (float)(k * k);
}
