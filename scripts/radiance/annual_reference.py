#!/usr/bin/env python3
"""annual_reference.py — an annual daylight study of a fenestra scene (its open-window variant)
computed twice, with Radiance's two-phase method and with `fenestra render --annual`, on the same
geometry, the same sensor points, the same weather file and the same Reinhart sky subdivision,
and the two sets of numbers side by side. Radiance is a checking tool only: nothing in the build
or the tests uses it or this script.

    python3 scripts/radiance/annual_reference.py [--scene docs/results/radiance/room_open.gltf] \
        [--spacing 0.125] [--epw scenes/weather/tmy_45.000_8.000_2005_2016.epw] [--mf 1] \
        [--ab 5] [--ad 2048] [--lw LW] [--subpoints 1] [--direct-ad 4096] [--direct-subpoints 4] \
        [--processes 2] [--fenestra-time T] [--seed 1] [--repeat 1] [--radiance-uncorrelated] \
        [--occupied 8-18] [--work out/annual] [--json OUT] [--reuse]

The speed comparison at equal accuracy (step 7) repeats each method with independent random numbers:

    python3 scripts/radiance/annual_reference.py --ab 16 --ad 4096 --lw 2e-5 --repeat 2 \
        --radiance-uncorrelated --fenestra-time 30 --seed 1 --reuse --json out/annual/speed_t30.json
    python3 scripts/radiance/annual_reference.py --ab 16 --ad 4096 --lw 2e-5 --repeat 2 \
        --radiance-uncorrelated --fenestra-time 120 --seed 3 --reuse --json out/annual/speed_t120.json

(the second reuses the first's rcontrib runs and direct matrix; run nothing else meanwhile, the
times are the point).

Needs Radiance (`pip install pyradiance`: found in /opt/radenv's pyradiance/bin, or on PATH, or
`--radiance DIR`, pyradiance's package folder) with RAYPATH holding its lib/ (reinhart.cal), numpy,
and a built fenestra (build/fenestra; `--fenestra PATH`). Every step and every command line is
printed; the files go to --work (default out/annual/, which git ignores).

Steps:
1. Model: `gltf_to_rad.py SCENE --open-windows` (materials and polygons, frame
   (x, y, z)_glTF -> (x, -z, y)_Radiance: east +x, north +y, up +z), its CIE sky replaced by one
   glow of unit radiance over the whole sphere (`skyglow source skydome 0 0 4 0 0 1 360`; the
   directions below the horizon are reinhart.cal's patch 0, the ground); a second model with every
   material black; their octrees. The sensor points: workplane_points.py's lattice of --spacing
   over the node --floor, --height above it (glTF frame; fenestra reads it as it is), rotated into
   Radiance's frame for rcontrib, normals too.
2. Daylight coefficients, irradiance per unit radiance (sr):
   `rcontrib -I+ -ab AB -ad AD -lw LW -lr 0 -n N -e MF:M -f reinhart.cal -b rbin -bn Nrbins
   -m skyglow` (all light, AB ambient bounces), and the direct matrix (light that met no diffuse
   surface, as LM-83 asks for ASE) from the black model with -ab 1 -ad DIRECT_AD: a glow of radius
   0 is no light source, so `-ab 0` gives zeros (checked and reported); one ambient bounce onto
   the black model sees the sky directly and nothing else. fenestra's coefficients are means over
   each sensor's square cell, not values at its centre, so each matrix may be computed on K x K
   points spread over the cell and averaged (--subpoints, default 1, and --direct-subpoints, default
   4: near the window the direct view of the high sky changes within a cell). Wall and CPU seconds
   of each run (CPU: user + system of the child processes). With --repeat R the all-light matrix
   is computed R times with `-u+` added (--radiance-uncorrelated: rcontrib then seeds its random
   numbers from the clock, so runs started in different seconds are independent; with -u- every run
   is the same, and identical matrices stop the script), files dc_TAG_u_rK.mtx; everything below
   uses their mean (pooled), and Radiance's time is the mean of one run's.
3. Skies: `epw2wea`; `gendaymtx -m M` (Perez all-weather sky from the file's irradiance, the sun
   spread over its four nearest patches, ground reflectance 0.2) and `gendaymtx -m M -d` (the sun
   alone). Columns are the wea records (the middle of each hour: 0.5 .. 23.5); an hour is occupied
   where the hour ending at mid + 0.5 lies in (FROM, TO], i.e. mids FROM+0.5 .. TO-0.5: 3,650 a year
   for 8-18. Patch luminance = 179 x (0.265 R + 0.670 G + 0.065 B) cd/m^2.
4. Radiance's hourly illuminance: 179 x (0.265 R + 0.670 G + 0.065 B) of the coefficients times
   the sky, per point and occupied hour (dark hours 0 lux); the direct sun's illuminance: the
   direct matrix times the sun-only sky.
5. fenestra: `fenestra render SCENE --annual EPW --sensor-points PTS --sensor-size SPACING
   [--sky-patches M] --occupied FROM-TO --time T --seed N --no-progress` (T: --fenestra-time,
   default the wall time of Radiance's all-light rcontrib run). Its PATH.dc.mtx (lux per cd/m^2 of
   each patch) and PATH.dc-direct.mtx are multiplied by the same gendaymtx skies (the light
   transport compared alone); its own PATH.annual.csv (its own Perez patch skies, the sun in one
   patch) is reported apart. With --repeat R: R runs with seeds SEED .. SEED+R-1, matrices pooled,
   times the mean of one run's; the own-skies figures are the first run's.
6. Report: a markdown table per method (time; grid means of mean illuminance, sDA300/50%,
   ASE1000/250h, DA300, UDI 100-2000 and the shares below and above it); the matrices compared
   directly (per point: the sum over patches, i.e. the illuminance under a uniform sky of 1 cd/m^2,
   ground included, fenestra's ratio to Radiance, mean and RMS over points; per patch: summed over
   points; the relative Frobenius difference, also with fenestra's patches mirrored east-west and
   north-south, which shows a frame mistake); the per-point relative RMS difference of the mean
   annual illuminance on identical skies; ASE again with gendaymtx's sun gathered into the one
   patch holding most of it (fenestra places the sun in one patch, gendaymtx over four).
7. With --repeat R >= 2, each method's Monte Carlo noise from its runs' spread, on identical skies
   (gendaymtx's, as in 4 and 5): the hourly illuminance of every (cell, occupied daylit hour) and
   each cell's mean annual illuminance (mean over the occupied hours); the relative noise of one run
   = sqrt(mean over the elements of the variance across runs) / RMS of the pooled values, with two
   runs RMS(E1 - E2) / RMS(E) / sqrt 2 (both printed). fenestra's noise falls as 1/sqrt(its render
   time), so it reaches Radiance's noise in render x (sigma_F / sigma_R)^2 seconds; the ratio
   Radiance time (one all-light run) / that, in wall and CPU seconds, for fenestra's render
   seconds alone, its total (the fixed rest -- kernel build, calibration, the year's skies,
   output -- added unscaled) and its total scaled whole; fenestra's CPU seconds of rendering are
   estimated as its process CPU x render / total. The bias: fenestra / Radiance of the pooled
   hourly illuminance (ratio of the means over (cell, daylit hour) and mean of the ratios), and per
   row of patches in 6. fenestra's self-reported hourly noise (its JSON) beside the measured one.
   Everything also goes to --json (default WORK/annual_reference.json).

-ab 5 (the two-phase method's customary setting) stops after five bounces, which in a bright room
loses several per cent of the light far from the window; fenestra traces every bounce (Russian
roulette, unbiased). `--ab 16 --ad 4096 --lw 2e-5` (reference.py's check settings, within 0.1 % of
its converged reference on the room) gives the matrices to compare light transport against.

Metrics (equal cell areas): DA300 = share of occupied hours >= 300 lux; sDA300/50% = share of the
points with DA >= 50 %; ASE1000/250h = share of the points with more than 250 occupied hours of
direct sun >= 1000 lux; UDI = shares of occupied hours < 100, within [100, 2000], > 2000 lux.

--reuse takes matrices already in --work for the same settings (with the timings recorded beside
them) instead of computing them again; the fenestra run is reused only with an explicit
--fenestra-time (its files are named after the time and the seed).
"""
import argparse
import glob
import json
import math
import os
import re
import resource
import shlex
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gltf_to_rad  # noqa: E402
import workplane_points  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))
W_RAD = np.array(gltf_to_rad.RADIANCE_WEIGHTS)
EFFICACY = gltf_to_rad.RADIANCE_EFFICACY
TNAZ = [30, 30, 24, 24, 18, 12, 6]

