#!/usr/bin/env python3
"""five_phase_speed.py — time at equal accuracy of each cell's yearly mean illuminance: fenestra's
five-phase annual study (`--annual-sun exact`, its default) against Radiance's five-phase method, on
the open-window room, the shipped weather file and 1,280 points (0.125 m cells). Radiance is a
checking tool only: nothing in the build or the tests uses it or this script.

    /opt/radenv/bin/python scripts/radiance/five_phase_speed.py [--pair N] [--seeds S1,S2] \
        [--fenestra-time 30] [--ds-subpoints 8] [--ds-alt-subpoints 4] [--reuse] [--reuse-fenestra] \
        [--work out/annual] [--json OUT]

The measurement (each pair about 6-7 minutes on 2 cores; run nothing else meanwhile, the times are
the point; the script does not lower its priority), two independent pairs, then both together:

    export POCL_CACHE_DIR=build/pocl-cache
    /opt/radenv/bin/python scripts/radiance/five_phase_speed.py --json out/annual/five_phase_speed.json
    /opt/radenv/bin/python scripts/radiance/five_phase_speed.py --pair 2 --json out/annual/five_phase_speed_p2.json
    /opt/radenv/bin/python scripts/radiance/five_phase_speed.py --combine out/annual/five_phase_speed.json \
        out/annual/five_phase_speed_p2.json --json out/annual/five_phase_speed_combined.json

(--pair N: Radiance's matrices r(2N-1), r(2N), fenestra's seeds 2N-1, 2N, DS timed again into
dsun_kK_dj0_pN.mtx; --combine: each method's noise from all its runs, the times their means. Adding
--reuse --reuse-fenestra to a pair's command recomputes its analysis from the files, with the times
recorded then; only the skies are made and timed again.) It needs direct_sun_reference.py's files in WORK/direct_sun/ (its octree of
suns, its 8 x 8 sub-points and its gendaylit hours): run that first
(`/opt/radenv/bin/python scripts/radiance/direct_sun_reference.py`). Needs what annual_reference.py
needs (its build_models, run, read_matrix, radiance_points, find_radiance are used here, and
direct_sun_reference.py's solar_hours, read_epw, read_float_matrix, cached_run): Radiance
(pyradiance in /opt/radenv), numpy, a built fenestra (build/fenestra). Every command is printed.

The commands (WORK = out/annual; F = five_phase/):

    python3 scripts/radiance/gltf_to_rad.py docs/results/radiance/room_open.gltf --open-windows \
        --out WORK/scene_open.rad                 # + model.rad (unit sky glow), model_black.rad
    (cd WORK) oconv model.rad > model.oct; oconv model_black.rad > black.oct
    python3 scripts/radiance/workplane_points.py docs/results/radiance/room_open.gltf \
        --out WORK/points_0.125.pts --floor floor --height 0.8 --spacing 0.125
    # DC_all, twice (runs r1, r2; -u+: random numbers seeded from the clock, runs started in
    # different seconds are independent), at the cell centres:
    (cd WORK) rcontrib -I+ -ab 16 -ad 4096 -lw 2e-05 -lr 0 -u+ -n 2 -e MF:1 -f reinhart.cal -b rbin \
        -bn Nrbins -m skyglow model.oct < points_0.125_radiance.txt > dc_ab16_ad4096_lw2e-05_u_rK.mtx
    # DC_direct, twice, on the black model, 4 x 4 sub-points a cell (averaged here):
    (cd WORK) rcontrib -I+ -ab 1 -ad 4096 -lw 4.88281e-05 -lr 0 -u+ -n 2 -e MF:1 -f reinhart.cal \
        -b rbin -bn Nrbins -m skyglow black.oct < points_0.125_radiance_sub4.txt \
        > dc_direct_ad4096_u_rK_sub4.mtx
    # DS: one sun per occupied hour with sun (gendaylit -y, direct_sun_reference.py's), 8 x 8
    # sub-points a cell (deterministic: -dj 0), run again here to time it:
    (cd WORK/direct_sun) rcontrib -I+ -ab 0 -dj 0 -ds 0 -dt 0 -dc 1 -lr 0 -n 2 -faf -c 64 \
        -M suns.mod dsun.oct < points_0.125_k8.txt > ../five_phase/dsun_k8_dj0.mtx
    # (and the same with -c 16 on points_0.125_k4.txt: the 4 x 4 variant, for comparison)
    # skies: epw2wea EPW F/weather.wea; (cd F) gendaymtx -m 1 weather.wea > sky_mf1.mtx;
    # gendaymtx -m 1 -d weather.wea > sun_mf1.mtx; gendaylit ... once per occupied hour with sun
    # (all of them in F/gendaylit.sh)
    # fenestra, S = 1, 2, one at a time:
    POCL_CACHE_DIR=build/pocl-cache build/fenestra render docs/results/radiance/room_open.gltf \
        --out out/annual/five_phase/f_t30_sS --annual scenes/weather/tmy_45.000_8.000_2005_2016.epw \
        --sensor-points out/annual/points_0.125.pts --sensor-size 0.125 --time 30 --seed S --no-progress

Per cell, the yearly mean (the mean over the occupied hours 8-18, 3,650, dark hours 0):
- Radiance five-phase, run K: 179 w . [DC_all_K x mean(sky) - DC_direct_K x mean(sun-only sky)]
  + sum over the hours of DS x (the hour's direct normal lux) / 3,650, with the skies of
  annual_reference.py (gendaymtx's columns at the occupied hours, the sun-only sky's ground set to
  0, w = (0.265, 0.670, 0.065)); two-phase: the first term alone.
- fenestra: the mean_lux column of its OUT.annual.csv (its own Perez patch skies, exact sun).
The noise of one run: RMS over cells of (m1 - m2) / RMS(m) / sqrt 2 (m: the pair's mean). fenestra's
noise falls as 1/sqrt(render time), so it reaches Radiance's noise in render x (sigma_F/sigma_R)^2
seconds; its fixed rest (process wall - render: kernel build, calibration, skies, the direct-sun
pass, output) added unscaled. Radiance's time: one DC_all + one DC_direct (means over the pairs) +
DS + the skies (epw2wea, both gendaymtx, the gendaylit calls). CPU: user + system of the children;
fenestra's rendering CPU is estimated as its process CPU x render / wall. Also: the part of
fenestra's noise from its direct-sun pass (jittered sun points, fixed cost: the sun_mean_lux
column's spread), which does not fall with --time, and the time at equal accuracy with it kept
fixed. Everything to --json (default WORK/five_phase_speed.json).

Agreement (step 7): fenestra's pooled yearly means against Radiance's pooled five-phase ones, per
cell (RMS of f/r - 1, mean of f/r, RMS(f - r)/RMS(r)) and area means, also split into the sun
(fenestra's sun_mean_lux against DS) and the rest, and by quarter of the cells along z (glTF; the
window at large z). DC_all is sampled at the cell centres (as annual_reference.py's) and DC_direct
over the cell, so the patch sun's direct light does not cancel cell by cell; the same sum with
DC_direct taken at its sub-points nearest the centre shows how much of the per-cell difference that
is.

--reuse takes Radiance matrices already in WORK (same command; the timings recorded beside them);
--reuse-fenestra the fenestra runs (same command, same binary).

Measured (2 cores, Intel Xeon, PoCL; 2 pairs): Radiance one five-phase run 175.8 s wall / 329.7 s
CPU (DC_all 86.1, DC_direct 41.6, DS 8x8 41.7, skies 6.3 s wall), yearly-mean noise 0.83 %
(two-phase 0.84 %); fenestra --time 30: 35.2 s wall / 67.0 s CPU (render 28.2 s), noise 0.58 %;
Radiance five-phase / fenestra at equal accuracy 8.4x wall, 8.3x CPU (fixed costs unscaled; two-phase
DC_all alone: 4.2x, 4.3x).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import annual_reference as ar  # noqa: E402
import direct_sun_reference as dsr  # noqa: E402
import workplane_points  # noqa: E402

ROOT = ar.ROOT
W_RAD = ar.W_RAD
EFFICACY = ar.EFFICACY


def loadavg():
    return "load %.2f %.2f %.2f" % os.getloadavg()


def steal_s():
    """CPU time stolen from this virtual machine so far (all CPUs, s; /proc/stat), 0 where unknown."""
    try:
        f = open("/proc/stat").readline().split()
        return int(f[8]) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return 0.0


def pair_noise(x1, x2):
    """One run's relative noise from two independent runs: RMS(x1 - x2) / RMS(pooled) / sqrt 2."""
    pooled = 0.5 * (x1 + x2)
    rms = float(np.sqrt(np.mean(pooled ** 2)))
    return float(np.sqrt(np.mean((x1 - x2) ** 2)) / rms / math.sqrt(2.0)), rms


