#!/usr/bin/env python3
"""perez_reference.py — the reference table for fenestra's Perez all-weather sky (host/sky/perez_sky.h).

Runs Radiance's gendaylit (`pip install pyradiance`; RAYPATH set to its lib/; nothing in the build or
the tests needs it) as `gendaylit -ang ALT 180 -P EPSILON DELTA` over a grid of sun altitudes,
clearness values in each of the model's eight bins and brightness values, and writes
tests/data/perez_gendaylit.csv: the inputs and the five coefficients a..e gendaylit derives (the
brightfunc's arguments 3..7), or why it refused the condition; and tests/data/perez_condition_gendaylit.csv, the clearness and
brightness gendaylit derives from direct normal and diffuse horizontal irradiance; and
tests/data/perez_efficacy_gendaylit.csv, the direct normal illuminance it derives from irradiance. Altitudes stay at or below 87 degrees and brightness in (0.01, 0.6],
where gendaylit uses the inputs as given. Run: python3 scripts/radiance/perez_reference.py
"""
import csv
import glob
import os
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
binary = os.environ.get("GENDAYLIT") or (glob.glob("/opt/radenv/lib/python3*/site-packages/pyradiance/bin/gendaylit") or ["gendaylit"])[0]
rows = []
for alt in (5, 20, 40, 60, 80):
    for eps in (1.03, 1.1, 1.35, 1.7, 2.3, 3.5, 5.0, 8.0):
        for delta in (0.05, 0.15, 0.3, 0.5):
            run = subprocess.run([binary, "-ang", str(alt), "180", "-P", str(eps), str(delta)], capture_output=True,
                                 text=True, check=True)
            args = next(l for l in run.stdout.split("\n") if l.startswith("10 ")).split()
            # gendaylit prints a black sky (zeros) for a condition it refuses, and says why: the
            # gradation unbounded towards the horizon (B > 0), or a clearness and brightness that would
            # take more direct light than the sun has (not a sky that occurs): 1 and 2 here, else 0.
            refused = 1 if "positive Perez parameter B" in run.stderr else 2 if "exceeds solar constant" in run.stderr else 0
            rows.append([alt, eps, delta] + args[3:8] + [refused])
path = os.path.join(root, "tests", "data", "perez_gendaylit.csv")
with open(path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["sun_altitude_deg", "epsilon", "delta", "a", "b", "c", "d", "e", "refused"])
    w.writerows(rows)
print("wrote %d rows to %s (gendaylit: %s)" % (len(rows), path, binary), file=sys.stderr)

# Clearness and brightness from irradiance: `gendaylit -ang ALT 180 -W DNI DHI` (without a date it
# takes the eccentricity of 1 January), which prints them with four decimals.
rows = []
for alt in (10, 30, 50, 70):
    for dni, dhi in ((0, 80), (50, 200), (300, 150), (600, 120), (850, 90)):
        out = subprocess.run([binary, "-ang", str(alt), "180", "-W", str(dni), str(dhi)], capture_output=True,
                             text=True, check=True).stdout.split("\n")
        line = next(l for l in out if l.startswith("# epsilon, delta"))
        eps, delta = line.split(":")[1].split()[:2]
        rows.append([alt, dni, dhi, eps, delta])
path = os.path.join(root, "tests", "data", "perez_condition_gendaylit.csv")
with open(path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["sun_altitude_deg", "direct_normal_w_m2", "diffuse_horizontal_w_m2", "epsilon", "delta"])
    w.writerows(rows)
print("wrote %d rows to %s" % (len(rows), path), file=sys.stderr)

# The direct normal illuminance Perez's 1990 efficacy model gives: `gendaylit -ang ALT 180 -W DNI DHI -O 2`
# prints the sun's luminance (cd/m^2, as %.3e) over its disk of 0.2665 degrees radius; times the
# disk's solid angle that is the direct normal illuminance (precipitable water 2 cm, its default).
rows = []
for alt in (15, 30, 50, 70):
    for dni, dhi in ((100, 150), (400, 120), (700, 100), (850, 80)):
        out = subprocess.run([binary, "-ang", str(alt), "180", "-W", str(dni), str(dhi), "-O", "2"], capture_output=True,
                             text=True, check=True).stdout.split("\n")
        k = next(i for i, l in enumerate(out) if l.startswith("void light solar"))
        rows.append([alt, dni, dhi, out[k + 3].split()[1]])  # as printed: %.3e
path = os.path.join(root, "tests", "data", "perez_efficacy_gendaylit.csv")
with open(path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["sun_altitude_deg", "direct_normal_w_m2", "diffuse_horizontal_w_m2", "sun_luminance_cd_m2"])
    w.writerows(rows)
print("wrote %d rows to %s" % (len(rows), path), file=sys.stderr)