SKY = """# one glow of unit radiance over the whole sphere: the daylight coefficients' source
# (reinhart.cal numbers the directions below the horizon as patch 0, the ground)
void glow skyglow
0
0
4 1 1 1 0

skyglow source skydome
0
0
4 0 0 1 360
"""


# --------------------------------------------------------------------------------------------
# running things


def step(text):
    print("\n== %s" % text, flush=True)


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, cwd=None, stdin=None, stdout=None, env=None):
    """Runs cmd (printed as a shell line), stdin/stdout from/to files; returns (wall s, CPU s)."""
    line = " ".join(shlex.quote(c) for c in cmd)
    if stdin:
        line += " < " + shlex.quote(os.path.relpath(stdin, cwd or os.getcwd()))
    if stdout:
        line += " > " + shlex.quote(os.path.relpath(stdout, cwd or os.getcwd()))
    print("$ %s%s" % ("(cd %s) " % os.path.relpath(cwd, ROOT) if cwd else "", line), flush=True)
    fin = open(stdin) if stdin else subprocess.DEVNULL
    fout = open(stdout + ".tmp", "w") if stdout else None
    cpu0, t0 = children_cpu(), time.time()
    p = subprocess.run(cmd, cwd=cwd, stdin=fin, stdout=fout, stderr=subprocess.PIPE, text=True, env=env)
    wall, cpu = time.time() - t0, children_cpu() - cpu0
    if stdin:
        fin.close()
    if fout:
        fout.close()
    err = p.stderr.strip().splitlines()
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (p.returncode, line, "\n".join(err[-20:])))
    if err:
        shown = err[:3] + (["... (%d more lines)" % (len(err) - 3)] if len(err) > 3 else [])
        print("   stderr: " + "\n   stderr: ".join(shown))
    if stdout:
        os.replace(stdout + ".tmp", stdout)
    print("   [%.1f s wall, %.1f s CPU]" % (wall, cpu), flush=True)
    return wall, cpu, p.stderr


def find_radiance(folder):
    """(bin folder, lib folder) of Radiance: --radiance, /opt/radenv's pyradiance, or PATH."""
    if folder:
        return os.path.join(folder, "bin"), os.path.join(folder, "lib")
    pkg = (glob.glob("/opt/radenv/lib/python3*/site-packages/pyradiance") or [""])[0]
    if pkg and os.path.exists(os.path.join(pkg, "bin", "rcontrib")):
        return os.path.join(pkg, "bin"), os.path.join(pkg, "lib")
    for d in os.environ.get("PATH", "").split(os.pathsep):
        if os.path.exists(os.path.join(d, "rcontrib")):
            return d, None
    sys.exit("annual_reference.py: Radiance not found (pip install pyradiance, or --radiance DIR)")


# --------------------------------------------------------------------------------------------
# matrices


def read_matrix(path):
    """(header dict, values as a float array of shape (rows, cols, comps)) of a Radiance matrix
    (ASCII, with or without header); rows inferred where the header has no NROWS."""
    with open(path) as f:
        text = f.read()
    head = {}
    if text.startswith("#?RADIANCE"):
        h, text = text.split("\n\n", 1)
        for line in h.splitlines():
            if "=" in line:
                k, v = line.split("=", 1)
                head[k.strip()] = v.strip()
    vals = np.array(text.split(), dtype=float)
    ncomp = int(head.get("NCOMP", 3))
    ncols = int(head["NCOLS"]) if "NCOLS" in head else None
    if ncols is None:
        first = text.strip().split("\n", 1)[0]
        ncols = len(first.split()) // ncomp
    rows = vals.size // (ncols * ncomp)
    if "NROWS" in head and int(head["NROWS"]) != rows:
        sys.exit("%s: NROWS=%s but %d rows of data" % (path, head["NROWS"], rows))
    return head, vals.reshape(rows, ncols, ncomp)