def equal_accuracy(sig_f, sig_r, rad_wall, rad_cpu, f_render, f_wall, f_cpu, sig_sun=None):
    """fenestra's time at Radiance's noise sig_r: render x (sig_f / sig_r)^2 (+ its fixed rest, process
    wall - render, for 'total'); CPU: its process CPU split in the same proportion. With sig_sun, the
    part of fenestra's noise that does not fall with --time (its direct-sun pass) is held fixed."""
    if sig_sun is not None:
        if sig_r <= sig_sun:
            return None
        k = (sig_f ** 2 - sig_sun ** 2) / (sig_r ** 2 - sig_sun ** 2)
    else:
        k = (sig_f / sig_r) ** 2
    f_cpu_render = f_cpu * f_render / f_wall
    fw = {"render": f_render * k, "total": f_wall - f_render + f_render * k}
    fc = {"render": f_cpu_render * k, "total": f_cpu - f_cpu_render + f_cpu_render * k}
    return {"time_factor": k, "fenestra_wall_s": fw, "fenestra_cpu_s": fc,
            "radiance_wall_s": rad_wall, "radiance_cpu_s": rad_cpu,
            "ratio_wall": {q: rad_wall / v for q, v in fw.items()}, "ratio_cpu": {q: rad_cpu / v for q, v in fc.items()}}


def print_ratios(eq):
    print("| against | Radiance wall / CPU s | (sigma_F/sigma_R)^2 | fenestra wall s (render; total) | wall ratio: render | total | CPU ratio: render | total |")
    print("|---|---|---:|---|---:|---:|---:|---:|")
    for name, e in eq.items():
        if e is None:
            print("| %s | - | (Radiance's noise below fenestra's sun-pass noise) | | | | | |" % name)
            continue
        print("| %s | %.1f / %.1f | %.4f | %.1f; %.1f | %.2f | %.2f | %.2f | %.2f |" % (
            name, e["radiance_wall_s"], e["radiance_cpu_s"], e["time_factor"], e["fenestra_wall_s"]["render"],
            e["fenestra_wall_s"]["total"], e["ratio_wall"]["render"], e["ratio_wall"]["total"],
            e["ratio_cpu"]["render"], e["ratio_cpu"]["total"]))


def multi_noise(runs):
    """One run's relative noise from R >= 2 independent runs: sqrt(mean over cells of the variance
    across runs, ddof 1) / RMS(pooled); with two runs the same as pair_noise."""
    X = np.array(runs)
    return float(np.sqrt(X.var(axis=0, ddof=1).mean()) / np.sqrt(np.mean(X.mean(axis=0) ** 2)))


