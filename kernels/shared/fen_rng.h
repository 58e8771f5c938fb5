/* fen_rng.h — counter-based random numbers, identical on host and device.
 *
 * Philox-4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011):
 * a keyed bijection of a 128-bit counter. A light path draws its numbers from the counter
 * (path index, iteration, bounce, dimension block) under the key (seed), so a render does not
 * depend on thread scheduling or work-group size (DESIGN.md §4). Integer-only: host and device
 * streams match bit for bit (tests/kernels/probes_test.cpp checks it).
 */
#ifndef FEN_RNG_H
#define FEN_RNG_H

#include "shared/fen_types.h"

#ifdef __OPENCL_VERSION__
#define FEN_RNG_FN static inline
#else
#define FEN_RNG_FN inline
#endif

/* The purpose word of a counter (its last 32 bits): what the numbers are for. One list for host
   and device, so that no two uses of one (seed, path) draw the same block. */
#define FEN_RNG_EMIT 0u         /* source and sky cell (32 bits), direction and origin (4 x 24) */
#define FEN_RNG_SCATTER 2u      /* glass choice, scattering direction, Russian roulette */
#define FEN_RNG_CAMERA 3u       /* camera pass: position in the pixel */
#define FEN_RNG_EMIT_PORTAL 4u  /* portal triangle (32 bits), point on it, overlap rejection */
#define FEN_RNG_GUIDE 5u        /* first-bounce guide: box (32 bits), point in it (2 x 32) */
#define FEN_RNG_PICK_LATTICE 6u /* host: each run's table-pick lattice offset (render/renderer.cpp) */
#define FEN_RNG_DIRECT_SUN 7u   /* direct-sun pass: a point in the cell's stratum, a point on the sun's disc */
#define FEN_RNG_WINDOW 8u       /* weight windows: the roulette of a path below its window */
#define FEN_RNG_OPENING 9u      /* openings' walks: the part and pane side (depth 0); vertex i's roulette (1 + i) */
#define FEN_RNG_WALK 10u        /* ... walk vertex i (depth i): a point on the sun's disc, the next direction */

/* The stream word of a key (its second 32 bits, beside the seed): which family of counters. Also
   one list: light paths (lib/rng.h rng_path_bits), camera samples (rng_camera), and the host's
   pick-lattice offsets (render/renderer.cpp), and the annual study's direct-sun pass (direct_sun.cl). The kernel test probes draw from streams of their
   own, outside a render. */
#define FEN_RNG_STREAM_PATH 0x6a09e667u
#define FEN_RNG_STREAM_CAMERA 0x3c6ef372u
#define FEN_RNG_STREAM_PICK_LATTICE 0x1a771ceu
#define FEN_RNG_STREAM_DIRECT_SUN 0x510e527fu

FEN_NS_BEGIN

typedef struct {
    fen_u32 x, y, z, w;
} RngBlock;

FEN_RNG_FN RngBlock fen_philox4x32_10(RngBlock ctr, fen_u32 key0, fen_u32 key1)
{
    for (int round = 0; round < 10; ++round) {
        /* Both halves from one 64-bit product. Not mul_hi(): PoCL 3.1 emulates it with 16-bit
           partial products (measured: most of the emission kernel's time). Nor the product for
           the high half and a 32-bit multiply for the low one: the compiler keeps both, and
           dropping the second made CPU renders 1.1-1.25x the paths/s with bit-identical images
           (README "Render throughput"). */
        const fen_u64 p0 = (fen_u64)0xD2511F53u * (fen_u64)ctr.x;
        const fen_u64 p1 = (fen_u64)0xCD9E8D57u * (fen_u64)ctr.z;
        const fen_u32 hi0 = (fen_u32)(p0 >> 32), lo0 = (fen_u32)p0;
        const fen_u32 hi1 = (fen_u32)(p1 >> 32), lo1 = (fen_u32)p1;
        RngBlock next;
        next.x = hi1 ^ ctr.y ^ key0;
        next.y = lo1;
        next.z = hi0 ^ ctr.w ^ key1;
        next.w = lo0;
        ctr = next;
        key0 += 0x9E3779B9u;
        key1 += 0xBB67AE85u;
    }
    return ctr;
}

/* A float in [0, 1) from the top 24 bits: every value is exactly representable, 1 never occurs. */
FEN_RNG_FN fen_f32 fen_u32_to_unit(fen_u32 x)
{
    return (fen_f32)(x >> 8) * (1.0f / 16777216.0f);
}

FEN_NS_END

#endif /* FEN_RNG_H */
