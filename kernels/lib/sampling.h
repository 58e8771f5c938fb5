/* sampling.h — warping uniform numbers to the distributions the estimator needs, each with the
 * exact density the path weights assume (DESIGN.md §2-§3). Checked against their densities by
 * chi-square in tests/kernels/sampling_test.cpp.
 */
#ifndef FEN_SAMPLING_H
#define FEN_SAMPLING_H

#include "lib/trig.h"

#define FEN_PI 3.14159265358979323846f

/* Uniform on the unit disk: density 1/pi. (Angles in units of pi: fen_sincospi's reduction is
   exact and cheap, where PoCL's sin/cos of angles beyond pi/4 take a slow path.) */
static inline float2 sample_disk(float u1, float u2)
{
    const float r = sqrt(u1);
    float c;
    const float s = fen_sincospi(2.0f * u2, &c);
    return (float2)(r * c, r * s);
}

/* Uniform on the unit disk by the concentric map (Shirley and Chiu 1997): density 1/pi, and it
   maps boxes of [0,1)^2 to compact pieces of the disk (the polar map of sample_disk turns a box
   into a thin ring sector, a sliver near the centre) -- the adaptive strategy's cells are boxes. */
static inline float2 sample_disk_concentric(float u1, float u2)
{
    const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f)
        return (float2)(0.0f);
    float r, t; /* t: polar angle in units of pi */
    if (fabs(a) > fabs(b)) {
        r = a;
        t = 0.25f * (b / a);
    } else {
        r = b;
        t = 0.5f - 0.25f * (a / b);
    }
    float c;
    const float s = fen_sincospi(t, &c);
    return (float2)(r * c, r * s);
}

/* Two uniforms in (0, 1) from the two halves of 32 random bits, at the centres of 2^16 steps: a
   cell of the adaptive grid is a box, so 16 bits across it are plenty. */
static inline float2 unit16x2(uint bits)
{
    return ((float2)((float)(bits >> 16), (float)(bits & 0xFFFFu)) + 0.5f) * (1.0f / 65536.0f);
}

/* Two unit vectors completing n (unit) to an orthonormal basis (Duff et al., JCGT 2017). */
static inline void orthonormal_basis(float3 n, float3* t1, float3* t2)
{
    const float s = copysign(1.0f, n.z);
    const float a = -1.0f / (s + n.z);
    const float b = n.x * n.y * a;
    *t1 = (float3)(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
    *t2 = (float3)(b, s + n.y * n.y * a, -n.y);
}

/* An orthonormal basis (t1, t2) of the plane orthogonal to unit n that varies continuously with n
   everywhere but at n = +y: Duff et al.'s construction in the frame (x, z, -y). Sky and sun light
   travels downwards (n.y <= 0), so nearby directions of travel always get nearby bases -- what
   the adaptive strategy needs, since it learns where on the disk spanned by (t1, t2) light
   matters. (orthonormal_basis flips at n.z = 0, which would split a bin of directions in two.) */
static inline void travel_basis_down(float3 n, float3* t1, float3* t2)
{
    const float3 m = (float3)(n.x, n.z, -n.y);
    const float a = -1.0f / (1.0f + m.z);
    const float b = m.x * m.y * a;
    const float3 s1 = (float3)(1.0f + m.x * m.x * a, b, -m.x);
    const float3 s2 = (float3)(b, 1.0f + m.y * m.y * a, -m.y);
    *t1 = (float3)(s1.x, -s1.z, s1.y);
    *t2 = (float3)(s2.x, -s2.z, s2.y);
}

/* The same for any direction of travel: the ground's glow travels upwards (n.y > 0), where the
   construction above is singular at n = +y, so there it is the mirror image, in the horizontal
   plane, of the basis of n's mirror image -- continuous over the upper hemisphere of travel, and
   discontinuous only at the horizon, which no adaptive direction box straddles. */
static inline void travel_basis(float3 n, float3* t1, float3* t2)
{
    if (!(n.y > 0.0f)) {
        travel_basis_down(n, t1, t2);
        return;
    }
    float3 a, b;
    travel_basis_down((float3)(n.x, -n.y, n.z), &a, &b);
    *t1 = (float3)(a.x, -a.y, a.z);
    *t2 = (float3)(b.x, -b.y, b.z);
}

/* Cosine-weighted direction around unit n: density cos(theta)/pi per steradian. */
static inline float3 sample_cosine_hemisphere(float3 n, float u1, float u2)
{
    const float2 d = sample_disk(u1, u2);
    const float z = sqrt(fmax(0.0f, 1.0f - dot(d, d)));
    float3 t1, t2;
    orthonormal_basis(n, &t1, &t2);
    /* unit within rounding: (t1, t2, n) is orthonormal and |d|^2 + z^2 = 1 */
    return d.x * t1 + d.y * t2 + z * n;
}

/* Uniform in the cone of directions within angle acos(cos_max) of unit axis. */
static inline float3 sample_cone(float3 axis, float cos_max, float u1, float u2)
{
    const float c = 1.0f - u1 * (1.0f - cos_max);
    const float s = sqrt(fmax(0.0f, 1.0f - c * c));
    float3 t1, t2;
    orthonormal_basis(axis, &t1, &t2);
    float cp;
    const float sp = fen_sincospi(2.0f * u2, &cp);
    return normalize(s * cp * t1 + s * sp * t2 + c * axis);
}

/* x in [0,1) with density proportional to (1-x) a + x b, a, b >= 0, a + b > 0 (PBRT-v4's
   SampleLinear, stable when a == b). */
static inline float sample_linear(float u, float a, float b)
{
    if (u == 0.0f && a == 0.0f)
        return 0.0f;
    if (!(a + b > 0.0f))
        return u; /* zero density everywhere: only reachable on a set of measure zero */
    const float x = u * (a + b) / (a + sqrt(mix(a * a, b * b, u)));
    return fmin(x, 0x1.fffffep-1f);
}

/* The entry for 32 random bits r from an integer alias table (host: render/emission_setup.h
   IntegerCdf): column j = r >> shift gives entry j to offsets below its threshold table[2j] and
   entry table[2j+1] to the rest. Each entry i is chosen with probability exactly
   (cdf[i+1] - cdf[i]) / 2^32 -- the number the host puts in the path weight -- and never when that
   is zero. (A float CDF searched with a 24-bit float realises other probabilities, up to 0.6 %
   off for small cells, and zero for tiny ones.) One 8-byte read where a guided CDF search took
   two dependent ones; measured on the finest sky (43k cells): 6 % less emission time. The read
   itself still misses the cache: a sixth of the emission kernel on scenes/room.gltf. */
static inline uint alias_pick(const global uint* table, uint shift, uint r)
{
    const uint j = r >> shift;
    const uint2 c = vload2(j, table);
    return (r & ((1u << shift) - 1u)) < c.x ? j : c.y;
}

#endif /* FEN_SAMPLING_H */
