#!/usr/bin/env python3
"""race.py — races fenestra's sensor grid against a typical Radiance run on the same work plane:
the "consultant" rtrace run (irradiance cache on, one process; reference.py) and `fenestra
render --sensor-points`, interleaved (Radiance, fenestra, Radiance, fenestra, ...), each scored
against the converged Radiance reference (docs/results/radiance/<scene>_converged.csv).

    python3 scripts/radiance/race.py room [--fenestra build/host/fenestra] [--repeats 3] \
        [--time T] [--seed 1] [--radiance DIR] [--fenestra-arg=--emission=portal ...]

fenestra renders docs/results/radiance/<scene>_open.gltf (the open-window variant, the same
geometry as the Radiance scene) under the CIE type 1 overcast sky of 10 000 lux diffuse
horizontal, no sun:

    fenestra render <scene>_open.gltf --out DIR/f.exr --no-image --sky cie:1 --sky-lux 10000
        --sun none --sensor-points <scene>_workplane.pts --sensor-size 0.036 --time T --seed S

and writes DIR/f.sensors.csv (sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,
std_err_lux; rows in the points file's order) and DIR/f.json. fenestra gets the wall time T of
the median Radiance run: --time T, or else the median wall time of the consultant runs recorded
in <scene>_radiance.json, or else that of one untimed warm-up run. Each repetition gets its own
seed (S, S+1, ...).

Reported per method: median wall and CPU seconds (CPU: user + system of the child process and
its threads), and against the reference (on the points it has, overall and per region): RMS
error as % of the reference mean, bias (mean error) as % of it, and the RMS with the
reference's own noise taken out (sqrt(RMS^2 - s_ref^2), s_ref from its two passes). Prints a
markdown table; --json OUT writes the numbers too.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import reference  # noqa: E402
import workplane_points  # noqa: E402


def read_sensors(path):
    """[(x, y, z, illuminance)] of a fenestra sensors CSV, in its row order."""
    out = []
    with open(path) as f:
        head = f.readline().strip().split(",")
        col = {n: i for i, n in enumerate(head)}
        for need in ("x_m", "y_m", "z_m", "illuminance_lux"):
            if need not in col:
                sys.exit("race.py: %s has no column %s (header: %s)" % (path, need, ",".join(head)))
        for line in f:
            v = line.strip().split(",")
            if len(v) < len(head):
                continue
            out.append((float(v[col["x_m"]]), float(v[col["y_m"]]), float(v[col["z_m"]]),
                        float(v[col["illuminance_lux"]])))
    return out


def ref_noise(data, scene):
    """Per-region per-point standard error of the reference, lux ({region: (s, points)})."""
    regs = data.get("converged", {}).get("regions", {})
    return {n: (r["point_std_err_lux"], r["points"]) for n, r in regs.items()}


def add_noise_corrected(sc, noise):
    for name, s in sc.items():
        if name == "all":
            tot = sum(n for _, n in noise.values())
            s2 = sum(se * se * n for se, n in noise.values()) / tot if tot else 0.0
        elif name in noise:
            s2 = noise[name][0] ** 2
        else:
            continue
        if s["rms_error_pct"] is None:
            continue
        rms = s["rms_error_pct"] / 100 * s["reference_mean_lux"]
        s["reference_point_std_err_pct"] = round(100 * math.sqrt(s2) / s["reference_mean_lux"], 3)
        s["rms_error_ref_noise_removed_pct"] = round(
            100 * math.sqrt(max(rms * rms - s2, 0.0)) / s["reference_mean_lux"], 3)
    return sc


def run_fenestra(binary, scene_gltf, pts, t, seed, extra, workdir):
    out = os.path.join(workdir, "f.exr")
    cmd = [binary, "render", scene_gltf, "--out", out, "--no-image", "--sky", "cie:1",
           "--sky-lux", "10000", "--sun", "none", "--sensor-points", pts, "--sensor-size", "0.036",
           "--time", "%g" % t, "--seed", str(seed)] + extra
    cpu0, t0 = reference.children_cpu(), time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall, cpu = time.time() - t0, reference.children_cpu() - cpu0
    if r.returncode != 0:
        sys.exit("race.py: fenestra failed (%s):\n%s" % (" ".join(cmd), r.stderr.strip()))
    rows = read_sensors(os.path.join(workdir, "f.sensors.csv"))
    return rows, wall, cpu, " ".join(cmd)


def fmt(v, d=2):
    return "—" if v is None else ("%.*f" % (d, v))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", choices=sorted(reference.REGIONS))
    ap.add_argument("--fenestra", default=os.path.join(reference.ROOT, "build", "host", "fenestra"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--time", type=float, help="fenestra's --time (default: Radiance's median wall)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--radiance", metavar="DIR", help="pyradiance's package folder")
    ap.add_argument("--fenestra-arg", action="append", default=[],
                    help="extra argument for fenestra render (repeatable; use --fenestra-arg=--x)")
    ap.add_argument("--json", metavar="OUT", help="write the numbers as JSON")
    a = ap.parse_args()
    if a.radiance:
        os.environ["PATH"] = os.path.join(a.radiance, "bin") + os.pathsep + os.environ["PATH"]
        os.environ["RAYPATH"] = os.pathsep.join([".", os.path.join(a.radiance, "lib")])
    p = reference.paths(a.scene)
    for need in ("open_gltf", "pts", "converged"):
        if not os.path.exists(p[need]):
            sys.exit("race.py: %s missing: run scripts/radiance/reference.py %s first" % (p[need], a.scene))
    if not os.path.exists(p["oct"]):
        reference.stage_prepare(a.scene, p, {})  # rebuilds the octree (and the same files)
    data = reference.load_json(p)
    ref = reference.read_csv(p["converged"])
    noise = ref_noise(data, a.scene)
    points = workplane_points.read_points(p["pts"])
    xyz = [q[:3] for q in points]
    if not (os.path.isfile(a.fenestra) and os.access(a.fenestra, os.X_OK)):
        sys.exit("race.py: no fenestra binary at %s (build it, or give --fenestra)" % a.fenestra)

    t = a.time
    if t is None:
        walls = [r["wall_s"] for r in data.get("consultant", {}).get("runs", [])]
        if walls:
            t = statistics.median(walls)
            print("fenestra --time %.2f: median wall of the recorded consultant runs" % t, flush=True)
        else:
            _, w, _ = reference.run_consultant(p, points)
            t = w
            print("fenestra --time %.2f: wall of a warm-up Radiance run" % t, flush=True)

    rad_runs, fen_runs, fen_cmd = [], [], None
    with tempfile.TemporaryDirectory(prefix="race_") as tmp:
        for k in range(a.repeats):
            vals, wall, cpu = reference.run_consultant(p, points)
            sc = reference.score(ref, xyz, vals, a.scene)
            rad_runs.append({"wall_s": wall, "cpu_s": cpu, "score": add_noise_corrected(sc, noise)})
            print("radiance %d: %.2f s wall, %.2f s CPU, RMS %s%%" % (
                k + 1, wall, cpu, sc["all"]["rms_error_pct"]), flush=True)
            rows, wall, cpu, fen_cmd = run_fenestra(a.fenestra, p["open_gltf"], p["pts"], t,
                                                    a.seed + k, a.fenestra_arg, tmp)
            if len(rows) != len(points):
                sys.exit("race.py: fenestra wrote %d sensors for %d points" % (len(rows), len(points)))
            for (x, y, z, _), q in zip(rows, xyz):
                if max(abs(x - q[0]), abs(y - q[1]), abs(z - q[2])) > 1e-3:
                    sys.exit("race.py: fenestra's sensor at (%g, %g, %g) is not the point %s"
                             % (x, y, z, q))
            sc = reference.score(ref, xyz, [r[3] for r in rows], a.scene)
            fen_runs.append({"wall_s": wall, "cpu_s": cpu, "score": add_noise_corrected(sc, noise)})
            print("fenestra %d: %.2f s wall, %.2f s CPU, RMS %s%%" % (
                k + 1, wall, cpu, sc["all"]["rms_error_pct"]), flush=True)

    def summary(runs):
        med = lambda key: statistics.median(r[key] for r in runs)
        regions = {}
        for name in runs[0]["score"]:
            regions[name] = {m: statistics.median(r["score"][name][m] for r in runs
                                                  if r["score"][name].get(m) is not None)
                             for m in ("rms_error_pct", "bias_pct", "rms_error_ref_noise_removed_pct")
                             if any(r["score"][name].get(m) is not None for r in runs)}
            regions[name]["points"] = runs[0]["score"][name]["points"]
        return {"wall_s": med("wall_s"), "cpu_s": med("cpu_s"), "regions": regions, "runs": runs}

    res = {"scene": a.scene, "repeats": a.repeats, "fenestra_time_s": t,
           "radiance": dict(summary(rad_runs), command="rtrace " + " ".join(reference.CONSULTANT)),
           "fenestra": dict(summary(fen_runs), command=fen_cmd)}
    print()
    print("%s: medians of %d interleaved runs; errors against the converged Radiance reference "
          "(RMS and bias as %% of the reference mean)" % (a.scene, a.repeats))
    print()
    print("| method | region | wall s | CPU s | RMS error % | bias % | RMS without reference noise % |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for label, key in (("Radiance rtrace, irradiance cache (1 process)", "radiance"),
                       ("fenestra --time %g" % t, "fenestra")):
        s = res[key]
        for name, r in s["regions"].items():
            print("| %s | %s (%d points) | %s | %s | %s | %s | %s |" % (
                label, name, r["points"], fmt(s["wall_s"]), fmt(s["cpu_s"]),
                fmt(r.get("rms_error_pct")), fmt(r.get("bias_pct")),
                fmt(r.get("rms_error_ref_noise_removed_pct"))))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)
            f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
