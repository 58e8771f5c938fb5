/* rng.h — the random numbers of a light path and of a camera sample (DESIGN.md §4).
 *
 * Counter-based: a path's numbers depend only on (seed, path index, depth, purpose), never on
 * which slot or thread handles it, so a render is the same whatever the scheduling. Each call
 * yields four independent floats in [0, 1).
 */
#ifndef FEN_LIB_RNG_H
#define FEN_LIB_RNG_H

#include "shared/fen_rng.h" /* also the purposes and streams FEN_RNG_*, one list for host and device */

static inline RngBlock rng_bits(uint seed, uint stream, uint c0, uint c1, uint c2, uint purpose)
{
    RngBlock ctr;
    ctr.x = c0;
    ctr.y = c1;
    ctr.z = c2;
    ctr.w = purpose;
    return fen_philox4x32_10(ctr, seed, stream);
}

static inline float4 rng_to_floats(RngBlock r)
{
    return (float4)(fen_u32_to_unit(r.x), fen_u32_to_unit(r.y), fen_u32_to_unit(r.z),
                    fen_u32_to_unit(r.w));
}

/* Four floats in [0, 1) from 96 random bits, 24 each -- all a float in [0, 1) can hold, so one
   Philox block serves a 32-bit discrete choice and four continuous dimensions. */
static inline float4 rng_unit24x4(uint a, uint b, uint c)
{
    const float k = 1.0f / 16777216.0f;
    return (float4)((float)(a >> 8), (float)(((a & 0xFFu) << 16) | (b >> 16)),
                    (float)(((b & 0xFFFFu) << 8) | (c >> 24)), (float)(c & 0xFFFFFFu)) * k;
}

static inline float4 rng_floats(uint seed, uint stream, uint c0, uint c1, uint c2, uint purpose)
{
    return rng_to_floats(rng_bits(seed, stream, c0, c1, c2, purpose));
}

/* Light path `path` (64-bit, as lo/hi) at interaction `depth`: raw bits (for exact discrete
   choices) or floats. */
static inline RngBlock rng_path_bits(uint seed, uint path_lo, uint path_hi, uint depth, uint purpose)
{
    return rng_bits(seed, FEN_RNG_STREAM_PATH, path_lo, path_hi, depth, purpose);
}

static inline float4 rng_path(uint seed, uint path_lo, uint path_hi, uint depth, uint purpose)
{
    return rng_to_floats(rng_path_bits(seed, path_lo, path_hi, depth, purpose));
}

/* Camera sample `sample` of pixel `pixel` in batch `batch`: a stream of its own. */
static inline float4 rng_camera(uint seed, uint pixel, uint sample, uint batch)
{
    return rng_floats(seed, FEN_RNG_STREAM_CAMERA, pixel, sample, batch, FEN_RNG_CAMERA);
}

#endif /* FEN_LIB_RNG_H */