def combine(paths, out_json):
    """--combine: the pairs' JSONs (runs with distinct matrices and seeds) taken together: each
    method's noise from all its runs, the times their means, the ratios again."""
    js = [json.load(open(p)) for p in paths]
    runs = sorted({r for j in js for r in j["settings"]["radiance_runs"]})
    seeds = sorted({sd for j in js for sd in j["settings"]["seeds"]})
    if len(runs) != 2 * len(js) or len(seeds) != 2 * len(js):
        sys.exit("--combine: the files share Radiance runs or fenestra seeds (%s, %s)" % (runs, seeds))
    K = js[0]["settings"]["ds_subpoints"]
    m5 = [np.array(j["per_cell"]["radiance_5ph_r%d" % i]) for j in js for i in (1, 2)]
    m2 = [np.array(j["per_cell"]["radiance_2ph_r%d" % i]) for j in js for i in (1, 2)]
    fm = [np.array(v) for j in js for v in j["per_cell"]["fenestra_mean_lux"]]
    fs = [np.array(v) for j in js for v in j["per_cell"]["fenestra_sun_mean_lux"]]
    rms_f = float(np.sqrt(np.mean(np.mean(fm, axis=0) ** 2)))
    sig = {"radiance_5ph": multi_noise(m5), "radiance_2ph": multi_noise(m2), "fenestra": multi_noise(fm),
           "fenestra_sun_pass": float(np.sqrt(np.array(fs).var(axis=0, ddof=1).mean()) / rms_f)}
    mean = lambda xs: float(np.mean(xs))  # noqa: E731
    t = {"dc_all": [(m["wall_s"], m["cpu_s"]) for j in js for m in j["radiance"]["dc_all_runs"]],
         "dc_direct": [(m["wall_s"], m["cpu_s"]) for j in js for m in j["radiance"]["dc_direct_runs"]],
         "ds_k%d" % K: [(j["radiance"]["ds"][str(K)]["wall_s"], j["radiance"]["ds"][str(K)]["cpu_s"]) for j in js],
         "skies": [(sum(v["wall_s"] for v in j["radiance"]["skies_s"].values()),
                    sum(v["cpu_s"] for v in j["radiance"]["skies_s"].values())) for j in js]}
    tm = {k: (mean([w for w, _ in v]), mean([c for _, c in v])) for k, v in t.items()}
    rad5 = (sum(v[0] for v in tm.values()), sum(v[1] for v in tm.values()))
    fr = [r for j in js for r in j["fenestra"]["runs"]]
    f_render, f_wall, f_cpu = mean([r["seconds"]["render"] for r in fr]), mean([r["wall_s"] for r in fr]), mean([r["cpu_s"] for r in fr])
    eq = {"five_phase": equal_accuracy(sig["fenestra"], sig["radiance_5ph"], rad5[0], rad5[1], f_render, f_wall, f_cpu),
          "five_phase_sun_noise_fixed": equal_accuracy(sig["fenestra"], sig["radiance_5ph"], rad5[0], rad5[1], f_render,
                                                       f_wall, f_cpu, sig["fenestra_sun_pass"]),
          "two_phase_dc_all_only": equal_accuracy(sig["fenestra"], sig["radiance_2ph"], tm["dc_all"][0], tm["dc_all"][1],
                                                  f_render, f_wall, f_cpu)}
    ar.step("Combined: %s (Radiance runs %s, fenestra seeds %s)" % (", ".join(os.path.relpath(p, ROOT) for p in paths), runs, seeds))
    print("| step | each run: wall / CPU s | mean |")
    print("|---|---|---|")
    for k, v in t.items():
        print("| Radiance %s | %s | %.1f / %.1f |" % (k, ", ".join("%.1f / %.1f" % x for x in v), tm[k][0], tm[k][1]))
    print("| Radiance five-phase, one run | | %.1f / %.1f |" % rad5)
    print("| fenestra process (render) | %s | %.1f / %.1f (%.1f) |" % (
        ", ".join("%.1f / %.1f (%.1f)" % (r["wall_s"], r["cpu_s"], r["seconds"]["render"]) for r in fr), f_wall, f_cpu, f_render))
    print("\nNoise of one run's yearly means, from all %d runs of each: Radiance five-phase %.3f %%, two-phase %.3f %%; "
          "fenestra %.3f %% (its sun pass %.3f %%)" % (len(m5), 100 * sig["radiance_5ph"], 100 * sig["radiance_2ph"],
                                                     100 * sig["fenestra"], 100 * sig["fenestra_sun_pass"]))
    print()
    print_ratios(eq)
    with open(out_json, "w") as f:
        json.dump({"inputs": [os.path.relpath(p, ROOT) for p in paths], "radiance_runs": runs, "fenestra_seeds": seeds,
                   "noise_single_run_rel": sig, "times": t, "mean_times": tm, "radiance_five_phase_s": rad5,
                   "fenestra": {"render_s": f_render, "wall_s": f_wall, "cpu_s": f_cpu}, "equal_accuracy": eq}, f, indent=1)
        f.write("\n")
    print("\nwrote %s" % os.path.relpath(out_json, ROOT))
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=os.path.join(ROOT, "docs", "results", "radiance", "room_open.gltf"))
    ap.add_argument("--floor", default="floor")
    ap.add_argument("--height", type=float, default=0.8)
    ap.add_argument("--spacing", type=float, default=0.125)
    ap.add_argument("--epw", default=os.path.join(ROOT, "scenes", "weather", "tmy_45.000_8.000_2005_2016.epw"))
    ap.add_argument("--mf", type=int, default=1)
    ap.add_argument("--occupied", default="8-18")
    ap.add_argument("--ab", type=int, default=16)
    ap.add_argument("--ad", type=int, default=4096)
    ap.add_argument("--lw", type=float, default=2e-5)
    ap.add_argument("--direct-ad", type=int, default=4096)
    ap.add_argument("--direct-subpoints", type=int, default=4)
    ap.add_argument("--ds-subpoints", type=int, default=8, help="DS: K x K sub-points a cell (8; its points file from direct_sun_reference.py)")
    ap.add_argument("--ds-alt-subpoints", default="4", help="DS also timed with these K (comma list; '' none): a variant")
    ap.add_argument("--processes", type=int, default=2)
    ap.add_argument("--fenestra", default=os.path.join(ROOT, "build", "fenestra"))
    ap.add_argument("--fenestra-time", type=float, default=30.0)
    ap.add_argument("--pair", type=int, default=1,
                    help="which pair of runs: Radiance's matrices r(2N-1), r(2N), DS timed into dsun_kK_dj0[_pN].mtx, "
                         "fenestra's seeds 2N-1, 2N (unless --seeds): a second pair repeats the whole measurement")
    ap.add_argument("--seeds", help="fenestra's two seeds (default 2N-1,2N for --pair N)")
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "annual"))
    ap.add_argument("--json")
    ap.add_argument("--radiance", metavar="DIR")
    ap.add_argument("--reuse", action="store_true", help="reuse Radiance matrices already in WORK")
    ap.add_argument("--reuse-fenestra", action="store_true", help="reuse fenestra runs already in WORK/five_phase")
    ap.add_argument("--combine", nargs="+", metavar="JSON",
                    help="only combine these pairs' --json files (noise from all runs, mean times) into --json")
    a = ap.parse_args()
    if a.combine:
        return combine(a.combine, a.json or os.path.join(os.path.abspath(a.work), "five_phase_speed_combined.json"))
    seeds = [int(t) for t in (a.seeds or "%d,%d" % (2 * a.pair - 1, 2 * a.pair)).split(",")]
    if len(seeds) != 2:
        sys.exit("--seeds: give two")
    ridx = (2 * a.pair - 1, 2 * a.pair)
    t_start = time.time()
    occ_from, occ_to = (int(v) for v in a.occupied.split("-"))
    work = os.path.abspath(a.work)
    fp = os.path.join(work, "five_phase")
    dsd = os.path.join(work, "direct_sun")
    os.makedirs(fp, exist_ok=True)
    out_json = a.json or os.path.join(work, "five_phase_speed.json")
    rbin, env = dsr.radiance_env(a.radiance)
    print("Radiance: %s (RAYPATH=%s); POCL_CACHE_DIR=%s; %d CPUs; %s" % (
        rbin, env["RAYPATH"], env["POCL_CACHE_DIR"], os.cpu_count(), loadavg()))
    version = subprocess.run(["rcontrib", "-version"], capture_output=True, text=True, env=env).stdout.strip()
    report = {"scene": os.path.relpath(a.scene, ROOT), "epw": os.path.relpath(a.epw, ROOT), "occupied": a.occupied,
              "radiance_version": version, "machine_nproc": os.cpu_count(), "commands": []}

    # 1. ---------------------------------------------------------------------------------------
    ar.step("1. Radiance models and points")
    ar.build_models(a.scene, work, env)
    pts_path = os.path.join(work, "points_%g.pts" % a.spacing)
    ar.run([sys.executable, os.path.join(HERE, "workplane_points.py"), a.scene, "--out", pts_path,
            "--floor", a.floor, "--height", "%g" % a.height, "--spacing", "%g" % a.spacing], env=env)
    points = workplane_points.read_points(pts_path)
    n = len(points)
    rad_pts = {}
    for k in sorted({1, a.direct_subpoints}):
        rad_pts[k] = os.path.join(work, "points_%g_radiance%s.txt" % (a.spacing, "" if k == 1 else "_sub%d" % k))
        with open(rad_pts[k], "w") as f:
            f.write(ar.radiance_points(points, a.spacing, k))
        print("%d points x %d sub-points in %s" % (n, k * k, os.path.relpath(rad_pts[k], ROOT)))

    # 2. ---------------------------------------------------------------------------------------
    ar.step("2. Radiance: DC_all and DC_direct, two independent runs each (-u+)")
    contrib = ["-e", "MF:%d" % a.mf, "-f", "reinhart.cal", "-b", "rbin", "-bn", "Nrbins", "-m", "skyglow"]
    last_start = [0.0]

    def rcontrib(tag, oct_name, opts, k):
        """annual_reference.py's rcontrib step (same file names and meta, so its --reuse takes them)."""
        out = os.path.join(work, "dc_%s%s.mtx" % (tag, "" if k == 1 else "_sub%d" % k))
        meta = out + ".json"
        cmd = ["rcontrib", "-I+"] + opts + ["-n", str(a.processes)] + contrib + [oct_name]
        report["commands"].append("(cd %s) %s < %s > %s" % (os.path.relpath(work, ROOT), " ".join(cmd),
                                                            os.path.basename(rad_pts[k]), os.path.basename(out)))
        if a.reuse and os.path.exists(out) and os.path.exists(meta):
            m = json.load(open(meta))
            if m.get("cmd") == cmd and m.get("points") == n and m.get("subpoints") == k * k:
                print("$ (reused) %s  [%.1f s wall, %.1f s CPU then]" % (" ".join(cmd), m["wall_s"], m["cpu_s"]))
                return out, m
        # -u+ seeds from the clock in seconds: never start two runs within the same second
        wait = last_start[0] + 1.5 - time.time()
        if wait > 0:
            time.sleep(wait)
        last_start[0] = time.time()
        la = loadavg()
        print("   (%s)" % la)
        st0 = steal_s()
        wall, cpu, _ = ar.run(cmd, cwd=work, stdin=rad_pts[k], stdout=out, env=env)
        m = {"cmd": cmd, "points": n, "subpoints": k * k, "wall_s": wall, "cpu_s": cpu, "start": last_start[0],
             "loadavg_at_start": la, "steal_s": steal_s() - st0}
        print("   (CPU time stolen from the VM meanwhile: %.1f s)" % m["steal_s"])
        json.dump(m, open(meta, "w"))
        return out, m

    def sub_values(path, k):
        """The matrix per cell and sub-point: (points, k*k, patches, 3)."""
        m = ar.read_matrix(path)[1]
        if m.shape[0] != n * k * k:
            sys.exit("%s: %d rows for %d points x %d sub-points" % (path, m.shape[0], n, k * k))
        return m.reshape(n, k * k, m.shape[1], m.shape[2])

    all_opts = ["-ab", str(a.ab), "-ad", str(a.ad), "-lw", "%g" % a.lw, "-lr", "0", "-u+"]
    all_tag = "ab%d_ad%d_lw%g_u" % (a.ab, a.ad, a.lw)
    dir_opts = ["-ab", "1", "-ad", str(a.direct_ad), "-lw", "%g" % (0.2 / a.direct_ad), "-lr", "0", "-u+"]
    dir_tag = "direct_ad%d_u" % a.direct_ad
    runs_all, runs_dir = [], []
    for r in ridx:        # interleaved: a slow spell of the machine falls on both kinds
        runs_all.append(rcontrib(all_tag + "_r%d" % r, "model.oct", all_opts, 1))
        runs_dir.append(rcontrib(dir_tag + "_r%d" % r, "black.oct", dir_opts, a.direct_subpoints))
    D = [sub_values(p, 1)[:, 0] for p, _ in runs_all]
    DD, DDc = [], []
    kd = a.direct_subpoints
    inner = [i * kd + j for i in range(kd) for j in range(kd)       # the sub-points nearest the centre
             if abs(i - (kd - 1) / 2.0) <= 0.5 and abs(j - (kd - 1) / 2.0) <= 0.5]
    for p, _ in runs_dir:
        v = sub_values(p, kd)
        DD.append(v.mean(axis=1))
        DDc.append(v[:, inner].mean(axis=1))
        del v
    if np.array_equal(D[0], D[1]) or np.array_equal(DD[0], DD[1]):
        sys.exit("two rcontrib runs gave identical matrices: their sampling is not independent")
    P = D[0].shape[1]

    # 3. ---------------------------------------------------------------------------------------
    ar.step("3. Skies: epw2wea, gendaymtx (sky with the sun in patches; the sun alone), gendaylit (one sun an hour)")
    sky_t = {}
    wea = os.path.join(fp, "weather.wea")
    sky_t["epw2wea"] = ar.run(["epw2wea", a.epw, wea], env=env)[:2]
    sky_path, sun_path = os.path.join(fp, "sky_mf%d.mtx" % a.mf), os.path.join(fp, "sun_mf%d.mtx" % a.mf)
    sky_t["gendaymtx"] = ar.run(["gendaymtx", "-m", str(a.mf), "weather.wea"], cwd=fp, stdout=sky_path, env=env)[:2]
    sky_t["gendaymtx_d"] = ar.run(["gendaymtx", "-m", str(a.mf), "-d", "weather.wea"], cwd=fp, stdout=sun_path, env=env)[:2]
    _, Srgb = ar.read_matrix(sky_path)
    _, Sun = ar.read_matrix(sun_path)
    recs = []
    for line in open(wea):
        v = line.split()
        if len(v) == 5 and not line[0].isalpha():
            recs.append((int(v[0]), int(v[1]), float(v[2])))
    if Srgb.shape[:2] != (P, len(recs)) or Sun.shape[:2] != (P, len(recs)):
        sys.exit("gendaymtx: unexpected shape %s / %s" % (Srgb.shape, Sun.shape))
    occ = np.array([h + 0.5 - 1 >= occ_from and h + 0.5 <= occ_to for _, _, h in recs])
    n_occ = int(occ.sum())
    if Sun[0].max() > 0:
        Sun[0] = 0.0
    sky_mean = Srgb[:, occ, :].mean(axis=1)     # patches x 3: mean over the occupied hours (dark: 0)
    sun_mean = Sun[:, occ, :].mean(axis=1)
    sun_cols = int((Sun[:, occ, :].sum(axis=(0, 2)) > 0).sum())
    site, erecs = dsr.read_epw(a.epw)

    def occ_rec(r):
        return r["hour"] - 1 >= occ_from and r["hour"] <= occ_to
    t0, c0 = time.time(), ar.children_cpu()
    hours, gl_cmds = dsr.solar_hours(erecs, site, occ_rec, env, os.path.join(fp, "hours.json"), False)
    sky_t["gendaylit"] = (time.time() - t0, ar.children_cpu() - c0)
    suns = [h for h in hours if h["sun"] is not None and h["sun"][2] > 0]
    ref_hours = json.load(open(os.path.join(dsd, "hours.json")))["hours"]
    ref_suns = [h for h in ref_hours if h["sun"] is not None and h["sun"][2] > 0]
    if [(h["sun"], h["lux"]) for h in suns] != [(h["sun"], h["lux"]) for h in ref_suns]:
        sys.exit("gendaylit's suns differ from %s's: run direct_sun_reference.py again" % os.path.relpath(dsd, ROOT))
    lux_g = np.array([h["lux"] for h in suns])
    print("%d wea records, %d occupied hours; gendaymtx -d: %d occupied hours with a sun; gendaylit: %d suns (the same "
          "as direct_sun/hours.json's)" % (len(recs), n_occ, sun_cols, len(suns)))
    print("sky generation: " + ", ".join("%s %.1f s wall / %.1f s CPU" % (k, w, c) for k, (w, c) in sky_t.items()))

    # 4. ---------------------------------------------------------------------------------------
    ar.step("4. DS: Radiance's direct sun (direct_sun_reference.py's rcontrib, run again to time it)")
    octree, sun_mod = os.path.join(dsd, "dsun.oct"), os.path.join(dsd, "suns.mod")
    mods = [l.strip() for l in open(sun_mod) if l.strip()]
    if len(mods) != len(suns):
        sys.exit("%s has %d suns, gendaylit %d" % (sun_mod, len(mods), len(suns)))
    ds = {}
    for k in [a.ds_subpoints] + [int(t) for t in a.ds_alt_subpoints.split(",") if t.strip() and int(t) != a.ds_subpoints]:
        pts_k = os.path.join(dsd, "points_%g_k%d.txt" % (a.spacing, k))
        if not os.path.exists(pts_k) or not os.path.exists(octree):
            sys.exit("%s or %s missing: run direct_sun_reference.py first" % (pts_k, octree))
        out = os.path.join(fp, "dsun_k%d_dj0%s.mtx" % (k, "" if a.pair == 1 else "_p%d" % a.pair))
        cmd = ["rcontrib", "-I+", "-ab", "0", "-dj", "0", "-ds", "0", "-dt", "0", "-dc", "1", "-lr", "0",
               "-n", str(a.processes), "-faf", "-c", str(k * k), "-M", "suns.mod", "dsun.oct"]
        print("   (%s)" % loadavg())
        st0 = steal_s()
        m = dsr.cached_run(cmd, dsd, pts_k, out, env, a.reuse, inputs=(pts_k, octree, sun_mod))
        print("   (CPU time stolen from the VM meanwhile: %.1f s)" % (steal_s() - st0))
        report["commands"].append("(cd %s) %s < %s > %s" % (os.path.relpath(dsd, ROOT), " ".join(cmd),
                                                            os.path.basename(pts_k), os.path.relpath(out, dsd)))
        M = dsr.read_float_matrix(out)
        if M.shape != (n + 1, len(suns), 3):
            sys.exit("%s: %s, expected %d x %d x 3" % (out, M.shape, n + 1, len(suns)))
        old = os.path.join(dsd, "dsun_k%d_dj0.mtx" % k)
        same = os.path.exists(old) and np.array_equal(dsr.read_float_matrix(old), M)
        G = M.mean(axis=2)[:n] / dsr.OMEGA_SUN          # visibility x cos(incidence), per cell and sun
        ds[k] = {"wall_s": m["wall_s"], "cpu_s": m["cpu_s"], "same_as_direct_sun": bool(same),
                 "mean": (G * lux_g[None, :]).sum(axis=1) / n_occ}
        print("   K = %d: %.1f s wall / %.1f s CPU; the same matrix as %s: %s" % (
            k, m["wall_s"], m["cpu_s"], os.path.relpath(old, ROOT), same))
    K = a.ds_subpoints
    ref_json = os.path.join(work, "direct_sun_reference.json")
    if os.path.exists(ref_json):
        rj = json.load(open(ref_json))
        if rj.get("settings", {}).get("subpoints") == K:
            rm = np.array(rj["per_cell"]["radiance_sun_mean_lux"])
            print("   DS yearly mean against %s's: max abs difference %.3g lux (its values rounded to 0.001)" % (
                os.path.relpath(ref_json, ROOT), float(np.abs(rm - ds[K]["mean"]).max())))

    # 5. ---------------------------------------------------------------------------------------
    ar.step("5. fenestra, --time %g, seeds %s (one at a time)" % (a.fenestra_time, ",".join(map(str, seeds))))
    fruns = []
    st = os.stat(a.fenestra)
    binary = {"size": st.st_size, "mtime": st.st_mtime}
    for seed in seeds:
        base = os.path.join(fp, "f_t%g_s%d" % (a.fenestra_time, seed))
        cmd = [a.fenestra, "render", a.scene, "--out", base, "--annual", a.epw, "--sensor-points", pts_path,
               "--sensor-size", "%g" % a.spacing, "--time", "%g" % a.fenestra_time, "--seed", str(seed), "--no-progress"]
        cmd = [os.path.relpath(c, ROOT) if os.path.isabs(c) else c for c in cmd]
        report["commands"].append("POCL_CACHE_DIR=%s %s" % (os.path.relpath(env["POCL_CACHE_DIR"], ROOT), " ".join(cmd)))
        meta = base + ".run.json"
        if (a.reuse_fenestra and os.path.exists(meta) and json.load(open(meta)).get("cmd") == cmd
                and json.load(open(meta)).get("binary") == binary and os.path.exists(base + ".annual.csv")):
            fm = json.load(open(meta))
            print("$ (reused) %s  [%.1f s wall, %.1f s CPU then]" % (" ".join(cmd), fm["wall_s"], fm["cpu_s"]))
        else:
            la = loadavg()
            print("   (%s)" % la)
            st0 = steal_s()
            wall, cpu, err = ar.run(cmd, cwd=ROOT, env=env)
            fm = {"cmd": cmd, "binary": binary, "wall_s": wall, "cpu_s": cpu, "loadavg_at_start": la,
                  "steal_s": steal_s() - st0, "stderr": err.strip().splitlines()[-6:]}
            print("   (CPU time stolen from the VM meanwhile: %.1f s)" % fm["steal_s"])
            json.dump(fm, open(meta, "w"))
        fj = json.load(open(base + ".json"))
        rows = [l.rstrip("\r\n").split(",") for l in open(base + ".annual.csv")]
        cols = {c: i for i, c in enumerate(rows[0])}
        csv = {c: np.array([float(r[cols[c]]) for r in rows[1:]]) for c in
               ("x_m", "y_m", "z_m", "area_m2", "mean_lux", "mean_std_err_lux", "sun_mean_lux")}
        pos = np.array([p[:3] for p in points])
        if len(rows) - 1 != n or np.abs(np.stack([csv["x_m"], csv["y_m"], csv["z_m"]], 1) - pos).max() > 1e-4:
            sys.exit("%s.annual.csv rows do not match the points file" % base)
        ja = fj["annual"]
        if ja["occupied_hours"] != n_occ or ja.get("sun") != "exact":
            sys.exit("fenestra: %s occupied hours (expected %d), sun %s (expected exact)" % (
                ja["occupied_hours"], n_occ, ja.get("sun")))
        sec = fj["seconds"]
        print("   seed %d: %s paths; seconds: total %.2f, render %.2f, kernel_build %.2f, calibration %.2f; annual: "
              "study %.2f, direct_sun %.2f; process %.1f s wall / %.1f s CPU; grid mean %.1f lux" % (
                  seed, fj.get("paths"), sec["total"], sec["render"], sec.get("kernel_build", 0), sec.get("calibration", 0),
                  ja.get("study_seconds", float("nan")), ja.get("direct_sun_seconds", float("nan")), fm["wall_s"],
                  fm["cpu_s"], csv["mean_lux"].mean()))
        fruns.append({"seed": seed, "base": base, "csv": csv, "json": fj, "meta": fm})

    # 6. ---------------------------------------------------------------------------------------
    ar.step("6. Yearly means, noise, time at equal accuracy")

    def proj(Dm, v):
        return EFFICACY * sum(W_RAD[c] * (Dm[:, :, c] @ v[:, c]) for c in range(3))
    m2 = [proj(Dk, sky_mean) for Dk in D]                           # two-phase
    dpatch = [proj(DDk, sun_mean) for DDk in DD]                    # direct light of the patch sun
    m5 = [m2[i] - dpatch[i] + ds[K]["mean"] for i in range(2)]      # five-phase
    fm_ = [r["csv"]["mean_lux"] for r in fruns]
    fs_ = [r["csv"]["sun_mean_lux"] for r in fruns]
    sig = {"radiance_5ph": pair_noise(*m5), "radiance_2ph": pair_noise(*m2), "fenestra": pair_noise(*fm_)}
    # parts of the noise: Radiance's from DC_all (two-phase term) and DC_direct x patch sun; fenestra's sun pass
    part = {"radiance_dc_direct_term": float(np.sqrt(np.mean((dpatch[0] - dpatch[1]) ** 2)) / sig["radiance_5ph"][1] / math.sqrt(2)),
            "radiance_dc_all_term": float(np.sqrt(np.mean((m2[0] - m2[1]) ** 2)) / sig["radiance_5ph"][1] / math.sqrt(2)),
            "fenestra_sun_pass": float(np.sqrt(np.mean((fs_[0] - fs_[1]) ** 2)) / sig["fenestra"][1] / math.sqrt(2))}
    se_rel = float(np.mean([np.sqrt(np.mean((r["csv"]["mean_std_err_lux"] / r["csv"]["mean_lux"]) ** 2)) for r in fruns]))
    pm_rel = float(np.mean([np.sqrt(np.mean(r["csv"]["mean_std_err_lux"] ** 2)) / sig["fenestra"][1] for r in fruns]))

    # times
    sky_wall = sum(w for w, _ in sky_t.values())
    sky_cpu = sum(c for _, c in sky_t.values())
    sky2_wall = sky_t["epw2wea"][0] + sky_t["gendaymtx"][0]
    sky2_cpu = sky_t["epw2wea"][1] + sky_t["gendaymtx"][1]
    r_all = (float(np.mean([m["wall_s"] for _, m in runs_all])), float(np.mean([m["cpu_s"] for _, m in runs_all])))
    r_dir = (float(np.mean([m["wall_s"] for _, m in runs_dir])), float(np.mean([m["cpu_s"] for _, m in runs_dir])))
    rad5 = {"dc_all": r_all, "dc_direct": r_dir, "ds_k%d" % K: (ds[K]["wall_s"], ds[K]["cpu_s"]), "skies": (sky_wall, sky_cpu)}
    rad5_wall, rad5_cpu = sum(v[0] for v in rad5.values()), sum(v[1] for v in rad5.values())
    f_render = float(np.mean([r["json"]["seconds"]["render"] for r in fruns]))
    f_total_json = float(np.mean([r["json"]["seconds"]["total"] for r in fruns]))
    f_wall = float(np.mean([r["meta"]["wall_s"] for r in fruns]))
    f_cpu = float(np.mean([r["meta"]["cpu_s"] for r in fruns]))
    f_cpu_render = f_cpu * f_render / f_wall
    f_sun = float(np.mean([r["json"]["annual"].get("direct_sun_seconds", 0.0) for r in fruns]))
    f_study = float(np.mean([r["json"]["annual"].get("study_seconds", 0.0) for r in fruns]))

    def equal_acc(sig_r, rad_wall, rad_cpu, sun_fixed=False):
        return equal_accuracy(sig["fenestra"][0], sig_r, rad_wall, rad_cpu, f_render, f_wall, f_cpu,
                              part["fenestra_sun_pass"] if sun_fixed else None)
    eq = {"five_phase": equal_acc(sig["radiance_5ph"][0], rad5_wall, rad5_cpu),
          "five_phase_no_skies": equal_acc(sig["radiance_5ph"][0], rad5_wall - sky_wall, rad5_cpu - sky_cpu),
          "five_phase_sun_noise_fixed": equal_acc(sig["radiance_5ph"][0], rad5_wall, rad5_cpu, sun_fixed=True),
          "two_phase_dc_all_only": equal_acc(sig["radiance_2ph"][0], r_all[0], r_all[1]),
          "two_phase_dc_all_plus_skies": equal_acc(sig["radiance_2ph"][0], r_all[0] + sky2_wall, r_all[1] + sky2_cpu)}
    for k in ds:
        if k != K:
            m5k = [m2[i] - dpatch[i] + ds[k]["mean"] for i in range(2)]
            sk = pair_noise(*m5k)[0]
            w = rad5_wall - ds[K]["wall_s"] + ds[k]["wall_s"]
            c = rad5_cpu - ds[K]["cpu_s"] + ds[k]["cpu_s"]
            eq["five_phase_ds_k%d" % k] = equal_acc(sk, w, c)

    print("\nTimes (Radiance: each rcontrib run; fenestra: each process):")
    print("| step | run 1 wall / CPU s | run 2 wall / CPU s |")
    print("|---|---|---|")
    for name, rr in (("Radiance DC_all (rcontrib -ab %d -ad %d -lw %g -u+, cell centres)" % (a.ab, a.ad, a.lw), runs_all),
                     ("Radiance DC_direct (black model, -ab 1 -ad %d -u+, %dx%d points a cell)" % (
                         a.direct_ad, a.direct_subpoints, a.direct_subpoints), runs_dir)):
        print("| %s | %s |" % (name, " | ".join("%.1f / %.1f" % (m["wall_s"], m["cpu_s"]) for _, m in rr)))
    for k in ds:
        print("| Radiance DS (rcontrib -ab 0, %dx%d points a cell, %d suns) | %.1f / %.1f | (deterministic) |" % (
            k, k, len(suns), ds[k]["wall_s"], ds[k]["cpu_s"]))
    print("| Radiance skies (epw2wea, gendaymtx, gendaymtx -d, %d x gendaylit) | %.1f / %.1f | |" % (len(suns), sky_wall, sky_cpu))
    print("| fenestra --time %g, process (render s; JSON total; study; direct-sun pass) | %s |" % (
        a.fenestra_time, " | ".join("%.1f / %.1f (%.1f; %.1f; %.1f; %.1f)" % (
            r["meta"]["wall_s"], r["meta"]["cpu_s"], r["json"]["seconds"]["render"], r["json"]["seconds"]["total"],
            r["json"]["annual"].get("study_seconds", float("nan")), r["json"]["annual"].get("direct_sun_seconds", float("nan")))
            for r in fruns)))
    print("\nYearly mean per cell, noise of one run (RMS(m1 - m2) / RMS(m) / sqrt 2):")
    print("| method | one run: wall / CPU s | noise | grid mean lux, run 1 / run 2 |")
    print("|---|---|---:|---|")
    print("| Radiance five-phase (DC_all + DC_direct + DS %dx%d + skies) | %.1f / %.1f | %.3f %% | %.1f / %.1f |" % (
        K, K, rad5_wall, rad5_cpu, 100 * sig["radiance_5ph"][0], m5[0].mean(), m5[1].mean()))
    print("| Radiance two-phase (DC_all alone; + skies %.1f s) | %.1f / %.1f | %.3f %% | %.1f / %.1f |" % (
        sky2_wall, r_all[0], r_all[1], 100 * sig["radiance_2ph"][0], m2[0].mean(), m2[1].mean()))
    print("| fenestra --time %g (render %.1f s, fixed %.1f s) | %.1f / %.1f | %.3f %% | %.1f / %.1f |" % (
        a.fenestra_time, f_render, f_wall - f_render, f_wall, f_cpu, 100 * sig["fenestra"][0], fm_[0].mean(), fm_[1].mean()))
    print("Parts of the noise (each relative to its method's RMS yearly mean): Radiance's DC_all term %.3f %%, "
          "DC_direct x patch-sun term %.3f %%; fenestra's direct-sun pass (sun_mean_lux) %.3f %%" % (
              100 * part["radiance_dc_all_term"], 100 * part["radiance_dc_direct_term"], 100 * part["fenestra_sun_pass"]))
    print("fenestra's self-reported standard error of the yearly mean: RMS over cells of se/mean %.3f %%, RMS(se)/RMS(mean) "
          "%.3f %% (measured %.3f %%)" % (100 * se_rel, 100 * pm_rel, 100 * sig["fenestra"][0]))
    print("\nRadiance time / fenestra's time at Radiance's noise (fenestra: render x (sigma_F/sigma_R)^2; 'total': + its "
          "fixed %.1f s wall unscaled):" % (f_wall - f_render))
    print_ratios(eq)

    # 7. ---------------------------------------------------------------------------------------
    ar.step("7. Agreement of the yearly means (pooled runs)")
    area = fruns[0]["csv"]["area_m2"]
    wgt = area / area.sum()
    R5 = 0.5 * (m5[0] + m5[1])
    R2 = 0.5 * (m2[0] + m2[1])
    F = 0.5 * (fm_[0] + fm_[1])
    FS = 0.5 * (fs_[0] + fs_[1])
    RS = ds[K]["mean"]
    Rpatch = 0.5 * (dpatch[0] + dpatch[1])
    # DC_all is sampled at the cell centres, DC_direct over each cell: the patch sun's direct light
    # then does not cancel cell by cell. The same five-phase sum with DC_direct taken at the sub-points
    # nearest the centre (consistent with DC_all; the centre's direct sun is not the cell's) shows how
    # much of the per-cell difference that is.
    dpatch_c = [proj(v, sun_mean) for v in DDc]
    R5c = 0.5 * (m5[0] - dpatch_c[0] + dpatch[0] + m5[1] - dpatch_c[1] + dpatch[1])

    def cmp(f, r):
        ok = r > 0
        q = f[ok] / r[ok]
        return {"rel_rms_per_cell": float(np.sqrt(np.mean((q - 1) ** 2))), "mean_ratio_per_cell": float(q.mean()),
                "rel_rms_diff": float(np.sqrt(np.mean((f - r) ** 2)) / np.sqrt(np.mean(r ** 2))),
                "area_mean_f": float((wgt * f).sum()), "area_mean_r": float((wgt * r).sum()),
                "area_mean_ratio": float((wgt * f).sum() / (wgt * r).sum())}
    agree = {"fenestra_vs_radiance_5ph": cmp(F, R5),
             "fenestra_sun_vs_radiance_ds": cmp(FS, RS),
             "fenestra_rest_vs_radiance_rest": cmp(F - FS, R5 - RS),
             "fenestra_vs_radiance_5ph_dc_direct_at_centre": cmp(F, R5c),
             "fenestra_rest_vs_radiance_rest_dc_direct_at_centre": cmp(F - FS, R5c - RS),
             "radiance_2ph_vs_5ph": cmp(R2, R5),
             "radiance_patch_sun_direct_vs_ds": cmp(Rpatch, RS)}
    # the noise floor of the pooled difference: each pooled value has half a run's variance
    floor = math.sqrt(0.5 * sig["fenestra"][0] ** 2 + 0.5 * sig["radiance_5ph"][0] ** 2)
    print("| comparison (per cell) | rel. RMS of f/r - 1 | mean f/r | RMS(f - r)/RMS(r) | area mean f / r lux | ratio |")
    print("|---|---:|---:|---:|---|---:|")
    for name, c in agree.items():
        print("| %s | %.2f %% | %.4f | %.2f %% | %.1f / %.1f | %.4f |" % (
            name, 100 * c["rel_rms_per_cell"], c["mean_ratio_per_cell"], 100 * c["rel_rms_diff"],
            c["area_mean_f"], c["area_mean_r"], c["area_mean_ratio"]))
    print("Noise floor of the pooled difference (sqrt((sigma_F^2 + sigma_R5^2) / 2)): %.2f %%" % (100 * floor))
    # where the difference is: by distance from the window (rows of cells along z, glTF frame)
    zc = fruns[0]["csv"]["z_m"]
    bands = np.quantile(zc, [0, 0.25, 0.5, 0.75, 1.0])
    by_band = []
    for i in range(4):
        sel = (zc >= bands[i]) & (zc <= bands[i + 1]) if i == 3 else (zc >= bands[i]) & (zc < bands[i + 1])
        by_band.append({"z_from": float(bands[i]), "z_to": float(bands[i + 1]), "cells": int(sel.sum()),
                        "radiance_ds_mean_lux": float(RS[sel].mean()), "radiance_5ph_mean_lux": float(R5[sel].mean()),
                        "ratio_f_over_r": float(F[sel].sum() / R5[sel].sum()),
                        "sun_ratio": float(FS[sel].sum() / RS[sel].sum()) if RS[sel].sum() > 0 else None,
                        "rest_ratio": float((F - FS)[sel].sum() / (R5 - RS)[sel].sum())})
    print("By quarter of the cells along z (glTF): " + "; ".join(
        "z %.2f-%.2f m (Radiance %.0f lux, sun %.0f): all %.4f, sun %.4f, rest %.4f" % (
            b["z_from"], b["z_to"], b["radiance_5ph_mean_lux"], b["radiance_ds_mean_lux"], b["ratio_f_over_r"],
            b["sun_ratio"] or float("nan"), b["rest_ratio"]) for b in by_band))

    report.update({
        "settings": {"pair": a.pair, "radiance_runs": list(ridx), "ab": a.ab, "ad": a.ad, "lw": a.lw, "direct_ad": a.direct_ad, "direct_subpoints": a.direct_subpoints,
                     "ds_subpoints": K, "processes": a.processes, "fenestra_time_s": a.fenestra_time, "seeds": seeds},
        "points": {"file": os.path.relpath(pts_path, ROOT), "count": n},
        "hours": {"occupied": n_occ, "gendaymtx_sun_hours": sun_cols, "gendaylit_suns": len(suns)},
        "radiance": {"dc_all_runs": [dict(m, file=os.path.relpath(p, ROOT)) for p, m in runs_all],
                     "dc_direct_runs": [dict(m, file=os.path.relpath(p, ROOT)) for p, m in runs_dir],
                     "ds": {str(k): {kk: v for kk, v in d.items() if kk != "mean"} for k, d in ds.items()},
                     "skies_s": {k: {"wall_s": w, "cpu_s": c} for k, (w, c) in sky_t.items()},
                     "five_phase_one_run": {k: {"wall_s": w, "cpu_s": c} for k, (w, c) in rad5.items()},
                     "five_phase_wall_s": rad5_wall, "five_phase_cpu_s": rad5_cpu},
        "fenestra": {"runs": [{"seed": r["seed"], "files": os.path.relpath(r["base"], ROOT) + ".*", "wall_s": r["meta"]["wall_s"],
                               "cpu_s": r["meta"]["cpu_s"], "seconds": r["json"]["seconds"], "paths": r["json"].get("paths"),
                               "study_seconds": r["json"]["annual"].get("study_seconds"),
                               "direct_sun_seconds": r["json"]["annual"].get("direct_sun_seconds"),
                               "loadavg_at_start": r["meta"].get("loadavg_at_start"),
                               "steal_s": r["meta"].get("steal_s")} for r in fruns],
                     "render_s": f_render, "total_json_s": f_total_json, "wall_s": f_wall, "cpu_s": f_cpu,
                     "cpu_render_s_est": f_cpu_render, "fixed_wall_s": f_wall - f_render,
                     "study_s": f_study, "direct_sun_s": f_sun,
                     "self_reported_se_rel_rms": se_rel, "self_reported_se_rms_over_rms_mean": pm_rel},
        "noise": {k: {"single_run_rel": v[0], "rms_lux": v[1]} for k, v in sig.items()},
        "noise_parts": part,
        "equal_accuracy": eq,
        "agreement": agree, "agreement_noise_floor": floor, "agreement_by_z_quarter": by_band,
        "per_cell": {"radiance_5ph_r1": m5[0].round(3).tolist(), "radiance_5ph_r2": m5[1].round(3).tolist(),
                     "radiance_2ph_r1": m2[0].round(3).tolist(), "radiance_2ph_r2": m2[1].round(3).tolist(),
                     "radiance_ds": RS.round(3).tolist(), "radiance_5ph_dc_direct_at_centre_pooled": R5c.round(3).tolist(),
                     "fenestra_mean_lux": [r["csv"]["mean_lux"].tolist() for r in fruns],
                     "fenestra_sun_mean_lux": [r["csv"]["sun_mean_lux"].tolist() for r in fruns]},
        "seconds": time.time() - t_start})
    dsr.write_report(out_json, report, t_start)
    return 0


if __name__ == "__main__":
    sys.exit(main())
