#!/usr/bin/env python3
"""reference.py — computes, with Radiance, the reference illuminance on the work-plane sensor
points of a fenestra scene (its open-window variant), the convergence study behind the chosen
settings, and a typical "consultant" Radiance run (irradiance cache on) timed and scored against
the reference. Results go to docs/results/radiance/ and are described in
docs/results/radiance.md. Radiance is a checking tool only: nothing in the build or the tests
uses it.

    python3 scripts/radiance/reference.py room [--stages prepare,study,converged,consultant,checks]

Needs Radiance on PATH (e.g. `pip install pyradiance`; its binaries are in pyradiance/bin and
RAYPATH must include pyradiance/lib — `--radiance DIR` sets both from the package folder).
Runs at most two rtrace processes at a time, under `nice -n 10`.

Stages (each adds its part to docs/results/radiance/<scene>_radiance.json):
- prepare: <scene>_open.gltf (gltf_to_rad.py --write-gltf), the Radiance scene and octree in
  out/radiance/, and <scene>_workplane.pts (workplane_points.py; glTF frame, y up).
- study: the settings ladder RUNGS on a sparse subsample (every STUDY_STEP-th point); each rung
  is two independent rtrace passes run side by side (one per core), so each rung gives the grid
  mean and RMS per region and the per-point noise (from the passes' difference).
- converged: the final settings (FINAL, per region) on every k-th point of the region (k in
  FINAL; all points where k = 1), two independent passes averaged; <scene>_converged.csv has a
  row per computed point, in the points file's order.
- consultant: `rtrace -I -h -ab 5 -ad 1024 -as 512 -aa 0.1 -ar 256` (irradiance cache, one
  process) on every point; wall and CPU seconds; <scene>_consultant.csv; RMS error and bias on
  the converged points.
- checks: an unobstructed point under the sky alone against the closed form; the luminance
  weighting (Radiance 0.265/0.670/0.065 against fenestra's Rec.709 0.2126/0.7152/0.0722) from
  the reference's own RGB, and a rerun with grey materials; gensky's CIE overcast sky against
  the ISO 15469 type 1 sky that the reference uses.

Illuminance = 179 lm/W x (0.265 R + 0.670 G + 0.065 B) of rtrace -I's irradiance.
Points: the points file is in the glTF frame; rtrace gets them rotated by
gltf_to_rad.to_radiance ((x, y, z) -> (x, -z, y)), normals too.
"""
import argparse
import json
import math
import os
import platform
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gltf_to_rad  # noqa: E402
import workplane_points  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))
RESULTS = os.path.join(ROOT, "docs", "results", "radiance")
WORK = os.path.join(ROOT, "out", "radiance")

# Every reference run: no irradiance cache (-aa 0), no adaptive super-sampling (-as 0: Radiance's
# own source says it introduces bias), Russian roulette below the weight -lw with no upper
# reflection limit (-lr 0), and bounces up to -ab (beyond which Radiance returns -av = 0).
BASE = ["-I", "-h", "-aa", "0", "-as", "0", "-lr", "0"]
CONSULTANT = ["-I", "-h", "-ab", "5", "-ad", "1024", "-as", "512", "-aa", "0.1", "-ar", "256"]

# The convergence ladder: (-ab, -ad, -lw, regions it runs in (None: all)). Russian roulette
# starts once a path's weight (about albedo^k / ad) falls below -lw, so ad x lw sets how many
# bounces are traced in full; the last rung serves the inner room, lit only through a 5 cm gap.
RUNGS = {
    "room": [(4, 1024, 1e-3, None), (8, 4096, 1e-4, None), (16, 4096, 2e-5, None),
             (64, 16384, 1e-5, None)],
    "inner_room": [(4, 1024, 1e-3, None), (8, 4096, 1e-4, None), (16, 4096, 2e-5, None),
                   (64, 16384, 1e-5, None), (64, 65536, 1e-6, ("inner room",))],
}
STUDY_STEP = {"room": 97, "inner_room": 317}
CHECK_RUNG = (16, 4096, 2e-5)  # settings of the model-difference checks (compared at equal settings)

# Regions (glTF frame): name -> predicate on (x, y, z).
REGIONS = {
    "room": [("room", lambda p: True)],
    "inner_room": [("outer room", lambda p: p[2] > 0), ("inner room", lambda p: p[2] < 0)],
}
# Final settings per region: (-ab, -ad, -lw) and the subsample step k (every k-th point of the
# region, in file order).
FINAL = {
    "room": {"room": ((64, 16384, 1e-5), 10)},
    "inner_room": {"outer room": ((64, 16384, 1e-5), 48),
                   "inner room": ((64, 65536, 1e-6), 300)},
}

