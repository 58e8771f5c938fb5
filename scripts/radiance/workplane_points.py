#!/usr/bin/env python3
"""workplane_points.py — writes the sensor points of a work plane: a regular square lattice at a
height above the floor of a fenestra glTF scene, one point per line as `x y z dx dy dz` (metres,
the scene's own glTF frame: y up, so the normal is 0 1 0). The same file feeds Radiance's
`rtrace -I` (through scripts/radiance/reference.py, which rotates it into Radiance's frame) and
`fenestra render SCENE --sensor-points FILE --sensor-size S`, which reads it as it is.

    python3 scripts/radiance/workplane_points.py scenes/room.gltf --out room_workplane.pts \
        [--floor floor] [--height 0.8] [--spacing 0.036] [--margin 0]

The lattice covers the bounding rectangle (x, z) of the node named --floor, shrunk by --margin on
every side: n = floor(L / S) cells of side S along each axis, the block of cells centred in the
rectangle, so the first cell centre lies at least S/2 from each edge (exactly S/2 where L is a
whole multiple of S). A point is kept only where it lies above one of the floor's triangles; its
height is that of the floor's highest point plus --height (the floors here are flat). Points are
written row by row: z outer (north to south), x inner (west to east).

Standard library only.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_to_rad  # noqa: E402


def inside_xz(p, tri, eps=1e-12):
    """Whether (x, z) of p lies in the (x, z) projection of the triangle (either winding)."""
    (ax, _, az), (bx, _, bz), (cx, _, cz) = tri
    x, z = p
    d1 = (bx - ax) * (z - az) - (bz - az) * (x - ax)
    d2 = (cx - bx) * (z - bz) - (cz - bz) * (x - bx)
    d3 = (ax - cx) * (z - cz) - (az - cz) * (x - cx)
    neg = d1 < -eps or d2 < -eps or d3 < -eps
    pos = d1 > eps or d2 > eps or d3 > eps
    return not (neg and pos)


def lattice(lo, hi, s):
    n = int(math.floor((hi - lo) / s + 1e-9))
    first = lo + 0.5 * ((hi - lo) - n * s) + 0.5 * s
    return [first + i * s for i in range(n)]


def workplane(scene, floor="floor", height=0.8, spacing=0.036, margin=0.0):
    doc, buffers = gltf_to_rad.load_gltf(scene)
    tris = gltf_to_rad.node_triangles(doc, buffers, floor)
    if not tris:
        sys.exit("workplane_points.py: %s has no mesh node named '%s'" % (scene, floor))
    xs = [v[0] for t in tris for v in t]
    ys = [v[1] for t in tris for v in t]
    zs = [v[2] for t in tris for v in t]
    if max(ys) - min(ys) > 1e-6:
        print("workplane_points.py: warning: the floor is not flat (y %g..%g); the plane is %g m "
              "above its highest point" % (min(ys), max(ys), height), file=sys.stderr)
    y = max(ys) + height
    gx = lattice(min(xs) + margin, max(xs) - margin, spacing)
    gz = lattice(min(zs) + margin, max(zs) - margin, spacing)
    pts = []
    for z in gz:
        for x in gx:
            if any(inside_xz((x, z), t) for t in tris):
                pts.append((x, y, z))
    return pts, {"x": (min(xs), max(xs)), "z": (min(zs), max(zs)), "y": y,
                 "nx": len(gx), "nz": len(gz)}


def fmt_coord(v):
    """Micrometre precision without trailing zeros (the lattices here fall on whole mm)."""
    t = ("%.6f" % v).rstrip("0").rstrip(".")
    return "0" if t in ("-0", "") else t


def write_points(path, pts):
    """Writes (x, y, z) points with the normal 0 1 0 (through a temporary file, then renamed)."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        for x, y, z in pts:
            f.write("%s %s %s 0 1 0\n" % (fmt_coord(x), fmt_coord(y), fmt_coord(z)))
    os.replace(tmp, path)


def read_points(path):
    """[(x, y, z, dx, dy, dz)] of a points file."""
    pts = []
    with open(path) as f:
        for line in f:
            v = line.split()
            if len(v) >= 6:
                pts.append(tuple(float(t) for t in v[:6]))
    return pts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--out", required=True)
    ap.add_argument("--floor", default="floor", help="name of the floor node (default floor)")
    ap.add_argument("--height", type=float, default=0.8, help="metres above the floor (0.8)")
    ap.add_argument("--spacing", type=float, default=0.036, help="lattice spacing S, m (0.036)")
    ap.add_argument("--margin", type=float, default=0.0,
                    help="band along the floor's edges left without points, m (0)")
    a = ap.parse_args()
    pts, info = workplane(a.scene, a.floor, a.height, a.spacing, a.margin)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    write_points(a.out, pts)
    print("%s: %d points (%d x %d lattice, spacing %g m, %g m above the floor at y = %g)"
          % (a.out, len(pts), info["nx"], info["nz"], a.spacing, a.height, info["y"] - a.height))
    return 0


if __name__ == "__main__":
    sys.exit(main())
