/* fen_sensor.h — device layout of the sensor grids (DESIGN.md §8).
 *
 * One declaration for host and device (fen_types.h). A sensor is a set of square cells that do
 * not block light; cells lie on planes, and each plane carries a grid of buckets over its cells so
 * that the cell a path segment crosses is found in constant time (lib/sensor.h):
 *   - DevSensorPlane: the plane (a point on it, its unit normal -- the side it faces -- and two unit
 *     axes u, v in it), its bucket grid (cols x rows buckets of side 1 / normal.w metres starting at
 *     the origin), and where its buckets start in the bucket table;
 *   - DevSensorCell: a cell's centre (u, v) in its plane's coordinates, half its side, 1 / area;
 *   - bucket table (uint): for plane p, bucket b = row * cols + col, the cells overlapping it are
 *     bucket_cells[bucket_start[first + b] .. bucket_start[first + b + 1]); every cell is listed in
 *     every bucket its square overlaps, so a crossing point looks in one bucket only.
 * Accumulators: two fen_u64 per cell (128-bit fixed point, lib/accumulate.h) of the illuminance
 * sum(Y(beta)) / area x fixed_scale -- lux x paths; the host divides by paths and the scale.
 * With daylight coefficients (info.patches > 0, DESIGN.md §8 "Daylight coefficients") two matrices
 * of cells x patches such sums follow them, row-major by cell: every crossing by the patch its path
 * started from, then the same for the light that has met no diffuse surface yet (direct light).
 * Invariants: struct sizes multiples of 16 bytes; listed in fen_layout.h for the layout probe.
 */
#ifndef FEN_SENSOR_H
#define FEN_SENSOR_H

#include "shared/fen_types.h"

FEN_NS_BEGIN

typedef struct {
    fen_float4 origin;  /* xyz: the bucket grid's corner (m); w: the plane's offset dot(normal, x) */
    fen_float4 normal;  /* xyz: unit normal, the side the sensor faces; w: 1 / bucket side (1/m) */
    fen_float4 u_axis;  /* xyz: unit, in the plane */
    fen_float4 v_axis;  /* xyz: unit, in the plane, normal x u */
    fen_u32 bucket_first; /* index of the plane's first entry in bucket_start */
    fen_u32 cols;         /* buckets along u */
    fen_u32 rows;         /* buckets along v */
    fen_u32 pad;
} DevSensorPlane;
FEN_ASSERT_SIZE(DevSensorPlane, 80);
FEN_ASSERT_OFFSET(DevSensorPlane, bucket_first, 64);

typedef struct {
    fen_f32 u, v;      /* centre in the plane's coordinates (m) */
    fen_f32 half_side; /* half the side of the square (m) */
    fen_f32 inv_area;  /* 1 / area (1/m^2) */
} DevSensorCell;
FEN_ASSERT_SIZE(DevSensorCell, 16);

typedef struct {
    fen_u32 planes;       /* 0: no sensors */
    fen_u32 cells;
    fen_f32 fixed_scale;  /* accumulators hold round(lux x paths x fixed_scale) */
    fen_u32 patches;      /* sky patches of the daylight-coefficient matrices; 0: none */
} DevSensorInfo;
FEN_ASSERT_SIZE(DevSensorInfo, 16);

FEN_NS_END

#endif /* FEN_SENSOR_H */