def patch_table(mf):
    """[(row, altitude centre deg, azimuth centre deg, patches in the row)] per patch, 0 the ground."""
    out = [(-1, -45.0, 0.0, 1)]
    alpha = 90.0 / (7 * mf + 0.5)
    for r in range(7 * mf + 1):
        n = 1 if r == 7 * mf else mf * TNAZ[r // mf]
        alt = 90.0 if r == 7 * mf else (r + 0.5) * alpha
        for c in range(n):
            out.append((r, alt, c * 360.0 / n, n))
    return out


def mirror_permutation(mf, kind):
    """Patch index map of the sky mirrored east-west (azimuth a -> -a) or north-south (a -> 180 - a)."""
    table = patch_table(mf)
    first = {}
    for i, (r, _, _, _) in enumerate(table):
        first.setdefault(r, i)
    perm = []
    for i, (r, _, _, n) in enumerate(table):
        if r < 0 or n == 1:
            perm.append(i)
            continue
        c = i - first[r]
        c2 = (-c) % n if kind == "ew" else (n // 2 - c) % n
        perm.append(first[r] + c2)
    return np.array(perm)


def radiance_points(points, side, k):
    """rcontrib input: each point (glTF frame) rotated into Radiance's frame, normal too; with k > 1,
    k x k points on a regular lattice over the point's square cell of side `side` (for a horizontal
    cell, its sides along x and z as fenestra's cells; otherwise along an arbitrary tangent pair)."""
    lines = []
    offs = [((i + 0.5) / k - 0.5) * side for i in range(k)]
    for x, y, z, dx, dy, dz in points:
        nrm = np.array([dx, dy, dz]) / math.sqrt(dx * dx + dy * dy + dz * dz)
        if abs(nrm[1]) > 0.999:
            t1, t2 = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
        else:
            t1 = np.cross([0.0, 1.0, 0.0], nrm)
            t1 /= np.linalg.norm(t1)
            t2 = np.cross(nrm, t1)
        d = gltf_to_rad.to_radiance((dx, dy, dz))
        for u in offs:
            for v in offs:
                q = np.array([x, y, z]) + (u * t1 + v * t2 if k > 1 else 0.0)
                lines.append("%.6f %.6f %.6f %.6g %.6g %.6g" % (gltf_to_rad.to_radiance(tuple(q)) + d))
    return "\n".join(lines) + "\n"


def patch_solid_angles(mf):
    alpha = 90.0 / (7 * mf + 0.5)
    out = [2.0 * math.pi]
    for r, _, _, n in patch_table(mf)[1:]:
        lo, hi = r * alpha, (90.0 if r == 7 * mf else (r + 1) * alpha)
        out.append(2.0 * math.pi / n * (math.sin(math.radians(hi)) - math.sin(math.radians(lo))))
    return np.array(out)


def sun_in_one_patch(Lsun, omega):
    """gendaymtx's sun (spread over its four nearest patches) gathered into the patch holding most of
    it, as fenestra places the sun: the same normal illuminance sum_p L_p omega_p."""
    e = Lsun * omega[:, None]
    out = np.zeros_like(Lsun)
    cols = np.nonzero(e.sum(axis=0) > 0)[0]
    best = e[:, cols].argmax(axis=0)
    out[best, cols] = e[:, cols].sum(axis=0) / omega[best]
    return out


def build_models(scene, work, env):
    """Step 1's models in WORK: scene_open.rad (gltf_to_rad.py SCENE --open-windows), model.rad (it
    under the unit sky glow) and model_black.rad (every material black), and their octrees; returns
    {"model": WORK/model.oct, "black": WORK/black.oct}."""
    geom = os.path.join(work, "scene_open.rad")
    run([sys.executable, os.path.join(HERE, "gltf_to_rad.py"), scene, "--open-windows", "--out", geom], env=env)
    text = open(geom).read()
    if text.count("\n# materials\n") != 1:
        sys.exit("%s: unexpected layout (no single '# materials' line)" % geom)
    head, body = text.split("\n# materials\n")
    if "void glass" in body:
        sys.exit("%s: still has glass; give the open-window scene" % geom)
    header = "\n".join(l for l in head.splitlines()[:3] if l.startswith("#"))
    model, black = os.path.join(work, "model.rad"), os.path.join(work, "model_black.rad")
    with open(model, "w") as f:
        f.write(header + "\n\n" + SKY + "\n# materials\n" + body)
    black_body, nblack = re.subn(r"(void plastic \S+\n0\n0\n5) \S+ \S+ \S+ (\S+) (\S+)", r"\1 0 0 0 0 0", body)
    with open(black, "w") as f:
        f.write(header + "\n# every material black: only the sky seen directly\n\n" + SKY + "\n# materials\n" + black_body)
    print("wrote %s (unit sky glow + %s) and %s (%d materials made black)" % (
        os.path.relpath(model, ROOT), os.path.relpath(geom, ROOT), os.path.relpath(black, ROOT), nblack))
    octs = {}
    for name, rad in (("model", model), ("black", black)):
        octs[name] = os.path.join(work, name + ".oct")
        run(["oconv", os.path.basename(rad)], cwd=work, stdout=octs[name], env=env)
    return octs


# --------------------------------------------------------------------------------------------
# metrics


def metrics(E, Esun, da_lux=300.0, sda_share=50.0, ase_lux=1000.0, ase_hours=250.0, udi=(100.0, 2000.0)):
    """Per point and grid means of (points x occupied hours) illuminance and direct-sun illuminance."""
    mean = E.mean(axis=1)
    da = 100.0 * (E >= da_lux).mean(axis=1)
    low = 100.0 * (E < udi[0]).mean(axis=1)
    useful = 100.0 * ((E >= udi[0]) & (E <= udi[1])).mean(axis=1)
    high = 100.0 * (E > udi[1]).mean(axis=1)
    ase_h = (Esun >= ase_lux).sum(axis=1)
    return {"per_point": {"mean_lux": mean, "da_pct": da, "udi_low_pct": low, "udi_useful_pct": useful,
                          "udi_high_pct": high, "ase_hours": ase_h},
            "grid": {"mean_lux": float(mean.mean()), "sda_pct": float(100.0 * (da >= sda_share).mean()),
                     "ase_pct": float(100.0 * (ase_h > ase_hours).mean()), "mean_da_pct": float(da.mean()),
                     "mean_udi_useful_pct": float(useful.mean()), "mean_udi_low_pct": float(low.mean()),
                     "mean_udi_high_pct": float(high.mean())}}


def rel_rms(a, b):
    """RMS over points of a / b - 1 (points where b > 0), and the mean of a / b."""
    ok = b > 0
    r = a[ok] / b[ok]
    return float(np.sqrt(np.mean((r - 1.0) ** 2))), float(r.mean())


# --------------------------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=os.path.join(ROOT, "docs", "results", "radiance", "room_open.gltf"),
                    help="glTF scene (its windows are dropped for Radiance; give the open-window variant)")
    ap.add_argument("--floor", default="floor")
    ap.add_argument("--height", type=float, default=0.8)
    ap.add_argument("--spacing", type=float, default=0.125, help="points' lattice spacing and cell side, m")
    ap.add_argument("--epw", default=os.path.join(ROOT, "scenes", "weather", "tmy_45.000_8.000_2005_2016.epw"))
    ap.add_argument("--mf", type=int, default=1, help="Reinhart subdivision MF (1: 145 patches + ground)")
    ap.add_argument("--occupied", default="8-18")
    ap.add_argument("--ab", type=int, default=5)
    ap.add_argument("--ad", type=int, default=2048)
    ap.add_argument("--lw", type=float, help="rcontrib -lw (default 0.2 / AD)")
    ap.add_argument("--subpoints", type=int, default=1,
                    help="the all-light matrix averaged over K x K points spread over each cell (1: its centre)")
    ap.add_argument("--direct-ad", type=int, default=4096, help="-ad of the direct matrix (-ab 1)")
    ap.add_argument("--direct-subpoints", type=int, default=4,
                    help="the direct matrix averaged over K x K points spread over each cell (4)")
    ap.add_argument("--processes", type=int, default=2, help="rcontrib -n")
    ap.add_argument("--fenestra", default=os.path.join(ROOT, "build", "fenestra"))
    ap.add_argument("--fenestra-time", type=float,
                    help="fenestra's --time, s (default: the wall time of the all-light rcontrib run)")
    ap.add_argument("--seed", type=int, default=1, help="fenestra's first --seed (the runs take SEED, SEED+1, ...)")
    ap.add_argument("--repeat", type=int, default=1,
                    help="independent runs of each method (the all-light rcontrib and fenestra); with 2 or more, "
                         "each method's Monte Carlo noise is measured from the spread between its runs and the "
                         "times are compared at equal accuracy (step 7); needs --radiance-uncorrelated")
    ap.add_argument("--radiance-uncorrelated", action="store_true",
                    help="give the all-light rcontrib -u+ (random sampling seeded from the clock) so that "
                         "repeated runs are independent; the runs' files are named ..._u_rK")
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "annual"))
    ap.add_argument("--json", help="results (default WORK/annual_reference.json)")
    ap.add_argument("--radiance", metavar="DIR", help="pyradiance's package folder (bin/ and lib/ inside)")
    ap.add_argument("--reuse", action="store_true", help="reuse matrices already in --work")
    a = ap.parse_args()
    if a.repeat < 1 or (a.repeat > 1 and not a.radiance_uncorrelated):
        sys.exit("annual_reference.py: --repeat %d needs --radiance-uncorrelated (with -u- rcontrib's runs are "
                 "identical)" % a.repeat)
    lw = a.lw if a.lw else 0.2 / a.ad
    occ_from, occ_to = (int(v) for v in a.occupied.split("-"))
    work = os.path.abspath(a.work)
    os.makedirs(work, exist_ok=True)
    out_json = a.json or os.path.join(work, "annual_reference.json")
    rbin, rlib = find_radiance(a.radiance)
    env = dict(os.environ, PATH=rbin + os.pathsep + os.environ.get("PATH", ""))
    env["RAYPATH"] = os.pathsep.join(["."] + ([rlib] if rlib else []) + ([os.environ["RAYPATH"]] if "RAYPATH" in os.environ else []))
    env.setdefault("POCL_CACHE_DIR", os.path.join(ROOT, "build", "pocl-cache"))
    print("Radiance: %s (RAYPATH=%s)" % (rbin, env["RAYPATH"]))
    version = subprocess.run(["rcontrib", "-version"], capture_output=True, text=True, env=env).stdout.strip()
    report = {"scene": os.path.relpath(a.scene, ROOT), "epw": os.path.relpath(a.epw, ROOT), "mf": a.mf,
              "occupied": a.occupied, "radiance_version": version, "machine_nproc": os.cpu_count()}

    # 1. ---------------------------------------------------------------------------------------
    step("1. Radiance model, octrees and sensor points")
    octs = build_models(a.scene, work, env)
    pts_path = os.path.join(work, "points_%g.pts" % a.spacing)
    run([sys.executable, os.path.join(HERE, "workplane_points.py"), a.scene, "--out", pts_path,
         "--floor", a.floor, "--height", "%g" % a.height, "--spacing", "%g" % a.spacing], env=env)
    points = workplane_points.read_points(pts_path)
    n = len(points)
    rad_pts = {}
    for k in sorted({1, a.subpoints, a.direct_subpoints}):
        rad_pts[k] = os.path.join(work, "points_%g_radiance%s.txt" % (a.spacing, "" if k == 1 else "_sub%d" % k))
        with open(rad_pts[k], "w") as f:
            f.write(radiance_points(points, a.spacing, k))
        print("%d points%s; rotated into Radiance's frame (x, -z, y) in %s" % (
            n, "" if k == 1 else " x %d sub-points over each cell" % (k * k), os.path.relpath(rad_pts[k], ROOT)))
    report["points"] = {"file": os.path.relpath(pts_path, ROOT), "count": n, "spacing_m": a.spacing,
                        "height_m": a.height}

    # 2. ---------------------------------------------------------------------------------------
    step("2. Radiance daylight coefficients (rcontrib)")
    contrib = ["-e", "MF:%d" % a.mf, "-f", "reinhart.cal", "-b", "rbin", "-bn", "Nrbins", "-m", "skyglow"]
    # -ab 0: a glow of radius 0 is not a light source, so no direct calculation sees it
    check_pts = os.path.join(work, "points_check.txt")
    with open(check_pts, "w") as f:
        f.write("".join(open(rad_pts[1]).readlines()[n - 1:n]))
    chk = os.path.join(work, "check_ab0.mtx")
    _, _, err0 = run(["rcontrib", "-I+", "-ab", "0"] + contrib + ["model.oct"], cwd=work, stdin=check_pts,
                     stdout=chk, env=env)
    ab0 = float(read_matrix(chk)[1].sum())
    print("   -ab 0 on the point nearest the window: sum of coefficients %g (%s)" % (
        ab0, "zero: the glow is no light source, so the direct matrix uses -ab 1 on the black model"
        if ab0 == 0 else "non-zero"))
    report["ab0_check"] = {"sum_sr": ab0, "stderr": err0.strip()}

    def rcontrib(tag, oct_name, opts, k):
        out = os.path.join(work, "dc_%s%s.mtx" % (tag, "" if k == 1 else "_sub%d" % k))
        meta = out + ".json"
        cmd = ["rcontrib", "-I+"] + opts + ["-n", str(a.processes)] + contrib + [oct_name]
        if a.reuse and os.path.exists(out) and os.path.exists(meta):
            m = json.load(open(meta))
            if m.get("cmd") == cmd and m.get("points") == n and m.get("subpoints") == k * k:
                print("$ (reused) %s  [%.1f s wall, %.1f s CPU then]" % (" ".join(cmd), m["wall_s"], m["cpu_s"]))
                return out, m
        wall, cpu, _ = run(cmd, cwd=work, stdin=rad_pts[k], stdout=out, env=env)
        m = {"cmd": cmd, "points": n, "subpoints": k * k, "wall_s": wall, "cpu_s": cpu}
        json.dump(m, open(meta, "w"))
        return out, m

    def cell_means(path, k):
        """The matrix averaged over each cell's k x k sub-points: (points, patches, 3)."""
        m = read_matrix(path)[1]
        if m.shape[0] != n * k * k:
            sys.exit("%s: %d rows for %d points x %d sub-points" % (path, m.shape[0], n, k * k))
        return m.reshape(n, k * k, m.shape[1], m.shape[2]).mean(axis=1)

    all_opts = ["-ab", str(a.ab), "-ad", str(a.ad), "-lw", "%g" % lw, "-lr", "0"]
    all_tag = "ab%d_ad%d_lw%g" % (a.ab, a.ad, lw)
    if a.radiance_uncorrelated:
        # -u+: rcontrib seeds its random numbers from the clock (seconds) instead of a fixed table, so runs
        # started in different seconds sample independently (the runs below take minutes each)
        all_opts.append("-u+")
        all_tag += "_u"
    dc_runs = [rcontrib(all_tag + ("_r%d" % (k + 1) if a.repeat > 1 else ""), "model.oct", all_opts, a.subpoints)
               for k in range(a.repeat)]
    dc_path, dc_meta = dc_runs[0]
    dd_path, dd_meta = rcontrib("direct_ad%d" % a.direct_ad, "black.oct",
                                ["-ab", "1", "-ad", str(a.direct_ad), "-lw", "%g" % (0.2 / a.direct_ad), "-lr", "0"],
                                a.direct_subpoints)
    Drgb_runs = [cell_means(path, a.subpoints) for path, _ in dc_runs]
    for k in range(1, a.repeat):
        if np.array_equal(Drgb_runs[k], Drgb_runs[0]):
            sys.exit("rcontrib runs 1 and %d gave identical matrices: their sampling is not independent" % (k + 1))
    Drgb = np.mean(Drgb_runs, axis=0)     # the runs pooled
    rad_wall = float(np.mean([m["wall_s"] for _, m in dc_runs]))     # one all-light run, mean over the runs
    rad_cpu = float(np.mean([m["cpu_s"] for _, m in dc_runs]))
    DDrgb = cell_means(dd_path, a.direct_subpoints)
    P = Drgb.shape[1]
    print("Radiance matrices: %d points x %d patches x %d components" % Drgb.shape)
    report["radiance_dc"] = {"all": dict(dc_meta, file=os.path.relpath(dc_path, ROOT)),
                             "all_runs": [dict(m, file=os.path.relpath(path, ROOT)) for path, m in dc_runs],
                             "direct": dict(dd_meta, file=os.path.relpath(dd_path, ROOT))}

    # 3. ---------------------------------------------------------------------------------------
    step("3. Skies (epw2wea, gendaymtx)")
    wea = os.path.join(work, "weather.wea")
    run(["epw2wea", a.epw, wea], env=env)
    sky_path, sun_path = os.path.join(work, "sky_mf%d.mtx" % a.mf), os.path.join(work, "sun_mf%d.mtx" % a.mf)
    _, _, gerr = run(["gendaymtx", "-m", str(a.mf), os.path.basename(wea)], cwd=work, stdout=sky_path, env=env)
    run(["gendaymtx", "-m", str(a.mf), "-d", os.path.basename(wea)], cwd=work, stdout=sun_path, env=env)
    sky_head, Srgb = read_matrix(sky_path)
    _, Sun = read_matrix(sun_path)
    recs = []
    for line in open(wea):
        v = line.split()
        if len(v) == 5 and not line[0].isalpha():
            recs.append((int(v[0]), int(v[1]), float(v[2])))
    if Srgb.shape[0] != P or Srgb.shape[1] != len(recs):
        sys.exit("gendaymtx: %s rows x %s columns, expected %d patches x %d wea records" % (
            Srgb.shape[0], Srgb.shape[1], P, len(recs)))
    occ = np.array([h + 0.5 - 1 >= occ_from and h + 0.5 <= occ_to for _, _, h in recs])
    print("gendaymtx: %d patches x %d hours (the wea records, in order: first %s, last %s); %d occupied "
          "(mid-hours %g .. %g), %d of them with daylight" % (
              P, len(recs), recs[0], recs[-1], occ.sum(), occ_from + 0.5, occ_to - 0.5,
              int((Srgb[1:, occ, :].sum(axis=(0, 2)) > 0).sum())))
    if Sun[0].max() > 0:
        print("   note: the sun-only sky has ground luminance; set to 0")
        Sun[0] = 0.0
    L = EFFICACY * (Srgb[:, occ, :] @ W_RAD)       # patches x occupied hours, cd/m^2
    Lsun = EFFICACY * (Sun[:, occ, :] @ W_RAD)
    report["skies"] = {"wea_records": len(recs), "occupied_hours": int(occ.sum()),
                       "daylit_occupied_hours": int((L[1:].sum(axis=0) > 0).sum()),
                       "sun_occupied_hours": int((Lsun.sum(axis=0) > 0).sum()),
                       "gendaymtx_warnings": len([l for l in gerr.splitlines() if "warning" in l])}

    # 4. ---------------------------------------------------------------------------------------
    step("4. Radiance hourly illuminance and metrics")
    # 179 x (w . (D_c @ S_c)) = sum_p (w-weighted D)_p x ... only when the sky is grey; do it per component
    def rad_hourly(D):
        return EFFICACY * sum(W_RAD[c] * (D[:, :, c] @ Srgb[:, occ, c]) for c in range(3))
    E_rad_runs = [rad_hourly(D) for D in Drgb_runs]
    E_rad = np.mean(E_rad_runs, axis=0)
    Esun_rad = EFFICACY * sum(W_RAD[c] * (DDrgb[:, :, c] @ Sun[:, occ, c]) for c in range(3))
    m_rad = metrics(E_rad, Esun_rad)
    print("Radiance: mean %.1f lux, sDA %.1f %%, ASE %.1f %%, mean DA %.1f %%, mean UDI %.1f %%" % tuple(
        m_rad["grid"][k] for k in ("mean_lux", "sda_pct", "ase_pct", "mean_da_pct", "mean_udi_useful_pct")))

    # 5. ---------------------------------------------------------------------------------------
    step("5. fenestra --annual")
    t_f = a.fenestra_time if a.fenestra_time else round(dc_meta["wall_s"], 1)
    fdir = os.path.join(work, "fenestra")
    os.makedirs(fdir, exist_ok=True)
    f_runs = []     # per run: (base path, command, run meta, its JSON, DC matrix, direct DC matrix)
    for seed in range(a.seed, a.seed + a.repeat):
        fbase = os.path.join(fdir, "f_mf%d_t%g_s%d" % (a.mf, t_f, seed))
        fcmd = [a.fenestra, "render", a.scene, "--out", fbase, "--annual", a.epw, "--sensor-points", pts_path,
                "--sensor-size", "%g" % a.spacing, "--sky-patches", str(a.mf), "--occupied", a.occupied,
                "--time", "%g" % t_f, "--seed", str(seed), "--no-progress"]
        fmeta = fbase + ".run.json"
        if a.reuse and a.fenestra_time and os.path.exists(fmeta) and json.load(open(fmeta)).get("cmd") == fcmd:
            fm = json.load(open(fmeta))
            print("$ (reused) %s  [%.1f s wall, %.1f s CPU then]" % (" ".join(fcmd), fm["wall_s"], fm["cpu_s"]))
        else:
            wall, cpu, ferr = run(fcmd, cwd=ROOT, env=env)
            fm = {"cmd": fcmd, "wall_s": wall, "cpu_s": cpu, "stderr": ferr.strip().splitlines()[-8:]}
            json.dump(fm, open(fmeta, "w"))
        fj = json.load(open(fbase + ".json"))
        _, F = read_matrix(fbase + ".dc.mtx")
        _, FD = read_matrix(fbase + ".dc-direct.mtx")
        if F.shape[:2] != (n, P):
            sys.exit("fenestra's matrix is %s, expected %d x %d" % (F.shape, n, P))
        print("   fenestra seed %d: %s paths, seconds %s" % (seed, fj.get("paths"), json.dumps(fj.get("seconds"))))
        f_runs.append((fbase, fcmd, fm, fj, F[:, :, 0], FD[:, :, 0]))
    # the first run's command, files, JSON and own-skies CSV; its matrices are the runs pooled
    fbase, fcmd, fm, fj = f_runs[0][:4]
    F = np.mean([r[4] for r in f_runs], axis=0)
    FD = np.mean([r[5] for r in f_runs], axis=0)
    f_wall = float(np.mean([r[2]["wall_s"] for r in f_runs]))
    f_cpu = float(np.mean([r[2]["cpu_s"] for r in f_runs]))
    E_fen = F @ L
    Esun_fen = FD @ Lsun
    m_fen = metrics(E_fen, Esun_fen)
    # ASE with the sun gathered into one patch, as fenestra's own skies place it
    Lsun1 = sun_in_one_patch(Lsun, patch_solid_angles(a.mf))
    ase1_rad = metrics(E_rad, (DDrgb @ W_RAD) @ Lsun1)["grid"]["ase_pct"]
    ase1_fen = metrics(E_fen, FD @ Lsun1)["grid"]["ase_pct"]
    rows = [l.strip().split(",") for l in open(fbase + ".annual.csv")]
    cols = {k: i for i, k in enumerate(rows[0])}
    csv = {k: np.array([float(r[cols[k]]) for r in rows[1:]]) for k in
           ("x_m", "y_m", "z_m", "mean_lux", "mean_std_err_lux", "da_pct", "udi_low_pct", "udi_useful_pct",
            "udi_high_pct", "ase_hours")}
    pos = np.array([p[:3] for p in points])
    if len(rows) - 1 != n or np.abs(np.stack([csv["x_m"], csv["y_m"], csv["z_m"]], 1) - pos).max() > 1e-4:
        sys.exit("fenestra's annual.csv rows do not match the points file")
    own = {"mean_lux": float(csv["mean_lux"].mean()), "sda_pct": float(100.0 * (csv["da_pct"] >= 50.0).mean()),
           "ase_pct": float(100.0 * (csv["ase_hours"] > 250).mean()), "mean_da_pct": float(csv["da_pct"].mean()),
           "mean_udi_useful_pct": float(csv["udi_useful_pct"].mean()),
           "mean_udi_low_pct": float(csv["udi_low_pct"].mean()), "mean_udi_high_pct": float(csv["udi_high_pct"].mean())}
    ja = fj["annual"]
    print("fenestra: %s paths, render %.1f s, total %.1f s" % (
        fj.get("paths"), fj["seconds"].get("render", 0), fj["seconds"].get("total", 0)))
    print("fenestra's JSON: sDA %.2f %%, ASE %.2f %%, mean DA %.2f %%, mean UDI %.2f %%, mean %.1f lux; its CSV "
          "recomputed: sDA %.2f, ASE %.2f, mean DA %.2f, mean UDI %.2f, mean %.1f" % (
              ja["sda_pct"], ja["ase_pct"], ja["mean_da_pct"], ja["mean_udi_useful_pct"], ja["mean_lux"],
              own["sda_pct"], own["ase_pct"], own["mean_da_pct"], own["mean_udi_useful_pct"], own["mean_lux"]))

    # 6. ---------------------------------------------------------------------------------------
    step("6. Comparison")
    Dw = Drgb @ W_RAD      # Radiance's coefficients, luminance-weighted (sr)
    DDw = DDrgb @ W_RAD
    cmp_dc = {}
    for name, R, Fm in (("all", Dw, F), ("direct", DDw, FD)):
        sr, sf = R.sum(axis=1), Fm.sum(axis=1)
        rms, mean_ratio = rel_rms(sf, sr)
        cr, cf = R.sum(axis=0), Fm.sum(axis=0)
        frob = {}
        for kind in ("none", "ew", "ns"):
            Fp = Fm if kind == "none" else Fm[:, mirror_permutation(a.mf, kind)]
            frob[kind] = float(np.linalg.norm(Fp - R) / np.linalg.norm(R))
        cmp_dc[name] = {"uniform_sky_lux_radiance_mean": float(sr.mean()), "uniform_sky_lux_fenestra_mean": float(sf.mean()),
                        "ratio_of_means": float(sf.mean() / sr.mean()), "ratio_mean_over_points": mean_ratio,
                        "ratio_rms_dev_over_points": rms,
                        "ground_patch_ratio": float(cf[0] / cr[0]) if cr[0] > 0 else None,
                        "ground_patch_share_radiance": float(cr[0] / cr.sum()),
                        "frobenius_rel_diff": frob,
                        "per_patch_sum_over_points": {"radiance": cr.round(6).tolist(), "fenestra": cf.round(6).tolist()}}
    # per row of patches (altitude bands), summed over points
    table = patch_table(a.mf)
    band = {}
    for name, R, Fm in (("all", Dw, F), ("direct", DDw, FD)):
        cr, cf = R.sum(axis=0), Fm.sum(axis=0)
        rows_ = sorted({t[0] for t in table})
        band[name] = [(r, float(cr[[i for i, t in enumerate(table) if t[0] == r]].sum()),
                       float(cf[[i for i, t in enumerate(table) if t[0] == r]].sum())) for r in rows_]
    # hourly illuminance on identical skies
    pm_r, pm_f = m_rad["per_point"]["mean_lux"], m_fen["per_point"]["mean_lux"]
    rms_mean, ratio_mean = rel_rms(pm_f, pm_r)
    day = L[1:].sum(axis=0) > 0
    hourly_rel = float(np.sqrt(np.mean((E_fen[:, day] - E_rad[:, day]) ** 2)) / np.sqrt(np.mean(E_rad[:, day] ** 2)))
    sky_effect = own["mean_lux"] / m_fen["grid"]["mean_lux"] - 1.0
    # fenestra's own noise (its per-cell standard error of the mean annual illuminance)
    fen_se_rel = float(np.sqrt(np.mean((csv["mean_std_err_lux"] / csv["mean_lux"]) ** 2)))

    t_rad = rad_wall + dd_meta["wall_s"]
    c_rad = rad_cpu + dd_meta["cpu_s"]
    methods = [
        ("Radiance 2-phase (rcontrib -ab %d -ad %d; gendaymtx skies)" % (a.ab, a.ad), t_rad, c_rad, m_rad["grid"]),
        ("fenestra DC x gendaymtx skies", f_wall, f_cpu, m_fen["grid"]),
        ("fenestra --annual (own skies%s)" % (", seed %d" % a.seed if a.repeat > 1 else ""), f_wall, f_cpu, own),
    ]
    print("\n| method | wall s | CPU s | mean lux | sDA300/50 % | ASE1000/250h % | mean DA300 % | UDI 100-2000 % | UDI <100 % | UDI >2000 % |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, w, c, g in methods:
        print("| %s | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |" % (
            name, w, c, g["mean_lux"], g["sda_pct"], g["ase_pct"], g["mean_da_pct"], g["mean_udi_useful_pct"],
            g["mean_udi_low_pct"], g["mean_udi_high_pct"]))
    print("\nRadiance time: all-light %.1f s wall / %.1f s CPU, direct %.1f s / %.1f s; fenestra --time %g: %.1f s wall "
          "/ %.1f s CPU (render %.1f s)%s" % (
              rad_wall, rad_cpu, dd_meta["wall_s"], dd_meta["cpu_s"], t_f, f_wall, f_cpu,
              np.mean([r[3]["seconds"].get("render", 0) for r in f_runs]),
              "; means over %d runs each, matrices pooled" % a.repeat if a.repeat > 1 else ""))
    print("\n| matrix | uniform-sky lux, Radiance | fenestra | ratio of means | ratio mean / RMS dev over points | ground patch ratio | rel. Frobenius diff (as is / E-W mirrored / N-S mirrored) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in ("all", "direct"):
        c = cmp_dc[name]
        print("| %s | %.4f | %.4f | %.4f | %.4f / %.4f | %s | %.3f / %.3f / %.3f |" % (
            name, c["uniform_sky_lux_radiance_mean"], c["uniform_sky_lux_fenestra_mean"], c["ratio_of_means"],
            c["ratio_mean_over_points"], c["ratio_rms_dev_over_points"],
            "%.4f" % c["ground_patch_ratio"] if c["ground_patch_ratio"] is not None else "-",
            c["frobenius_rel_diff"]["none"], c["frobenius_rel_diff"]["ew"], c["frobenius_rel_diff"]["ns"]))
    alpha = 90.0 / (7 * a.mf + 0.5)
    print("\nPer row of patches, coefficients summed over points (sr), fenestra / Radiance:")
    print("| row | altitude deg | all: Radiance | fenestra | ratio | direct: Radiance | fenestra | ratio |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for (r, ra, fa), (_, rd, fd) in zip(band["all"], band["direct"]):
        alt = "below 0" if r < 0 else "%.1f-%.1f" % (r * alpha, 90.0 if r == 7 * a.mf else (r + 1) * alpha)
        print("| %s | %s | %.3f | %.3f | %s | %.3f | %.3f | %s |" % (
            "ground" if r < 0 else r, alt, ra, fa, "%.4f" % (fa / ra) if ra > 0 else "-", rd, fd,
            "%.4f" % (fd / rd) if rd > 0 else "-"))
    print("\nMean annual illuminance per point on identical skies: fenestra / Radiance mean %.4f, RMS of the "
          "relative difference %.2f %%; hourly (daylit occupied hours) relative RMS difference %.2f %%" % (
              ratio_mean, 100 * rms_mean, 100 * hourly_rel))
    print("fenestra's own skies against gendaymtx's (same coefficients): mean illuminance %+.2f %%" % (100 * sky_effect))
    print("ASE with gendaymtx's sun gathered into the one patch holding most of it (as fenestra places the sun): "
          "Radiance %.2f %%, fenestra DC %.2f %% (four patches: %.2f %%, %.2f %%; fenestra's own skies %.2f %%)" % (
              ase1_rad, ase1_fen, m_rad["grid"]["ase_pct"], m_fen["grid"]["ase_pct"], own["ase_pct"]))
    print("fenestra's noise: RMS relative standard error of a cell's mean annual illuminance %.2f %%; hourly noise %.2f %%"
          % (100 * fen_se_rel, 100 * ja.get("hourly_noise_rel", float("nan"))))

    # 7. ---------------------------------------------------------------------------------------
    noise = None
    if a.repeat > 1:
        step("7. Monte Carlo noise from the repeated runs; times at equal accuracy")
        E_fen_runs = [r[4] @ L for r in f_runs]
        noise = {"radiance": {}, "fenestra": {}}
        for name, runs in (("radiance", E_rad_runs), ("fenestra", E_fen_runs)):
            for q, X in (("hourly", np.stack([E[:, day] for E in runs])),          # (cell, daylit occupied hour)
                         ("annual_mean", np.stack([E.mean(axis=1) for E in runs]))):   # cell: mean over occupied hours
                rms = float(np.sqrt(np.mean(X.mean(axis=0) ** 2)))
                noise[name][q] = {"single_run_rel": float(np.sqrt(X.var(axis=0, ddof=1).mean()) / rms), "rms_lux": rms,
                                  "pair_diff_rel": float(np.sqrt(np.mean((X[0] - X[1]) ** 2)) / rms)}
            noise[name]["grid_mean_lux_per_run"] = [float(E[:, day].mean()) for E in runs]
        fsec = {k: float(np.mean([r[3]["seconds"].get(k, 0.0) for r in f_runs])) for k in ("render", "total")}
        noise["fenestra"]["self_reported_hourly_noise_rel"] = float(np.mean(
            [r[3]["annual"].get("hourly_noise_rel", float("nan")) for r in f_runs]))
        # fenestra's CPU seconds of rendering alone: its process CPU x render / total (an estimate)
        f_cpu_render = f_cpu * fsec["render"] / fsec["total"]
        times = {"radiance": {"wall_s": rad_wall, "cpu_s": rad_cpu},
                 "fenestra": {"wall_s": f_wall, "cpu_s": f_cpu, "render_s": fsec["render"], "total_s": fsec["total"],
                              "cpu_render_s_est": f_cpu_render, "time_option_s": t_f}}
        eq = {}
        for q in ("hourly", "annual_mean"):
            k = (noise["fenestra"][q]["single_run_rel"] / noise["radiance"][q]["single_run_rel"]) ** 2
            f_eq = {"wall_render": fsec["render"] * k,
                    "wall_total": fsec["total"] - fsec["render"] + fsec["render"] * k,
                    "wall_total_all_scaled": fsec["total"] * k,
                    "cpu_render": f_cpu_render * k,
                    "cpu_total": f_cpu - f_cpu_render + f_cpu_render * k,
                    "cpu_total_all_scaled": f_cpu * k}
            eq[q] = {"time_factor": k, "fenestra_s_at_radiance_noise": f_eq,
                     "radiance_over_fenestra": {kk: (rad_wall if kk.startswith("wall") else rad_cpu) / v
                                                for kk, v in f_eq.items()}}
        Ef, Er = E_fen[:, day], E_rad[:, day]
        ok = Er > 0
        bias = {"ratio_of_means": float(Ef.sum() / Er.sum()), "mean_of_ratios": float((Ef[ok] / Er[ok]).mean()),
                "per_row_all": [{"row": r, "ratio": y / x if x > 0 else None} for r, x, y in band["all"]]}
        noise.update({"times": times, "equal_accuracy": eq, "bias": bias})
        print("| method | wall s | CPU s | hourly noise, one run | (run 1 - run 2) | annual-mean noise, one run | (run 1 - run 2) | grid mean lux per run |")
        print("|---|---:|---:|---:|---:|---:|---:|---|")
        for name, label, w, c in (("radiance", "Radiance rcontrib -ab %d -ad %d -lw %g -u+" % (a.ab, a.ad, lw), rad_wall, rad_cpu),
                                  ("fenestra", "fenestra --time %g (render %.1f s, total %.1f s)" % (
                                      t_f, fsec["render"], fsec["total"]), f_wall, f_cpu)):
            h, m = noise[name]["hourly"], noise[name]["annual_mean"]
            print("| %s | %.1f | %.1f | %.3f %% | %.3f %% | %.3f %% | %.3f %% | %s |" % (
                label, w, c, 100 * h["single_run_rel"], 100 * h["pair_diff_rel"], 100 * m["single_run_rel"],
                100 * m["pair_diff_rel"], " / ".join("%.1f" % v for v in noise[name]["grid_mean_lux_per_run"])))
        print("fenestra's self-reported hourly noise (JSON annual.hourly_noise_rel, mean of the runs): %.3f %%" % (
            100 * noise["fenestra"]["self_reported_hourly_noise_rel"]))
        print("\nEqual accuracy: fenestra's time at Radiance's noise = its render time x (sigma_F / sigma_R)^2 (+ its "
              "fixed rest for 'total'; 'all scaled': the whole time scaled); ratio Radiance time / that:")
        print("| noise of | (sigma_F/sigma_R)^2 | wall: render | total | all scaled | CPU: render | total | all scaled |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|")
        for q in ("hourly", "annual_mean"):
            rr = eq[q]["radiance_over_fenestra"]
            print("| %s | %.4f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |" % (
                q, eq[q]["time_factor"], rr["wall_render"], rr["wall_total"], rr["wall_total_all_scaled"],
                rr["cpu_render"], rr["cpu_total"], rr["cpu_total_all_scaled"]))
        print("\nBias, pooled runs, hourly illuminance over (cell, daylit occupied hour): fenestra / Radiance ratio of "
              "means %.4f, mean of ratios %.4f (per row of patches: the table above)" % (
                  bias["ratio_of_means"], bias["mean_of_ratios"]))

    report.update({
        "noise": noise,
        "settings": {"ab": a.ab, "ad": a.ad, "lw": lw, "subpoints": a.subpoints, "direct_ad": a.direct_ad,
                     "direct_subpoints": a.direct_subpoints, "processes": a.processes,
                     "fenestra_time_s": t_f, "seed": a.seed, "repeat": a.repeat,
                     "radiance_uncorrelated": a.radiance_uncorrelated},
        "methods": {"radiance": dict(m_rad["grid"], wall_s=t_rad, cpu_s=c_rad),
                    "fenestra_dc_gendaymtx_skies": dict(m_fen["grid"], wall_s=f_wall, cpu_s=f_cpu),
                    "fenestra_own_skies_csv": dict(own, wall_s=f_wall, cpu_s=f_cpu),
                    "fenestra_own_skies_json": {k: ja.get(k) for k in (
                        "sda_pct", "ase_pct", "mean_da_pct", "mean_udi_useful_pct", "mean_lux", "hourly_noise_rel",
                        "occupied_hours", "daylit_hours", "dark_hours", "uniform_sky_hours", "missing_hours")}},
        "fenestra": {"cmd": " ".join(fcmd), "paths": fj.get("paths"), "seconds": fj.get("seconds"),
                     "files": os.path.relpath(fbase, ROOT) + ".*",
                     "runs": [{"seed": r[3].get("seed"), "wall_s": r[2]["wall_s"], "cpu_s": r[2]["cpu_s"],
                               "paths": r[3].get("paths"), "seconds": r[3].get("seconds"),
                               "hourly_noise_rel": r[3]["annual"].get("hourly_noise_rel"),
                               "files": os.path.relpath(r[0], ROOT) + ".*"} for r in f_runs]},
        "dc_comparison": cmp_dc,
        "per_row": {k: [{"row": r, "radiance": x, "fenestra": y} for r, x, y in v] for k, v in band.items()},
        "annual_mean_per_point": {"ratio_mean": ratio_mean, "rel_rms_diff": rms_mean},
        "hourly_rel_rms_diff": hourly_rel,
        "own_vs_gendaymtx_skies_mean_lux_rel": sky_effect,
        "ase_pct_sun_in_one_patch": {"radiance": ase1_rad, "fenestra_dc": ase1_fen},
        "fenestra_mean_std_err_rel_rms": fen_se_rel,
        "per_point": {"radiance_mean_lux": pm_r.round(3).tolist(), "fenestra_dc_mean_lux": pm_f.round(3).tolist(),
                      "fenestra_own_mean_lux": csv["mean_lux"].tolist(),
                      "radiance_ase_hours": m_rad["per_point"]["ase_hours"].tolist(),
                      "fenestra_dc_ase_hours": m_fen["per_point"]["ase_hours"].tolist(),
                      "fenestra_own_ase_hours": csv["ase_hours"].astype(int).tolist()},
    })
    with open(out_json, "w") as f:
        json.dump(report, f, indent=1)
        f.write("\n")
    print("\nwrote %s" % os.path.relpath(out_json, ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main())
