#!/usr/bin/env python3
"""direct_sun_reference.py — an annual study's direct sun by Radiance (five-phase) and by fenestra.

Radiance with one sun per hour at its true position, and `fenestra render --annual --annual-sun
exact` (and `--annual-sun patch`, the two-phase sun in its sky patch) on the same geometry, points,
weather file and occupied hours; per-cell ASE hours and mean direct-sun illuminance side by side. Radiance is a checking tool only: nothing in the build or the tests
uses it or this script.

    /opt/radenv/bin/python scripts/radiance/direct_sun_reference.py \
        [--scene docs/results/radiance/room_open.gltf] [--spacing 0.125] \
        [--epw scenes/weather/tmy_45.000_8.000_2005_2016.epw] [--occupied 8-18] [--subpoints 8] \
        [--check-subpoints 1,4] [--dj 0] [--processes 2] [--paths 4000000] [--seed 1] [--seeds 2] \
        [--extra-sun-points 8] [--spot 01-15:10,...] [--no-gendaymtx-check] [--work out/annual] \
        [--json OUT] [--reuse] [--nice 10]

About 2 minutes on 2 cores (rcontrib's 8 x 8 sub-points 35 s, gendaylit 10 s, fenestra ~5 s a run
on PoCL, 20 s with 8 x 8 sun points). The convergence check of the ASE hours (4 minutes more):

    /opt/radenv/bin/python scripts/radiance/direct_sun_reference.py --reuse --subpoints 16 \
        --check-subpoints 1,4,8 --extra-sun-points 8,16 --no-gendaymtx-check \
        --json out/annual/direct_sun_reference_k16.json

Needs what annual_reference.py needs (its step, run, find_radiance and radiance_points are used
here): Radiance (`pip install pyradiance`: /opt/radenv's pyradiance/bin, PATH, or --radiance DIR;
RAYPATH gets its lib/), numpy (so run it with /opt/radenv/bin/python), a built fenestra
(build/fenestra). Every command is printed (the per-hour gendaylit calls: the first and the last,
all of them in WORK/direct_sun/gendaylit.sh, which re-runs them); files go to WORK/direct_sun/
(the points file, as annual_reference.py's, to WORK/points_S.pts). The script lowers its own
priority (--nice) and so that of everything it starts.

Steps:
1. Model: `gltf_to_rad.py SCENE --open-windows` (frame (x, y, z)_glTF -> (x, -z, y)_Radiance: east
   +x, north +y, up +z), its sky removed: opaque geometry only. Points: workplane_points.py's
   lattice (glTF frame, as fenestra reads it), and for Radiance each cell's K x K sub-points on a
   regular lattice over its square (--subpoints K, default 8: fenestra's value is the mean over
   the square; --check-subpoints: more K, each compared with the reference), then K x K copies of a reference point 1 km above the model, normal up (its
   coefficient must be the sun's solid angle x sin(altitude): the check of the normalisation).
2. Suns, one per occupied hour whose record has direct normal and diffuse horizontal irradiance
   > 0 (fenestra's daylit hours with sun): Radiance's `gendaylit M D H-0.5 -y YEAR -a LAT -o -LON
   -m -15*TZ -d DEWPOINT -W DNI DHI`, i.e. the middle of the hour in the file's standard time,
   with the record's year: gendaylit's accurate solar position (-y; without a year, and in
   gendaymtx, Radiance uses its older sun.c formulas, off by up to ~1 degree: measured and
   reported in step 5), and its direct normal illuminance from the file's irradiance by Perez
   et al. (1990)'s luminous efficacy with the record's dew point (-d; 99.9 = missing: gendaylit's
   2 cm of precipitable water, as fenestra). The EPW has no illuminance fields (999999), so this
   is the "direct normal illuminance of the EPW" that fenestra also derives. Hours whose sun is
   below the horizon by gendaylit are dropped (their direct light on a horizontal plane is ~0).
3. Direct-sun coefficients, the five-phase direct-sun step: every sun a `light` of unit radiance
   and a `source` of 0.533 degrees in its own modifier (solarN, N = minutes since 1 January 0:00,
   gendaymtx -D's naming); `rcontrib -I+ -ab 0 -dj DJ -ds 0 -dt 0 -dc 1 -lr 0 -faf -c K*K -M
   suns.mod` (every sun tested by a shadow ray from every sub-point; -ab 0: only light straight
   from the sun; -c K*K: each output row the mean over a cell's sub-points; -dj 0: the ray aims at
   the disc's centre, --dj 1 jitters it over the disc). Coefficient / Omega_sun = visibility x
   cos(incidence); times the hour's direct normal illuminance = the cell's direct-sun lux.
4. fenestra: `fenestra render SCENE --out BASE --annual EPW --sensor-points PTS --sensor-size S
   --paths P --annual-sun exact|patch --seed N --no-progress` (exact with --seeds runs: N = SEED,
   SEED+1, ...: the spread of its jittered sun points between runs; --extra-sun-points N: exact
   runs with `--annual-sun-points N` added, N x N jittered points a cell and hour instead of its
   default 4 x 4), its BASE.annual.csv's ase_hours and sun_mean_lux.
5. Checks of the inputs: fenestra's sun (altitude, azimuth, normal illuminance) from `fenestra
   render SCENE --weather EPW --weather-hour MM-DD:HH` at the --spot hours against gendaylit's;
   gendaymtx -D's suns (the older formulas) against gendaylit -y's, all hours.
6. Per cell, for each fenestra run against Radiance: ase_hours (occupied hours with direct sun >=
   --ase-lux, default 1000), sun_mean_lux (the mean over ALL occupied hours, dark ones 0), ASE %
   (cells with > --ase-hours, default 250, hours); RMS, mean and max of the ase_hours difference,
   relative RMS difference of sun_mean_lux (RMS(f - r) / RMS(r), and RMS over cells of f/r - 1
   where r > 0), area-weighted means (fenestra's area_m2), the cells whose ASE class differs.
   Also Radiance with other K (--check-subpoints; K = 1: the cell centres) and with gendaymtx's
   suns, to show how much the quadrature and the solar position move the numbers. Everything to
   --json (default WORK/direct_sun_reference.json).

   Reading the ASE hours: a cell's hour counts when its mean direct sun over the square is >= 1000
   lux, a threshold a few per cent of full sun (~50 klux), so an hour in which a shadow edge (a
   window jamb, the sill, the head) leaves a small part of the cell in sun counts. An estimate of
   that mean from few points is unbiased, but whether it reaches the threshold is not: with N x N
   points a small sunlit part is often missed, so the count is biased low, most in the cells that
   shadow edges sweep (near the window wall), and independent points each hour do not average
   this out. The Radiance reference has the same bias on its regular lattice (K = 1 shows it
   large), shrinking with K; compare fenestra's default 4 x 4 with its --extra-sun-points runs.
   sun_mean_lux is linear in the estimate and has no such bias.

--reuse takes files already in WORK/direct_sun made with the same commands (gendaylit's hours, the
rcontrib matrices, the fenestra runs and spot renders) instead of running them again.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import annual_reference as ar  # noqa: E402  (step, run, find_radiance, radiance_points)
import workplane_points  # noqa: E402

ROOT = ar.ROOT
SUN_DEG = 0.533
OMEGA_SUN = 2.0 * math.pi * (1.0 - math.cos(math.radians(SUN_DEG / 2.0)))   # sr, as gendaylit and Radiance's source
EFFICACY = 179.0
MO_DA = (0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334)
DEFAULT_SPOT = "01-15:10,03-21:12,05-10:09,06-21:13,08-15:17,10-14:12,11-20:15,12-21:11"


# --------------------------------------------------------------------------------------------
# weather


def read_epw(path):
    """Site (lat, lon east +, tz hours) and records (line, year, month, day, hour, dew C or None,
    DNI, DHI W/m^2 or None) of an EPW file."""
    with open(path, newline="") as f:
        lines = f.read().splitlines()
    loc = lines[0].split(",")
    site = {"lat": float(loc[6]), "lon": float(loc[7]), "tz": float(loc[8])}
    recs = []
    for i, line in enumerate(lines[8:], start=9):
        v = line.split(",")
        if len(v) < 16:
            continue
        dew, dni, dhi = float(v[7]), float(v[14]), float(v[15])
        recs.append({"line": i, "year": int(v[0]), "month": int(v[1]), "day": int(v[2]), "hour": int(v[3]),
                     "dew": None if dew >= 99.0 else dew, "dni": None if dni >= 9999 else dni,
                     "dhi": None if dhi >= 9999 else dhi})
    return site, recs


def minute_id(month, day, mid_hour):
    """gendaymtx -D's sun number: minutes since 1 January 0:00 at the middle of the hour."""
    return int(round(60.0 * (24.0 * (MO_DA[month - 1] + day - 1) + mid_hour)))