W_RAD = gltf_to_rad.RADIANCE_WEIGHTS
W_709 = gltf_to_rad.REC709_WEIGHTS


def lux(rgb, w=W_RAD):
    return 179.0 * (w[0] * rgb[0] + w[1] * rgb[1] + w[2] * rgb[2])


def rung_args(ab, ad, lw):
    return BASE + ["-ab", str(ab), "-ad", str(ad), "-lw", "%g" % lw]


def rad_points(points):
    """The points rotated into Radiance's frame, as rtrace input text."""
    lines = []
    for x, y, z, dx, dy, dz in points:
        p, d = gltf_to_rad.to_radiance((x, y, z)), gltf_to_rad.to_radiance((dx, dy, dz))
        lines.append("%.6f %.6f %.6f %.6g %.6g %.6g" % (p + d))
    return "\n".join(lines) + "\n"


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_rtrace(octree, args, point_sets, nice=True):
    """Runs one rtrace per point set, all at once (at most 2), in out/radiance (RAYPATH has '.').
    Returns ([[rgb, ...] per set], wall seconds, CPU seconds of the children)."""
    assert len(point_sets) <= 2
    cmd = (["nice", "-n", "10"] if nice else []) + ["rtrace"] + args + [os.path.basename(octree)]
    cpu0, t0 = children_cpu(), time.time()
    procs = []
    # Two passes over the same points must be independent: rtrace has no seed option and two
    # copies started together draw the same random numbers (the same values came back), so the
    # second set is fed in reverse order (each point meets other random numbers) and started a
    # little later.
    point_sets = [ps if k == 0 else ps[::-1] for k, ps in enumerate(point_sets)]
    for k, pts in enumerate(point_sets):
        if k:
            time.sleep(1.1)
        p = subprocess.Popen(cmd, cwd=os.path.dirname(octree), stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        procs.append(p)
    # feed and collect: communicate() one by one would serialise large outputs; use threads
    import threading
    outs = [None] * len(procs)

    def talk(i):
        outs[i] = procs[i].communicate(rad_points(point_sets[i]))

    th = [threading.Thread(target=talk, args=(i,)) for i in range(len(procs))]
    for t in th:
        t.start()
    for t in th:
        t.join()
    wall, cpu = time.time() - t0, children_cpu() - cpu0
    res = []
    for p, (out, err) in zip(procs, outs):
        if p.returncode != 0:
            sys.exit("rtrace failed (%s): %s" % (" ".join(cmd), err.strip()))
        vals = [tuple(float(v) for v in line.split()[:3]) for line in out.splitlines() if line.strip()]
        res.append(vals)
    for vals, pts in zip(res, point_sets):
        if len(vals) != len(pts):
            sys.exit("rtrace returned %d values for %d points" % (len(vals), len(pts)))
    res = [vals if k == 0 else vals[::-1] for k, vals in enumerate(res)]
    return res, wall, cpu


def stats(values):
    n = len(values)
    mean = sum(values) / n
    rms = math.sqrt(sum(v * v for v in values) / n)
    return mean, rms


def region_indices(scene, points):
    return [(name, [i for i, p in enumerate(points) if pred(p[:3])]) for name, pred in REGIONS[scene]]


def two_pass_summary(a, b, idx):
    """Mean, RMS of values and per-point standard error of the two passes' average."""
    ea = [lux(a[i]) for i in idx]
    eb = [lux(b[i]) for i in idx]
    avg = [(x + y) / 2 for x, y in zip(ea, eb)]
    mean, rms = stats(avg)
    # var(a - b) = 2 s^2 for one pass; the average has s^2 / 2
    s2 = sum((x - y) ** 2 for x, y in zip(ea, eb)) / len(idx) / 2
    se = math.sqrt(s2 / 2)
    return {"points": len(idx), "mean_lux": round(mean, 4), "rms_lux": round(rms, 4),
            "point_std_err_lux": round(se, 4),
            "point_std_err_pct": round(100 * se / mean, 3) if mean > 0 else None,
            "mean_std_err_pct": round(100 * se / math.sqrt(len(idx)) / mean, 4) if mean > 0 else None}


# --------------------------------------------------------------------------------------------


def paths(scene):
    return {"gltf": os.path.join(ROOT, "scenes", scene + ".gltf"),
            "open_gltf": os.path.join(RESULTS, scene + "_open.gltf"),
            "pts": os.path.join(RESULTS, scene + "_workplane.pts"),
            "rad": os.path.join(WORK, scene + "_open.rad"),
            "oct": os.path.join(WORK, scene + "_open.oct"),
            "json": os.path.join(RESULTS, scene + "_radiance.json"),
            "converged": os.path.join(RESULTS, scene + "_converged.csv"),
            "consultant": os.path.join(RESULTS, scene + "_consultant.csv")}


def load_json(p):
    if os.path.exists(p["json"]):
        with open(p["json"]) as f:
            return json.load(f)
    return {}


def save_json(p, data):
    with open(p["json"], "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")


def make_octree(rad, octree):
    with open(octree, "wb") as f:
        subprocess.run(["oconv", os.path.basename(rad)], cwd=os.path.dirname(rad), stdout=f, check=True)


def stage_prepare(scene, p, data):
    os.makedirs(RESULTS, exist_ok=True)
    os.makedirs(WORK, exist_ok=True)
    doc, buffers = gltf_to_rad.load_gltf(p["gltf"])
    info = gltf_to_rad.write_rad(doc, buffers, p["rad"], True, "iso1", 10000.0)
    dropped = gltf_to_rad.write_open_gltf(p["gltf"], doc, p["open_gltf"])
    make_octree(p["rad"], p["oct"])
    pts, winfo = workplane_points.workplane(p["gltf"])
    workplane_points.write_points(p["pts"], pts)
    version = subprocess.run(["rtrace", "-version"], capture_output=True, text=True).stdout.strip()
    try:
        import importlib.metadata as md
        pyrad = md.version("pyradiance")
    except Exception:
        pyrad = None
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "")
    data["scene"] = scene
    data["radiance"] = {"rtrace_version": version, "pyradiance": pyrad}
    data["machine"] = {"nproc": os.cpu_count(), "cpu": cpu, "python": platform.python_version()}
    data["conversion"] = {"open_windows": True, "dropped_nodes": dropped,
                          "radiance_triangles": info["triangles"],
                          "frame": "(x, y, z)_glTF -> (x, -z, y)_Radiance",
                          "sky": "CIE standard general sky type 1 (ISO 15469), 10000 lux diffuse "
                                 "horizontal, upper hemisphere only, no sun",
                          "illuminance": "179 * (0.265 R + 0.670 G + 0.065 B)"}
    data["points"] = {"file": os.path.relpath(p["pts"], ROOT), "count": len(pts),
                      "lattice": [winfo["nx"], winfo["nz"]], "spacing_m": 0.036,
                      "height_m": 0.8, "floor_extent_x": winfo["x"], "floor_extent_z": winfo["z"]}
    print("%s: %d triangles, dropped %s; %d points" % (scene, info["triangles"], dropped, len(pts)))


