#!/usr/bin/env python3
"""reinhart_reference.py — the reference numbering of the Reinhart sky patches (host/annual/sky_patches.h).

Runs Radiance's rcalc with reinhart.cal (`pip install pyradiance`; RAYPATH set to its lib/; nothing
in the build or the tests needs it) on directions spread over the sphere, and writes
tests/data/reinhart_rbin.csv: each direction in fenestra's frame (y up, north -z, east +x), the
subdivision MF and the patch rcalc gives it (rbin). Radiance's frame is z up, north +y, east +x, so
(Dx, Dy, Dz) = (x, -z, y). Directions within 0.05 degrees of a patch boundary are left out, where
single- and double-precision arithmetic may disagree. Run: python3 scripts/radiance/reinhart_reference.py
"""
import glob
import math
import os
import random
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
pkg = (glob.glob("/opt/radenv/lib/python3*/site-packages/pyradiance") or [""])[0]
rcalc = os.environ.get("RCALC") or os.path.join(pkg, "bin", "rcalc")
env = dict(os.environ, RAYPATH=os.environ.get("RAYPATH", os.path.join(pkg, "lib")))
random.seed(7)
TNAZ = [30, 30, 24, 24, 18, 12, 6]


def near_boundary(alt, azi, mf):
    alpha = 90.0 / (7 * mf + 0.5)
    if alt < 0.05 and alt > -0.05:
        return True
    if alt < 0:
        return False
    row = min(int(alt / alpha), 7 * mf)
    if row < 7 * mf and min(alt - row * alpha, (row + 1) * alpha - alt) < 0.05:
        return True
    if row == 7 * mf:
        return alt - row * alpha < 0.05
    inc = 360.0 / (mf * TNAZ[row // mf])
    x = (azi + 0.5 * inc) % inc
    return min(x, inc - x) < 0.05


rows = []
for mf in (1, 2, 4):
    dirs = []
    while len(dirs) < 400:
        z = random.uniform(-1.0, 1.0)
        phi = random.uniform(0.0, 2 * math.pi)
        r = math.sqrt(1 - z * z)
        x, y, up = r * math.cos(phi), r * math.sin(phi), z  # Radiance: east, north, up
        alt = math.degrees(math.asin(up))
        azi = math.degrees(math.atan2(x, y)) % 360.0
        if not near_boundary(alt, azi, mf):
            dirs.append((x, y, up))
    text = "".join("%.9f %.9f %.9f\n" % d for d in dirs)
    out = subprocess.run([rcalc, "-e", "MF:%d" % mf, "-f", "reinhart.cal", "-e", "Dx=$1;Dy=$2;Dz=$3", "-e",
                          "$1=rbin"], input=text, capture_output=True, text=True, check=True, env=env).stdout.split()
    for (x, y, up), b in zip(dirs, out):
        rows.append("%.9f,%.9f,%.9f,%d,%d" % (x, up, -y, mf, int(float(b))))
path = os.path.join(root, "tests", "data", "reinhart_rbin.csv")
with open(path, "w") as f:
    f.write("x,y,z,mf,rbin\n" + "\n".join(rows) + "\n")
print("wrote %d rows to %s (rcalc: %s)" % (len(rows), path, rcalc), file=sys.stderr)
