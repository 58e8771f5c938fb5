/* sky_patch.h — the Reinhart sky patch a direction towards the sky falls in (DESIGN.md §8
 * "Daylight coefficients"); host twin: host/annual/sky_patches.h, compared on the same directions by
 * SkyPatches.DeviceFindsTheHostsPatch.
 *
 * Reinhart's subdivision of Tregenza's sky, as Radiance's reinhart.cal numbers it, so that a matrix
 * written by fenestra lines up with one of Radiance's: rows of altitude alpha = 90 / (7 MF + 0.5)
 * degrees from the horizon up, row r holding MF x (30, 30, 24, 24, 18, 12, 6)[r / MF] patches and
 * the top row (r = 7 MF) one cap; in a row, patches of equal azimuth width centred on north and then
 * every step towards east. Patch 0 is the ground (every direction with y <= 0), patches 1.. the
 * sky. Azimuth from north (-z) towards east (+x); y up (lib/sky.h).
 * Invariant: the result is < sky_patch_count(mf) for every direction, NaN included (ground).
 */
#ifndef FEN_SKY_PATCH_H
#define FEN_SKY_PATCH_H

#include "shared/fen_render.h"

/* Patches in row r (r <= 7 mf) of the subdivision MF = mf. */
static inline uint sky_patch_row_count(uint r, uint mf)
{
    if (r >= 7u * mf)
        return 1u;
    const uint band = r / mf;
    const uint tregenza = band < 2u ? 30u : band < 4u ? 24u : band == 4u ? 18u : band == 5u ? 12u : 6u;
    return mf * tregenza;
}

static inline uint reinhart_patch(float3 to_sky, uint mf)
{
    if (!(to_sky.y > 0.0f))
        return 0u;
    const float alpha_deg = 90.0f / (7.0f * (float)mf + 0.5f);
    const float alt_deg = degrees(asin(fmin(to_sky.y, 1.0f)));
    const uint row = min((uint)(alt_deg / alpha_deg), 7u * mf);
    uint first = 1u;
    for (uint r = 0; r < row; ++r)
        first += sky_patch_row_count(r, mf);
    const uint n = sky_patch_row_count(row, mf);
    float azi_deg = degrees(atan2(to_sky.x, -to_sky.z));
    if (azi_deg < 0.0f)
        azi_deg += 360.0f;
    const float inc = 360.0f / (float)n;
    uint col = (uint)((azi_deg + 0.5f * inc) / inc);
    if (col >= n)
        col = 0u; /* the last half patch before north is the first patch */
    return first + col;
}

/* The path's patch, kept in its flags (shared/fen_render.h FEN_PATH_PATCH_SHIFT); `dir` its
   direction of travel as it leaves the sky. Built with -DFEN_SKY_PATCH_MF=mf (daylight
   coefficients), else nothing. */
static inline void path_tag_sky_patch(PathState* p)
{
#ifdef FEN_SKY_PATCH_MF
    p->flags |= reinhart_patch(-p->dir.xyz, FEN_SKY_PATCH_MF) << FEN_PATH_PATCH_SHIFT;
#else
    (void)p;
#endif
}

#endif /* FEN_SKY_PATCH_H */
