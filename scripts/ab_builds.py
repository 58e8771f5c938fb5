#!/usr/bin/env python3
"""ab_builds.py — two builds of fenestra against each other on the same renders, interleaved.

For a change that should make rendering faster without changing what it estimates: each scene is
rendered for equal wall time by build A and build B in turn (A, B, A, B, ... one seed per round,
so drift of a shared machine hits both alike), then once each with the wavefront kernels for the
per-stage device time. Prints a Markdown table: paths/s, rays/s, noise, the image mean, B's
efficiency (1 / (noise^2 x seconds)) over A's per round and its median, and the emission stage's
share of device time.

    python3 scripts/ab_builds.py --a /tmp/old/fenestra --b build/fenestra \\
        --scenes bay_window,house --method portal --seconds 15 --rounds 3

Builds whose noise estimates may differ (an older build without the camera pass, say) are compared
with --noise pairs: each round renders two seeds with each build, the second with --reference the
first, and a build's per-pixel variance is half the mean squared difference between its two images
over the ROI, an estimate that takes nothing from either build's own bookkeeping:

    python3 scripts/ab_builds.py --a /tmp/old/build/fenestra --b build/fenestra --method adaptive \
        --scenes room,bay_window --seconds 10 --rounds 3 --noise pairs --no-stages

A's binary is usually the previous commit, built apart:
    git worktree add /tmp/old HEAD~1 && cmake -S /tmp/old -B /tmp/old/build -DCMAKE_BUILD_TYPE=Release \\
        && cmake --build /tmp/old/build -j2
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys


def render(binary, scene, method, seconds, width, seed, out, extra):
    cmd = [binary, "render", os.path.join("scenes", scene + ".gltf"), "--method", method, "--time", str(seconds),
           "--width", str(width), "--seed", str(seed), "--out", out, "--no-progress"] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out[:-4] + ".json") as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="build A's fenestra binary (the baseline)")
    ap.add_argument("--b", required=True, help="build B's fenestra binary")
    ap.add_argument("--scenes", required=True, help="comma-separated names under scenes/")
    ap.add_argument("--method", default="portal")
    ap.add_argument("--seconds", type=float, default=15.0)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--out", default="out/ab")
    ap.add_argument("--noise", choices=("json", "pairs"), default="json",
                    help="json: each render's own noise_std_err_cd_m2; pairs: from two seeds' images (above)")
    ap.add_argument("--extra", default="", help="options for every render, split at spaces (e.g. '--roi X0,Y0,X1,Y1')")
    ap.add_argument("--no-stages", action="store_true", help="skip the wavefront runs for the stages' device time")
    a = ap.parse_args()
    extra = a.extra.split()
    os.makedirs(a.out, exist_ok=True)
    builds = {"A": a.a, "B": a.b}
    runs = {}
    for rnd in range(1, a.rounds + 1):
        for scene in a.scenes.split(","):
            if a.noise == "json":
                for name, binary in builds.items():
                    out = os.path.join(a.out, "%s_%s_%d.exr" % (scene, name, rnd))
                    runs.setdefault((scene, name), []).append(
                        render(binary, scene, a.method, a.seconds, a.width, rnd, out, extra))
                continue
            # pairs: seeds 2r-1 and 2r, the builds in turn for each seed
            first = {}  # build -> (its first seed's image, that render's JSON)
            for name, binary in builds.items():
                out = os.path.join(a.out, "%s_%s_%d.exr" % (scene, name, 2 * rnd - 1))
                first[name] = (out, render(binary, scene, a.method, a.seconds, a.width, 2 * rnd - 1, out, extra))
            for name, binary in builds.items():
                out = os.path.join(a.out, "%s_%s_%d.exr" % (scene, name, 2 * rnd))
                reference, j0 = first[name]
                j = render(binary, scene, a.method, a.seconds, a.width, 2 * rnd, out,
                           extra + ["--reference", reference])
                # E[(Y1 - Y2)^2] = 2 var per pixel; the round's time is the two renders' mean
                j["noise_std_err_cd_m2"] = j["rmse_cd_m2"] / math.sqrt(2.0)
                j["seconds"]["render"] = 0.5 * (j["seconds"]["render"] + j0["seconds"]["render"])
                j["paths_per_second"] = 0.5 * (j["paths_per_second"] + j0["paths_per_second"])
                j["rays_per_second"] = 0.5 * (j["rays_per_second"] + j0["rays_per_second"])
                runs.setdefault((scene, name), []).append(j)
    share = {}
    for scene in a.scenes.split(",") if not a.no_stages else []:
        for name, binary in builds.items():
            out = os.path.join(a.out, "%s_%s_wavefront.exr" % (scene, name))
            j = render(binary, scene, a.method, min(a.seconds, 8.0), a.width, 1, out, ["--kernels", "wavefront"])
            k = j["kernels"]
            total = sum(v["device_seconds"] for v in k.values())
            emit = sum(v["device_seconds"] for n, v in k.items() if n.startswith("emit"))
            share[(scene, name)] = emit / total if total > 0 else float("nan")
    noise = "noise" if a.noise == "json" else "noise (pairs)"

    print("| scene | build | paths/s (M) | rays/s (M) | " + noise + " | mean ± s.e. | emission share | B's efficiency / A's |")
    print("|---|---|---|---|---|---|---|---|")
    for scene in a.scenes.split(","):
        A, B = runs[(scene, "A")], runs[(scene, "B")]
        eff = [(x["noise_std_err_cd_m2"] ** 2 * x["seconds"]["render"]) /
               (y["noise_std_err_cd_m2"] ** 2 * y["seconds"]["render"]) for x, y in zip(A, B)]
        for name, r in (("A", A), ("B", B)):
            cell = lambda f, fmt: ", ".join(fmt % f(x) for x in r)
            print("| %s | %s | %s | %s | %s | %s | %.1f %% | %s |" % (
                scene, name, cell(lambda x: x["paths_per_second"] / 1e6, "%.3f"),
                cell(lambda x: x["rays_per_second"] / 1e6, "%.2f"), cell(lambda x: x["noise_std_err_cd_m2"], "%.3g"),
                cell(lambda x: x["mean_luminance_cd_m2"], "%.4g") + " (± " +
                cell(lambda x: x["mean_std_err_cd_m2"], "%.2g") + ")",
                100 * share.get((scene, name), float("nan")),
                "" if name == "A" else "%s (median %.2f)" % (", ".join("%.2f" % e for e in eff), statistics.median(eff))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