def stage_study(scene, p, data):
    points = workplane_points.read_points(p["pts"])
    step = STUDY_STEP[scene]
    sub = points[::step]
    regions = region_indices(scene, sub)
    rows, prev = [], {}
    for ab, ad, lw, only in RUNGS[scene]:
        args = rung_args(ab, ad, lw)
        regs = [(n, idx) for n, idx in regions if only is None or n in only]
        use = sorted(i for _, idx in regs for i in idx)
        pos = {i: j for j, i in enumerate(use)}
        (a, b), wall, cpu = run_rtrace(p["oct"], args, [[sub[i] for i in use]] * 2)
        row = {"ab": ab, "ad": ad, "lw": lw, "wall_s": round(wall, 1), "cpu_s": round(cpu, 1),
               "regions": {}}
        for name, idx in regs:
            s = two_pass_summary(a, b, [pos[i] for i in idx])
            if name in prev:
                q = prev[name]
                s["mean_change_pct"] = round(100 * (s["mean_lux"] / q["mean_lux"] - 1), 3) \
                    if q["mean_lux"] > 0 else None
                s["rms_change_pct"] = round(100 * (s["rms_lux"] / q["rms_lux"] - 1), 3) \
                    if q["rms_lux"] > 0 else None
            row["regions"][name] = s
            prev[name] = s
        rows.append(row)
        print("study %s ab %d ad %d lw %g: %.0f s CPU; %s" % (scene, ab, ad, lw, cpu, "; ".join(
            "%s mean %.4g rms %.4g (%s%%, %s%%) se/pt %s%%" % (
                n, s["mean_lux"], s["rms_lux"], s.get("mean_change_pct"), s.get("rms_change_pct"),
                s["point_std_err_pct"]) for n, s in row["regions"].items())), flush=True)
        data["study"] = {"subsample_step": step, "points": len(sub), "passes": 2,
                         "fixed_args": " ".join(BASE), "rungs": rows}
        save_json(p, data)