def alt_az(v):
    """(altitude, azimuth clockwise from north) in degrees of a Radiance-frame direction."""
    return math.degrees(math.asin(max(-1.0, min(1.0, v[2])))), math.degrees(math.atan2(v[0], v[1])) % 360.0


def from_alt_az(alt, az):
    a, b = math.radians(alt), math.radians(az)
    return np.array([math.cos(a) * math.sin(b), math.cos(a) * math.cos(b), math.sin(a)])


def angle_deg(u, v):
    return math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(u, v) / np.linalg.norm(u) / np.linalg.norm(v))))))


SUN_RE = re.compile(r"void light solar\s+0\s+0\s+3 (\S+) \S+ \S+\s+solar source sun\s+0\s+0\s+4 (\S+) (\S+) (\S+) (\S+)")
ERROR_SKY_RE = re.compile(r"skybright perezlum.cal\s+0\s+10 (?:\S+\s+){7}(\S+)\s+(\S+)\s+(\S+)")

# Perez et al. (1990)'s direct luminous efficacy, Table 4: (a, b, c, d) per sky clearness category
PEREZ_DIRECT = ((57.20, -4.55, -2.98, 117.12), (98.99, -3.46, -1.21, 12.38), (109.83, -4.90, -1.71, -8.81),
                (110.34, -5.84, -1.99, -4.56), (106.36, -3.97, -1.75, -6.16), (107.19, -1.25, -1.51, -26.73),
                (105.75, 0.77, -1.26, -34.44), (101.18, 1.58, -1.10, -8.29))
PEREZ_BOUNDS = (1.0, 1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200, 12.1)


def perez_direct_lux(dni, dhi, alt_deg, doy, dew):
    """Direct normal illuminance as gendaylit -W computes it (its sky_brightness, sky_clearness with
    their limits, air_mass, get_eccentricity, direct_n_effi_PEREZ): used where gendaylit prints
    its error sky instead of a sun (a Perez sky with B > 0), and as a check of gendaylit's values."""
    z = 90.0 - min(alt_deg, 87.0)
    zr = math.radians(z)
    w = math.exp(0.07 * (dew if dew is not None and -40 <= dew <= 40 else 10.97353115) - 0.075)
    m = 1.0 / (math.cos(zr) + 0.15 * (93.885 - z) ** -1.253)
    da = 2.0 * math.pi * (doy - 1) / 365.0
    ecc = 1.00011 + 0.034221 * math.cos(da) + 0.00128 * math.sin(da) + 0.000719 * math.cos(2 * da) + 0.000077 * math.sin(2 * da)
    delta = min(max(dhi * m / (1367.0 * ecc), 0.01), 0.6)
    eps = ((dhi + dni) / dhi + 1.041 * zr ** 3) / (1.0 + 1.041 * zr ** 3)
    eps = 12.01 - 0.001 if eps > 12.01 else max(eps, 1.0)
    cat = max(i for i in range(8) if eps >= PEREZ_BOUNDS[i])
    a, b, c, d = PEREZ_DIRECT[cat]
    return dni * max(0.0, a + b * w + c * math.exp(5.73 * zr - 5.0) + d * delta)


