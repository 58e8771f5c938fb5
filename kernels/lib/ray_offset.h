/* ray_offset.h — where a ray leaving a surface starts, so that it cannot hit that surface again.
 *
 * The hit point is interpolated from the triangle's vertices with the barycentrics of the hit;
 * its rounding error is bounded per axis by gamma(7) * (|b0 p0| + |b1 p1| + |b2 p2|) (Pharr,
 * Jakob, Humphreys, PBRT 3rd ed., §3.9). PBRT projects that bound on the normal and relies on a
 * conservative "t > error" test inside its triangle routine; our watertight test has no such term
 * (it would cost every ray), so the offset must also outgrow the rounding noise of the t that the
 * triangle test computes for a ray starting on the plane. That noise scales with the coordinates
 * involved -- the point's and the triangle's extent around it -- not with the normal component:
 * a point on the plane y = 0 has no error in y, yet a ray from it gets t of about 1e-10 (measured,
 * tests/kernels/robustness_test.cpp). So the offset distance is the largest component of the
 * bound plus gamma(7) times four extents, pushed along the geometric normal to the side the new
 * ray leaves towards, then rounded one ulp further away. It scales with distance from the
 * origin, so a room 10 km away works as one at the origin.
 */
#ifndef FEN_RAY_OFFSET_H
#define FEN_RAY_OFFSET_H

#define FEN_GAMMA7 4.1723259e-07f /* 7 eps / (1 - 7 eps), eps = 2^-24, rounded up */

static inline float fen_max3(float3 v) { return fmax(fmax(v.x, v.y), v.z); }

/* Hit point from vertices and barycentrics (b1, b2 of vertices 1 and 2); *offset_m receives the
   distance by which a ray leaving it must start off the surface. */
static inline float3 surface_point(float3 p0, float3 p1, float3 p2, float b1, float b2,
                                   float* offset_m)
{
    const float b0 = 1.0f - b1 - b2;
    const float3 a = b0 * p0, b = b1 * p1, c = b2 * p2;
    const float3 p = a + b + c;
    const float3 extent = fmax(fabs(p0 - p), fmax(fabs(p1 - p), fabs(p2 - p)));
    *offset_m = FEN_GAMMA7 * (fen_max3(fabs(a) + fabs(b) + fabs(c)) + 4.0f * fen_max3(extent));
    return p;
}

static inline float fen_step_away(float x, float dir)
{
    return dir > 0.0f ? nextafter(x, INFINITY) : (dir < 0.0f ? nextafter(x, -INFINITY) : x);
}

/* Origin for a ray from surface point p (offset from surface_point, unit geometric normal n, as
   surface_hit() gives it) towards w. */
static inline float3 offset_ray_origin(float3 p, float offset_m, float3 n, float3 w)
{
    float3 off = offset_m * n;
    if (dot(w, off) < 0.0f)
        off = -off;
    const float3 po = p + off;
    return (float3)(fen_step_away(po.x, off.x), fen_step_away(po.y, off.y), fen_step_away(po.z, off.z));
}

#endif /* FEN_RAY_OFFSET_H */