def write_csv(path, points, values):
    with open(path, "w") as f:
        f.write("x,y,z,illuminance_lux\n")
        for (x, y, z), v in zip(points, values):
            f.write("%.4f,%.4f,%.4f,%.4g\n" % (x, y, z, v))


def read_csv(path):
    out = {}
    with open(path) as f:
        next(f)
        for line in f:
            x, y, z, v = line.strip().split(",")
            out[(round(float(x), 4), round(float(y), 4), round(float(z), 4))] = float(v)
    return out


def key(p):
    return (round(p[0], 4), round(p[1], 4), round(p[2], 4))


def stage_converged(scene, p, data):
    points = workplane_points.read_points(p["pts"])
    chosen = {}  # point index -> (rgb average, rgb pass a, rgb pass b)
    summary = {}
    for name, idx in region_indices(scene, points):
        (ab, ad, lw), k = FINAL[scene][name]
        sel = idx[::k]
        args = rung_args(ab, ad, lw)
        (a, b), wall, cpu = run_rtrace(p["oct"], args, [[points[i] for i in sel]] * 2)
        s = two_pass_summary(a, b, range(len(sel)))
        avg = [tuple((x + y) / 2 for x, y in zip(u, v)) for u, v in zip(a, b)]
        for j, i in enumerate(sel):
            chosen[i] = avg[j]
        m709 = sum(lux(c, W_709) for c in avg) / len(avg)
        s.update({"ab": ab, "ad": ad, "lw": lw, "args": " ".join(args), "every_kth_point": k,
                  "region_points": len(idx), "wall_s": round(wall, 1), "cpu_s": round(cpu, 1),
                  "mean_lux_rec709_weights": round(m709, 4),
                  "rec709_vs_radiance_weights_pct": round(100 * (m709 / s["mean_lux"] - 1), 3)
                  if s["mean_lux"] > 0 else None})
        summary[name] = s
        print("converged %s/%s: %d points, mean %.4g lux, se/pt %s%%, %.0f s CPU" % (
            scene, name, len(sel), s["mean_lux"], s["point_std_err_pct"], cpu), flush=True)
    order = sorted(chosen)
    write_csv(p["converged"], [points[i][:3] for i in order], [lux(chosen[i]) for i in order])
    allv = [lux(chosen[i]) for i in order]
    data["converged"] = {"csv": os.path.relpath(p["converged"], ROOT), "points": len(order),
                         "passes_averaged": 2, "regions": summary,
                         "mean_lux_all_computed_points": round(sum(allv) / len(allv), 4)}
    save_json(p, data)


def score(ref, points, values, scene):
    """RMS error (% of the reference mean) and bias on the points that have a reference value,
    overall and per region."""
    out = {}
    regions = [("all", lambda q: True)] + REGIONS[scene]
    for name, pred in regions:
        pairs = [(ref[key(q)], v) for q, v in zip(points, values) if key(q) in ref and pred(q)]
        if not pairs:
            continue
        n = len(pairs)
        rmean = sum(r for r, _ in pairs) / n
        bias = sum(v - r for r, v in pairs) / n
        rms = math.sqrt(sum((v - r) ** 2 for r, v in pairs) / n)
        out[name] = {"points": n, "reference_mean_lux": round(rmean, 4),
                     "mean_lux": round(sum(v for _, v in pairs) / n, 4),
                     "bias_pct": round(100 * bias / rmean, 3) if rmean > 0 else None,
                     "rms_error_pct": round(100 * rms / rmean, 3) if rmean > 0 else None}
    return out


def run_consultant(p, points):
    """One rtrace process, irradiance cache on; returns (lux values, wall s, CPU s)."""
    (vals,), wall, cpu = run_rtrace(p["oct"], CONSULTANT, [points], nice=True)
    return [lux(c) for c in vals], wall, cpu


def stage_consultant(scene, p, data, repeats=1):
    points = workplane_points.read_points(p["pts"])
    ref = read_csv(p["converged"])
    runs = []
    for r in range(repeats):
        vals, wall, cpu = run_consultant(p, points)
        runs.append({"wall_s": round(wall, 2), "cpu_s": round(cpu, 2)})
        print("consultant %s: %.1f s wall, %.1f s CPU" % (scene, wall, cpu), flush=True)
    write_csv(p["consultant"], [q[:3] for q in points], vals)
    sc = score(ref, [q[:3] for q in points], vals, scene)
    data["consultant"] = {"args": "rtrace " + " ".join(CONSULTANT), "processes": 1, "runs": runs,
                          "csv": os.path.relpath(p["consultant"], ROOT),
                          "mean_lux_all_points": round(sum(vals) / len(vals), 4),
                          "against_converged": sc}
    for name, s in sc.items():
        print("  %s: RMS %s%%, bias %s%% (%d points)" % (name, s["rms_error_pct"], s["bias_pct"],
                                                       s["points"]))
    save_json(p, data)