def gendaylit_cmd(r, site):
    dew = r["dew"] if r["dew"] is not None else 99.9   # out of -40..40: gendaylit's 2 cm of water
    return ["gendaylit", str(r["month"]), str(r["day"]), "%.1f" % (r["hour"] - 0.5), "-y", str(r["year"]),
            "-a", "%g" % site["lat"], "-o", "%g" % -site["lon"], "-m", "%g" % (-15.0 * site["tz"]),
            "-d", "%g" % dew, "-W", "%g" % r["dni"], "%g" % r["dhi"]]


def solar_hours(recs, site, occ, env, path, reuse):
    """gendaylit's sun (direction, direct normal lux) per occupied record with DNI, DHI > 0."""
    todo = [r for r in recs if occ(r) and r["dni"] is not None and r["dhi"] is not None
            and r["dni"] > 0 and r["dhi"] > 0]
    cmds = [gendaylit_cmd(r, site) for r in todo]
    if reuse and os.path.exists(path):
        cached = json.load(open(path))
        if cached.get("cmds") == cmds:
            print("$ (reused %d gendaylit runs from %s)" % (len(cmds), os.path.relpath(path, ROOT)))
            return cached["hours"], cmds
    sh = os.path.join(os.path.dirname(path), "gendaylit.sh")
    with open(sh, "w") as f:
        f.write("# one gendaylit per occupied hour with sun (direct_sun_reference.py); RAYPATH as printed\n")
        for c in cmds:
            f.write(" ".join(c) + "\n")
    print("$ %s\n$ ... (%d gendaylit runs, one per occupied hour with DNI > 0 and DHI > 0; all in %s)\n$ %s" % (
        " ".join(cmds[0]), len(cmds), os.path.relpath(sh, ROOT), " ".join(cmds[-1])), flush=True)
    t0 = time.time()
    hours = []
    for r, c in zip(todo, cmds):
        p = subprocess.run(c, capture_output=True, text=True, env=env)
        m = SUN_RE.search(p.stdout)
        doy = MO_DA[r["month"] - 1] + r["day"]
        if p.returncode == 0 and m:
            L, x, y, z, ang = (float(t) for t in m.groups())
            if abs(ang - SUN_DEG) > 1e-6:
                sys.exit("gendaylit's sun is %g degrees across, expected %g" % (ang, SUN_DEG))
            lux = EFFICACY * L * OMEGA_SUN
            hours.append({"rec": r, "sun": [x, y, z], "lux": lux, "source": "gendaylit",
                          "perez_py_lux": perez_direct_lux(r["dni"], r["dhi"], math.degrees(math.asin(z)), doy, r["dew"])})
            continue
        e = ERROR_SKY_RE.search(p.stdout)
        if p.returncode == 0 and e and "positive Perez parameter B" in p.stderr:
            # gendaylit's error sky (its Perez sky has B > 0): it still names the sun's direction; the
            # direct illuminance by the same formulas here (the sun itself is fine: only the sky fails)
            x, y, z = (float(t) for t in e.groups())
            hours.append({"rec": r, "sun": [x, y, z], "source": "gendaylit error sky + perez_direct_lux",
                          "lux": perez_direct_lux(r["dni"], r["dhi"], math.degrees(math.asin(z)), doy, r["dew"]),
                          "why": p.stderr.strip()[:200]})
            continue
        hours.append({"rec": r, "sun": None, "why": (p.stderr.strip() or "no sun in output")[:200]})
    print("   [%.1f s wall]" % (time.time() - t0))
    json.dump({"cmds": cmds, "hours": hours}, open(path, "w"))
    return hours, cmds


# --------------------------------------------------------------------------------------------
# Radiance


def read_float_matrix(path):
    with open(path, "rb") as f:
        data = f.read()
    head, body = data.split(b"\n\n", 1)
    h = {k.strip(): v.strip() for k, v in (l.split("=", 1) for l in head.decode().splitlines() if "=" in l)}
    if h.get("FORMAT") != "float" or h.get("NCOMP") != "3":
        sys.exit("%s: expected a float matrix of 3 components" % path)
    v = np.frombuffer(body, dtype="<f4" if h.get("BigEndian", "0") == "0" else ">f4")
    cols = int(h["NCOLS"])
    return v.reshape(-1, cols, 3).astype(np.float64)


def cached_run(cmd, cwd, stdin, stdout, env, reuse, inputs=()):
    """ar.run, or the earlier result when --reuse finds one from the same command and inputs."""
    meta = stdout + ".json"
    key = {"cmd": cmd, "inputs": {os.path.basename(p): os.path.getsize(p) for p in inputs}}
    if reuse and os.path.exists(stdout) and os.path.exists(meta):
        m = json.load(open(meta))
        if m.get("key") == key:
            print("$ (reused) %s  [%.1f s wall, %.1f s CPU then]" % (" ".join(cmd), m["wall_s"], m["cpu_s"]))
            return m
    wall, cpu, err = ar.run(cmd, cwd=cwd, stdin=stdin, stdout=stdout, env=env)
    m = {"key": key, "wall_s": wall, "cpu_s": cpu, "stderr": err.strip().splitlines()[-5:]}
    json.dump(m, open(meta, "w"))
    return m


# --------------------------------------------------------------------------------------------
# comparison


