/* fen_sun.h — device layout of the direct-sun pass of an annual study (DESIGN.md §8 "The sun
 * apart from the sky"; kernels/direct_sun.cl).
 *
 * One declaration for host and device (fen_types.h). Each sensor cell is a square; each daylit
 * hour a direction towards the sun's centre and its direct normal illuminance. The kernel writes,
 * for every cell of a launch and every hour, the cell's mean illuminance from the sun's disc alone
 * (lux), straight through nothing but glass: the five-phase method's direct-sun matrix.
 * Invariants: struct sizes multiples of 16 bytes; listed in fen_layout.h for the layout probe.
 */
#ifndef FEN_SUN_H
#define FEN_SUN_H

#include "shared/fen_types.h"

FEN_NS_BEGIN

typedef struct {
    fen_float4 centre;  /* xyz: the square's centre (m); w: its side (m) */
    fen_float4 u_axis;  /* xyz: unit, along one side */
    fen_float4 v_axis;  /* xyz: unit, along the other */
    fen_float4 normal;  /* xyz: unit normal, the side the cell measures light arriving at */
} DevSunCell;
FEN_ASSERT_SIZE(DevSunCell, 64);

typedef struct {
    fen_float4 dir;     /* xyz: unit direction towards the sun's centre; w: direct normal illuminance (lux) */
} DevSunHour;
FEN_ASSERT_SIZE(DevSunHour, 16);

typedef struct {
    fen_u32 first_cell;  /* the launch covers cells [first_cell, first_cell + cells) x every hour */
    fen_u32 cells;
    fen_u32 hours;
    fen_u32 points;      /* jittered points per side: points x points rays per cell and hour */
    fen_u32 seed;
    fen_f32 cos_radius;  /* cos of the sun's angular radius: each ray aims at a point of the disc */
    fen_u32 pad0, pad1;
} DevSunParams;
FEN_ASSERT_SIZE(DevSunParams, 32);
FEN_ASSERT_OFFSET(DevSunParams, cos_radius, 20);

FEN_NS_END

#endif /* FEN_SUN_H */