def stage_checks(scene, p, data):
    checks = data.setdefault("checks", {})
    points = workplane_points.read_points(p["pts"])
    sub = points[::STUDY_STEP[scene]]
    regions = region_indices(scene, sub)
    ab, ad, lw = CHECK_RUNG
    args = rung_args(ab, ad, lw)
    doc, buffers = gltf_to_rad.load_gltf(p["gltf"])
    # 1. unobstructed horizontal point under the sky alone (both skies)
    if scene == "room":
        res = {}
        for sky in ("iso1", "gensky"):
            rad = os.path.join(WORK, "sky_only_%s.rad" % sky)
            with open(rad, "w") as f:
                f.write(gltf_to_rad.sky_text(sky, 10000.0, WORK))
            octree = rad[:-4] + ".oct"
            make_octree(rad, octree)
            (a, b), _, _ = run_rtrace(octree, rung_args(ab, 65536, lw), [[(0, 0, 0, 0, 1, 0)]] * 2)
            res[sky] = round((lux(a[0]) + lux(b[0])) / 2, 2)
        checks["unobstructed_point"] = {"closed_form_lux": 10000.0, "radiance_lux": res,
                                        "args": " ".join(rung_args(ab, 65536, lw))}
        print("unobstructed point: %s" % res, flush=True)
    # 2. grey materials (equal luminance by either weighting) and 3. gensky's sky, on the
    # study subsample, each against the coloured / ISO type 1 run with the same settings
    variants = {"coloured": dict(grey=None, sky="iso1"),
                "grey_rec709": dict(grey="rec709", sky="iso1"),
                "grey_radiance": dict(grey="radiance", sky="iso1"),
                "gensky_c": dict(grey=None, sky="gensky")}
    results = {}
    for name, v in variants.items():
        rad = os.path.join(WORK, "%s_%s.rad" % (scene, name))
        gltf_to_rad.write_rad(doc, buffers, rad, True, v["sky"], 10000.0, v["grey"])
        octree = rad[:-4] + ".oct"
        make_octree(rad, octree)
        (a, b), wall, cpu = run_rtrace(octree, args, [sub, sub])
        results[name] = {rn: two_pass_summary(a, b, idx) for rn, idx in regions}
        print("check %s %s: %s" % (scene, name, {rn: s["mean_lux"] for rn, s in results[name].items()}),
              flush=True)
    diff = {}
    for name in ("grey_rec709", "grey_radiance", "gensky_c"):
        diff[name] = {rn: round(100 * (results[name][rn]["mean_lux"] /
                                       results["coloured"][rn]["mean_lux"] - 1), 3)
                      for rn, _ in regions if results["coloured"][rn]["mean_lux"] > 0}
    checks["variants"] = {"args": " ".join(args), "subsample_step": STUDY_STEP[scene],
                          "points": len(sub), "results": results,
                          "mean_change_vs_coloured_iso1_pct": diff}
    save_json(p, data)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", choices=sorted(REGIONS))
    ap.add_argument("--stages", default="prepare,study,converged,consultant,checks")
    ap.add_argument("--radiance", metavar="DIR",
                    help="pyradiance's package folder (bin/ and lib/ inside)")
    ap.add_argument("--consultant-repeats", type=int, default=3)
    a = ap.parse_args()
    if a.radiance:
        os.environ["PATH"] = os.path.join(a.radiance, "bin") + os.pathsep + os.environ["PATH"]
        os.environ["RAYPATH"] = os.pathsep.join([".", os.path.join(a.radiance, "lib")])
    p = paths(a.scene)
    data = load_json(p)
    for stage in a.stages.split(","):
        t0 = time.time()
        {"prepare": stage_prepare, "study": stage_study, "converged": stage_converged,
         "consultant": lambda s, p, d: stage_consultant(s, p, d, a.consultant_repeats),
         "checks": stage_checks}[stage](a.scene, p, data)
        print("[%s %s: %.0f s]" % (a.scene, stage, time.time() - t0), flush=True)
        save_json(p, data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