def compare(f_ase, f_mean, r_ase, r_mean, area, ase_hours):
    d = f_ase - r_ase
    ok = r_mean > 0
    w = area / area.sum()
    return {"ase_pct": float(100.0 * (area * (f_ase > ase_hours)).sum() / area.sum()),
            "ase_pct_reference": float(100.0 * (area * (r_ase > ase_hours)).sum() / area.sum()),
            "ase_hours_rms_diff": float(np.sqrt(np.mean(d ** 2))), "ase_hours_mean_diff": float(d.mean()),
            "ase_hours_max_abs_diff": float(np.abs(d).max()),
            "ase_hours_cells_differing": int((d != 0).sum()),
            "ase_class_differs": int(((f_ase > ase_hours) != (r_ase > ase_hours)).sum()),
            "sun_mean_rel_rms_diff": float(np.sqrt(np.mean((f_mean - r_mean) ** 2)) / np.sqrt(np.mean(r_mean ** 2))),
            "sun_mean_rel_rms_per_cell": float(np.sqrt(np.mean((f_mean[ok] / r_mean[ok] - 1.0) ** 2))),
            "sun_mean_area_weighted": float((w * f_mean).sum()), "sun_mean_area_weighted_reference": float((w * r_mean).sum()),
            "sun_mean_ratio_of_means": float((w * f_mean).sum() / (w * r_mean).sum())}


def metrics(E, occupied_hours, ase_lux):
    """(ase_hours, sun_mean_lux) per cell from (cells x sun hours) lux."""
    return (E >= ase_lux).sum(axis=1).astype(float), E.sum(axis=1) / occupied_hours


# --------------------------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=os.path.join(ROOT, "docs", "results", "radiance", "room_open.gltf"))
    ap.add_argument("--floor", default="floor")
    ap.add_argument("--height", type=float, default=0.8)
    ap.add_argument("--spacing", type=float, default=0.125, help="points' lattice spacing and cell side, m")
    ap.add_argument("--epw", default=os.path.join(ROOT, "scenes", "weather", "tmy_45.000_8.000_2005_2016.epw"))
    ap.add_argument("--occupied", default="8-18")
    ap.add_argument("--ase-lux", type=float, default=1000.0)
    ap.add_argument("--ase-hours", type=float, default=250.0)
    ap.add_argument("--subpoints", type=int, default=8, help="Radiance's reference: K x K sub-points over each cell (8)")
    ap.add_argument("--check-subpoints", default="1,4",
                    help="Radiance also with these K (comma list; '' none), each against the reference")
    ap.add_argument("--dj", type=float, default=0.0, help="rcontrib -dj: 0 aims at the sun's centre, 1 jitters over its disc")
    ap.add_argument("--processes", type=int, default=2, help="rcontrib -n")
    ap.add_argument("--fenestra", default=os.path.join(ROOT, "build", "fenestra"))
    ap.add_argument("--paths", default="4000000")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--seeds", type=int, default=2, help="fenestra exact runs with seeds SEED.. (2: its own spread)")
    ap.add_argument("--extra-sun-points", default="8",
                    help="also fenestra exact runs (seed SEED) with --annual-sun-points N for these N (comma list; '' none)")
    ap.add_argument("--spot", default=DEFAULT_SPOT,
                    help="hours MM-DD:HH at which fenestra's sun is compared with gendaylit's (a day later "
                         "while that hour has no direct sun); '' for none")
    ap.add_argument("--no-gendaymtx-check", action="store_true",
                    help="skip Radiance with gendaymtx's (older) sun directions")
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "annual"))
    ap.add_argument("--json", help="results (default WORK/direct_sun_reference.json)")
    ap.add_argument("--radiance", metavar="DIR", help="pyradiance's package folder (bin/ and lib/ inside)")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--nice", type=int, default=10, help="lower this process's priority by N (0: no)")
    a = ap.parse_args()
    if a.nice:
        os.nice(a.nice)
    occ_from, occ_to = (int(v) for v in a.occupied.split("-"))
    work = os.path.abspath(a.work)
    wd = os.path.join(work, "direct_sun")
    os.makedirs(wd, exist_ok=True)
    out_json = a.json or os.path.join(work, "direct_sun_reference.json")
    rbin, env = radiance_env(a.radiance)
    print("Radiance: %s (RAYPATH=%s); POCL_CACHE_DIR=%s; nice +%d" % (rbin, env["RAYPATH"], env["POCL_CACHE_DIR"], a.nice))
    version = subprocess.run(["rcontrib", "-version"], capture_output=True, text=True, env=env).stdout.strip()
    report = {"scene": os.path.relpath(a.scene, ROOT), "epw": os.path.relpath(a.epw, ROOT), "occupied": a.occupied,
              "radiance_version": version, "sun_deg": SUN_DEG, "omega_sun_sr": OMEGA_SUN, "commands": []}
    t_start = time.time()

    # 1. ---------------------------------------------------------------------------------------
    ar.step("1. Radiance model (opaque, no sky) and points")
    geom = os.path.join(wd, "scene_open.rad")
    ar.run([sys.executable, os.path.join(HERE, "gltf_to_rad.py"), a.scene, "--open-windows", "--out", geom], env=env)
    text = open(geom).read()
    if text.count("\n# materials\n") != 1:
        sys.exit("%s: unexpected layout (no single '# materials' line)" % geom)
    head, body = text.split("\n# materials\n")
    if re.search(r"\bglass\b", body):
        sys.exit("%s: has glass; give the open-window scene" % geom)
    header = "\n".join(l for l in head.splitlines()[:3] if l.startswith("#"))
    model = os.path.join(wd, "model_opaque.rad")
    with open(model, "w") as f:
        f.write(header + "\n# opaque geometry only: no sky, no sun (the suns are in suns.rad)\n\n# materials\n" + body)
    pts_path = os.path.join(work, "points_%g.pts" % a.spacing)
    ar.run([sys.executable, os.path.join(HERE, "workplane_points.py"), a.scene, "--out", pts_path,
            "--floor", a.floor, "--height", "%g" % a.height, "--spacing", "%g" % a.spacing], env=env)
    points = workplane_points.read_points(pts_path)
    n = len(points)
    verts = np.array([[float(t) for t in m.split()] for m in re.findall(r"polygon \S+\n0\n0\n\d+ ([^\n]+)", body)])
    verts = verts.reshape(-1, 3) if verts.size else np.zeros((1, 3))
    top = float(verts[:, 2].max()) if verts.size else 0.0
    ref_point = (float(verts[:, 0].mean()), float(verts[:, 1].mean()), top + 1000.0)
    check_ks = [int(t) for t in a.check_subpoints.split(",") if t.strip()]
    ks = sorted({a.subpoints} | set(check_ks))
    rad_pts = {}
    for k in ks:
        rad_pts[k] = os.path.join(wd, "points_%g_k%d.txt" % (a.spacing, k))
        with open(rad_pts[k], "w") as f:
            f.write(ar.radiance_points(points, a.spacing, k))
            f.write(("%.6f %.6f %.6f 0 0 1\n" % ref_point) * (k * k))
        print("%d cells x %d sub-points (+ %d of the reference point %s, 1 km above the model) in %s" % (
            n, k * k, k * k, ref_point, os.path.relpath(rad_pts[k], ROOT)))

    # 2. ---------------------------------------------------------------------------------------
    ar.step("2. Suns: gendaylit per occupied hour with sun (accurate position with -y, the record's dew point)")
    site, recs = read_epw(a.epw)
    def occ(r):
        return r["hour"] - 1 >= occ_from and r["hour"] <= occ_to
    occupied_hours = sum(1 for r in recs if occ(r))
    hours, gl_cmds = solar_hours(recs, site, occ, env, os.path.join(wd, "hours.json"), a.reuse)
    report["commands"].append({"gendaylit_first": " ".join(gl_cmds[0]), "count": len(gl_cmds),
                               "all": os.path.relpath(os.path.join(wd, "gendaylit.sh"), ROOT)})
    bad = [h for h in hours if h["sun"] is None]
    below = [h for h in hours if h["sun"] is not None and h["sun"][2] <= 0]
    suns = [h for h in hours if h["sun"] is not None and h["sun"][2] > 0]
    print("site %s; %d records, %d occupied (hours ending %d..%d); %d with DNI > 0 and DHI > 0; gendaylit: %d suns "
          "above the horizon, %d below, %d failed%s" % (
              site, len(recs), occupied_hours, occ_from + 1, occ_to, len(hours), len(suns), len(below), len(bad),
              "" if not bad else " (first: %s)" % bad[0]["why"]))
    lux_g = np.array([h["lux"] for h in suns])
    fallback = [h for h in suns if h["source"] != "gendaylit"]
    chk = np.array([h["perez_py_lux"] / h["lux"] - 1.0 for h in suns if h["source"] == "gendaylit" and h["lux"] > 0])
    print("%d suns from gendaylit's error sky (its Perez sky has B > 0), their direct illuminance by this script's copy "
          "of gendaylit's formulas, which reproduce gendaylit's own on the other %d hours to %.2e at most (mean %.1e; "
          "gendaylit prints 4 digits)" % (len(fallback), len(chk), np.abs(chk).max(), chk.mean()))
    print("direct normal illuminance (gendaylit, the record's dew point): mean %.0f lux over the %d hours, max %.0f" % (
        lux_g.mean(), len(suns), lux_g.max()))
    sun_rad = os.path.join(wd, "suns.rad")
    sun_mod = os.path.join(wd, "suns.mod")
    ids = [minute_id(h["rec"]["month"], h["rec"]["day"], h["rec"]["hour"] - 0.5) for h in suns]
    with open(sun_rad, "w") as f, open(sun_mod, "w") as g:
        f.write("# one sun per occupied hour with direct sun: gendaylit -y's direction, unit radiance\n")
        for i, h in zip(ids, suns):
            f.write("\nvoid light solar%d\n0\n0\n3 1 1 1\n\nsolar%d source sun%d\n0\n0\n4 %.6f %.6f %.6f %g\n" % (
                i, i, i, h["sun"][0], h["sun"][1], h["sun"][2], SUN_DEG))
            g.write("solar%d\n" % i)
    print("wrote %s and %s (%d suns)" % (os.path.relpath(sun_rad, ROOT), os.path.relpath(sun_mod, ROOT), len(suns)))
    report["hours"] = {"records": len(recs), "occupied": occupied_hours, "dni_dhi_positive": len(hours),
                       "suns": len(suns), "below_horizon": len(below), "gendaylit_failed": len(bad),
                       "mean_normal_lux": float(lux_g.mean()), "error_sky_hours": len(fallback),
                       "perez_py_vs_gendaylit_max_rel": float(np.abs(chk).max())}

    # 3. ---------------------------------------------------------------------------------------
    ar.step("3. Direct-sun coefficients (rcontrib -ab 0, one modifier per sun)")
    octree = os.path.join(wd, "dsun.oct")
    cached_run(["oconv", os.path.basename(model), os.path.basename(sun_rad)], wd, None, octree, env, a.reuse,
               inputs=(model, sun_rad))
    G = {}
    rc_meta = {}
    for k in ks:
        out = os.path.join(wd, "dsun_k%d_dj%g.mtx" % (k, a.dj))
        cmd = ["rcontrib", "-I+", "-ab", "0", "-dj", "%g" % a.dj, "-ds", "0", "-dt", "0", "-dc", "1", "-lr", "0",
               "-n", str(a.processes), "-faf", "-c", str(k * k), "-M", os.path.basename(sun_mod), os.path.basename(octree)]
        rc_meta[k] = cached_run(cmd, wd, rad_pts[k], out, env, a.reuse, inputs=(rad_pts[k], octree, sun_mod))
        report["commands"].append(" ".join(cmd) + " < " + os.path.relpath(rad_pts[k], wd) + " > " + os.path.relpath(out, wd))
        M = read_float_matrix(out)
        if M.shape != (n + 1, len(suns), 3):
            sys.exit("%s: %s, expected %d rows x %d suns x 3" % (out, M.shape, n + 1, len(suns)))
        M = M.mean(axis=2) / OMEGA_SUN          # grey: visibility x cos(incidence)
        ref = M[n]
        expect = np.array([h["sun"][2] for h in suns])
        err = float(np.abs(ref / expect - 1.0).max())
        print("   K = %d: reference point above the model: coefficient / (Omega_sun sin(altitude)) - 1 at most %.2e%s" % (
            k, err, "" if err < 1e-3 else "  (!)"))
        if err > 1e-2:
            sys.exit("the reference point's coefficients are not Omega_sun x sin(altitude): normalisation wrong")
        G[k] = M[:n]
    report["radiance_rcontrib"] = {str(k): {"wall_s": rc_meta[k]["wall_s"], "cpu_s": rc_meta[k]["cpu_s"]} for k in ks}

    E_rad = {k: G[k] * lux_g[None, :] for k in ks}
    K = a.subpoints
    r_ase, r_mean = metrics(E_rad[K], occupied_hours, a.ase_lux)

    # 4. ---------------------------------------------------------------------------------------
    ar.step("4. fenestra --annual, --annual-sun exact and patch")
    fdir = os.path.join(wd, "fenestra")
    os.makedirs(fdir, exist_ok=True)
    runs = []
    extra = [int(t) for t in a.extra_sun_points.split(",") if t.strip()]
    for mode, seed, sp in ([("exact", a.seed + i, None) for i in range(a.seeds)] + [("patch", a.seed, None)]
                           + [("exact", a.seed, v) for v in extra]):
        base = os.path.join(fdir, "f_%s%s_p%s_s%d" % (mode, "_sp%d" % sp if sp else "", a.paths, seed))
        cmd = [a.fenestra, "render", a.scene, "--out", base, "--annual", a.epw, "--sensor-points", pts_path,
               "--sensor-size", "%g" % a.spacing, "--paths", a.paths, "--annual-sun", mode]
        cmd += ["--annual-sun-points", str(sp)] if sp else []
        cmd += ["--seed", str(seed), "--occupied", a.occupied, "--ase-lux", "%g" % a.ase_lux,
                "--ase-hours", "%g" % a.ase_hours, "--no-progress"]
        cmd_rel = [os.path.relpath(c, ROOT) if os.path.isabs(c) else c for c in cmd]
        meta = base + ".run.json"
        st = os.stat(a.fenestra)
        binary = {"size": st.st_size, "mtime": st.st_mtime}     # a rebuilt fenestra is run again
        if (a.reuse and os.path.exists(meta) and json.load(open(meta)).get("cmd") == cmd_rel
                and json.load(open(meta)).get("binary") == binary and os.path.exists(base + ".annual.csv")):
            m = json.load(open(meta))
            print("$ (reused) %s  [%.1f s wall then]" % (" ".join(cmd_rel), m["wall_s"]))
        else:
            wall, cpu, err = ar.run(cmd_rel, cwd=ROOT, env=env)
            m = {"cmd": cmd_rel, "binary": binary, "wall_s": wall, "cpu_s": cpu, "stderr": err.strip().splitlines()[-6:]}
            json.dump(m, open(meta, "w"))
        report["commands"].append("POCL_CACHE_DIR=%s " % os.path.relpath(env["POCL_CACHE_DIR"], ROOT) + " ".join(cmd_rel))
        rows = [l.rstrip("\r\n").split(",") for l in open(base + ".annual.csv")]
        cols = {c: i for i, c in enumerate(rows[0])}
        if "sun_mean_lux" not in cols:
            sys.exit("%s.annual.csv has no sun_mean_lux column: an older fenestra?" % base)
        csv = {c: np.array([float(r[cols[c]]) for r in rows[1:]]) for c in ("x_m", "y_m", "z_m", "area_m2", "ase_hours", "sun_mean_lux")}
        pos = np.array([p[:3] for p in points])
        if len(rows) - 1 != n or np.abs(np.stack([csv["x_m"], csv["y_m"], csv["z_m"]], 1) - pos).max() > 1e-4:
            sys.exit("%s.annual.csv rows do not match the points file" % base)
        fj = json.load(open(base + ".json"))["annual"]
        print("   %s seed %d: JSON ase_pct %.2f %%, sun %s, sun_points %s, daylit %d of %d occupied hours, %s direct-sun "
              "samples" % (mode, seed, fj["ase_pct"], fj.get("sun"), fj.get("sun_points"), fj["daylit_hours"],
                           fj["occupied_hours"], fj.get("direct_sun_samples")))
        runs.append({"mode": mode, "seed": seed, "sun_points": fj.get("sun_points"), "extra": bool(sp),
                     "label": "%s%s seed %d" % (mode, ", %dx%d sun points" % (sp, sp) if sp else "", seed),
                     "base": base, "csv": csv, "json": fj, "wall_s": m["wall_s"]})
    area = runs[0]["csv"]["area_m2"]
    if runs[0]["json"]["occupied_hours"] != occupied_hours:
        print("   note: fenestra counts %d occupied hours, this script %d" % (runs[0]["json"]["occupied_hours"], occupied_hours))

    # 5. ---------------------------------------------------------------------------------------
    ar.step("5. Inputs: fenestra's sun against gendaylit's; gendaymtx's solar position against gendaylit's")
    by_key = {(h["rec"]["month"], h["rec"]["day"], h["rec"]["hour"]): h for h in suns}
    spot = []
    sdir = os.path.join(wd, "spot")
    os.makedirs(sdir, exist_ok=True)
    for s in [t for t in a.spot.split(",") if t]:
        mo, da, hr = int(s[0:2]), int(s[3:5]), int(s[6:8])
        jd = MO_DA[mo - 1] + da
        for step_d in range(15):          # the first day from there whose hour has a sun
            j = jd + step_d
            m2 = max(i for i in range(12) if MO_DA[i] < j) + 1
            key = (m2, j - MO_DA[m2 - 1], hr)
            if key in by_key:
                break
        else:
            continue
        h = by_key[key]
        label = "%02d-%02d:%02d" % key
        base = os.path.join(sdir, "wh_%02d%02d%02d" % key)
        cmd = [os.path.relpath(a.fenestra, ROOT), "render", os.path.relpath(a.scene, ROOT), "--out", os.path.relpath(base, ROOT) + ".exr",
               "--weather", os.path.relpath(a.epw, ROOT), "--weather-hour", label, "--paths", "10000", "--width", "64", "--no-progress"]
        if not (a.reuse and os.path.exists(base + ".json") and os.path.getmtime(base + ".json") > os.path.getmtime(a.fenestra)):
            ar.run(cmd, cwd=ROOT, env=env)
        else:
            print("$ (reused) " + " ".join(cmd))
        fj = json.load(open(base + ".json"))["sun"]
        f_alt, f_az, f_lux = fj["altitude_deg"], fj["azimuth_deg"], fj["normal_illuminance_lux"]
        g_alt, g_az = alt_az(h["sun"])
        spot.append({"hour": label, "fenestra_alt": f_alt, "fenestra_az": f_az, "fenestra_lux": f_lux,
                     "gendaylit_alt": g_alt, "gendaylit_az": g_az, "gendaylit_lux": h["lux"],
                     "angle_deg": angle_deg(from_alt_az(f_alt, f_az), np.array(h["sun"]))})
    if spot:
        print("\n| hour | fenestra alt / az deg (apparent) | gendaylit -y alt / az deg (true) | angle deg | fenestra lux | gendaylit lux | ratio |")
        print("|---|---|---|---:|---:|---:|---:|")
        for s in spot:
            print("| %s | %.3f / %.3f | %.3f / %.3f | %.3f | %.0f | %.0f | %.4f |" % (
                s["hour"], s["fenestra_alt"], s["fenestra_az"], s["gendaylit_alt"], s["gendaylit_az"], s["angle_deg"],
                s["fenestra_lux"], s["gendaylit_lux"], s["fenestra_lux"] / s["gendaylit_lux"]))
    # gendaymtx (the older sun.c formulas) against gendaylit -y, every sun
    wea = os.path.join(wd, "weather.wea")
    ar.run(["epw2wea", a.epw, wea], env=env)
    dm_rad = os.path.join(wd, "gendaymtx_suns.rad")
    ar.run(["gendaymtx", "-5", "%g" % SUN_DEG, "-d", "-D", os.path.basename(dm_rad), "-m", "1", os.path.basename(wea)],
           cwd=wd, stdout=os.path.join(wd, "gendaymtx_sun.mtx"), env=env)
    dm = {int(i): np.array([float(x), float(y), float(z)]) for i, x, y, z in
          re.findall(r"solar(\d+) source sun\d+\s+0\s+0\s+4 (\S+) (\S+) (\S+)", open(dm_rad).read())}
    ang = np.array([angle_deg(dm[i], np.array(h["sun"])) if i in dm else np.nan for i, h in zip(ids, suns)])
    dalt = np.array([alt_az(dm[i])[0] - alt_az(h["sun"])[0] if i in dm else np.nan for i, h in zip(ids, suns)])
    print("\ngendaymtx -D's suns (no year: Radiance's older sun.c formulas) against gendaylit -y's: angle mean %.3f, "
          "max %.3f deg; altitude difference mean %+.3f, extremes %+.3f / %+.3f deg (%d of %d suns matched)" % (
              np.nanmean(ang), np.nanmax(ang), np.nanmean(dalt), np.nanmin(dalt), np.nanmax(dalt),
              int(np.isfinite(ang).sum()), len(suns)))
    report["solar_position"] = {"spot_fenestra_vs_gendaylit": spot,
                                "gendaymtx_vs_gendaylit_y": {"angle_mean_deg": float(np.nanmean(ang)), "angle_max_deg": float(np.nanmax(ang)),
                                                             "alt_diff_mean_deg": float(np.nanmean(dalt)),
                                                             "alt_diff_min_deg": float(np.nanmin(dalt)), "alt_diff_max_deg": float(np.nanmax(dalt))}}
    # Radiance again with gendaymtx's sun directions: needs its own rcontrib run (cheap: the same points)
    dm_ok = all(i in dm for i in ids) and not a.no_gendaymtx_check
    E_dm = None
    if dm_ok:
        dm_sun_rad, dm_sun_mod = os.path.join(wd, "suns_gendaymtx_dir.rad"), os.path.join(wd, "suns_gendaymtx_dir.mod")
        with open(dm_sun_rad, "w") as f:
            f.write("# the same suns, gendaymtx's (older) directions\n")
            for i in ids:
                f.write("\nvoid light solar%d\n0\n0\n3 1 1 1\n\nsolar%d source sun%d\n0\n0\n4 %.6f %.6f %.6f %g\n" % (
                    i, i, i, dm[i][0], dm[i][1], dm[i][2], SUN_DEG))
        with open(dm_sun_mod, "w") as g:
            g.write("".join("solar%d\n" % i for i in ids))
        oct2 = os.path.join(wd, "dsun_gendaymtx_dir.oct")
        cached_run(["oconv", os.path.basename(model), os.path.basename(dm_sun_rad)], wd, None, oct2, env, a.reuse,
                   inputs=(model, dm_sun_rad))
        out2 = os.path.join(wd, "dsun_gendaymtx_dir_k%d.mtx" % K)
        cmd2 = ["rcontrib", "-I+", "-ab", "0", "-dj", "%g" % a.dj, "-ds", "0", "-dt", "0", "-dc", "1", "-lr", "0",
                "-n", str(a.processes), "-faf", "-c", str(K * K), "-M", os.path.basename(dm_sun_mod), os.path.basename(oct2)]
        cached_run(cmd2, wd, rad_pts[K], out2, env, a.reuse, inputs=(rad_pts[K], oct2, dm_sun_mod))
        report["commands"].append(" ".join(cmd2) + " < " + os.path.relpath(rad_pts[K], wd) + " > " + os.path.relpath(out2, wd))
        E_dm = read_float_matrix(out2).mean(axis=2)[:n] / OMEGA_SUN * lux_g[None, :]

    # 6. ---------------------------------------------------------------------------------------
    ar.step("6. Comparison per cell (%d cells; %d occupied hours, %d with a sun; ASE: >= %g lux for > %g hours)" % (
        n, occupied_hours, len(suns), a.ase_lux, a.ase_hours))
    rows = []
    ref_name = "Radiance, %dx%d sub-points%s" % (K, K, ", -dj %g" % a.dj if a.dj else "")
    for r in runs:
        c = compare(r["csv"]["ase_hours"], r["csv"]["sun_mean_lux"], r_ase, r_mean, area, a.ase_hours)
        rows.append(("fenestra %s vs %s" % (r["label"], ref_name), c))
    ex = [r for r in runs if r["mode"] == "exact" and not r["extra"]]
    if len(ex) >= 2:
        c = compare(ex[1]["csv"]["ase_hours"], ex[1]["csv"]["sun_mean_lux"], ex[0]["csv"]["ase_hours"],
                    ex[0]["csv"]["sun_mean_lux"], area, a.ase_hours)
        rows.append(("fenestra exact seed %d vs seed %d (its own spread)" % (ex[1]["seed"], ex[0]["seed"]), c))
    for k in check_ks:
        if k == K:
            continue
        a1, m1 = metrics(E_rad[k], occupied_hours, a.ase_lux)
        rows.append(("Radiance %s vs %s (quadrature)" % ("cell centres" if k == 1 else "%dx%d sub-points" % (k, k), ref_name),
                     compare(a1, m1, r_ase, r_mean, area, a.ase_hours)))
    if E_dm is not None:
        ad, md = metrics(E_dm, occupied_hours, a.ase_lux)
        rows.append(("Radiance with gendaymtx's sun directions vs %s" % ref_name, compare(ad, md, r_ase, r_mean, area, a.ase_hours)))
    print("\n| comparison | ASE % (first) | ASE % (second) | ase_hours RMS diff | mean diff | max abs diff | cells with ase_hours differing | ASE class differs (cells) | sun_mean rel. RMS diff | per-cell rel. RMS | area-weighted sun_mean lux (first / second) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, c in rows:
        print("| %s | %.2f | %.2f | %.2f | %+.2f | %.0f | %d | %d | %.2f %% | %.2f %% | %.1f / %.1f |" % (
            name, c["ase_pct"], c["ase_pct_reference"], c["ase_hours_rms_diff"], c["ase_hours_mean_diff"],
            c["ase_hours_max_abs_diff"], c["ase_hours_cells_differing"], c["ase_class_differs"],
            100 * c["sun_mean_rel_rms_diff"], 100 * c["sun_mean_rel_rms_per_cell"], c["sun_mean_area_weighted"],
            c["sun_mean_area_weighted_reference"]))
    print("\nRadiance (%s): ASE %.2f %%, area-weighted sun_mean %.1f lux, cells with any ASE hour %d of %d; "
          "rcontrib %.1f s wall" % (ref_name, 100.0 * (r_ase > a.ase_hours).mean(), float((area * r_mean).sum() / area.sum()),
                                    int((r_ase > 0).sum()), n, rc_meta[K]["wall_s"]))
    for r in runs:
        print("fenestra %s: JSON ase_pct %.2f %%, %.1f s wall" % (r["label"], r["json"]["ase_pct"], r["wall_s"]))

    report.update({
        "settings": {"subpoints": K, "check_subpoints": check_ks, "extra_sun_points": extra, "dj": a.dj, "spacing": a.spacing, "paths": a.paths, "seed": a.seed, "seeds": a.seeds,
                     "ase_lux": a.ase_lux, "ase_hours": a.ase_hours},
        "points": {"file": os.path.relpath(pts_path, ROOT), "count": n},
        "radiance": {"ase_pct": float(100.0 * (r_ase > a.ase_hours).mean()),
                     "sun_mean_area_weighted": float((area * r_mean).sum() / area.sum())},
        "fenestra": [{"mode": r["mode"], "seed": r["seed"], "sun_points": r["sun_points"], "files": os.path.relpath(r["base"], ROOT) + ".*",
                      "json_ase_pct": r["json"]["ase_pct"], "daylit_hours": r["json"]["daylit_hours"],
                      "direct_sun_samples": r["json"].get("direct_sun_samples"), "wall_s": r["wall_s"]} for r in runs],
        "comparisons": [dict(c, name=name) for name, c in rows],
        "per_cell": {"radiance_ase_hours": r_ase.astype(int).tolist(), "radiance_sun_mean_lux": r_mean.round(3).tolist(),
                     **{"fenestra_%s_ase_hours" % os.path.basename(r["base"]): r["csv"]["ase_hours"].astype(int).tolist() for r in runs},
                     **{"fenestra_%s_sun_mean_lux" % os.path.basename(r["base"]): r["csv"]["sun_mean_lux"].tolist() for r in runs}},
        "seconds": time.time() - t_start})
    write_report(out_json, report, t_start)
    return 0


def radiance_env(radiance):
    """Radiance's bin folder (annual_reference.find_radiance) and an environment that finds it:
    PATH, RAYPATH with its lib/, and fenestra's PoCL kernel cache."""
    rbin, rlib = ar.find_radiance(radiance)
    env = dict(os.environ, PATH=rbin + os.pathsep + os.environ.get("PATH", ""))
    env["RAYPATH"] = os.pathsep.join(["."] + ([rlib] if rlib else []) + ([os.environ["RAYPATH"]] if "RAYPATH" in os.environ else []))
    env.setdefault("POCL_CACHE_DIR", os.path.join(ROOT, "build", "pocl-cache"))
    return rbin, env


def write_report(out_json, report, t_start):
    """The report as indented JSON, and a line saying where and how long it all took."""
    with open(out_json, "w") as f:
        json.dump(report, f, indent=1)
        f.write("\n")
    print("\nwrote %s (%.0f s in all)" % (os.path.relpath(out_json, ROOT), time.time() - t_start))


if __name__ == "__main__":
    sys.exit(main())
