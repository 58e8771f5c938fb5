#!/usr/bin/env python3
"""camera_pass_study.py — the camera pass's two modes (DESIGN.md §2, `--camera-pass`) at two render
times, seeds interleaved: does the noise where the camera sees the sky directly (a window's box)
fall with time, and what does balancing cost or gain over the whole image.

    python3 scripts/camera_pass_study.py [--scene scenes/room.gltf] [--times 15,60] [--seeds 1,2,3]
        [--region win=350,0,575,210] [--out out/camera_pass] [--fenestra build/fenestra]

Runs fenestra for every (seed, time, mode), the modes alternating so that a machine's drift falls
on both alike, and prints a Markdown table of medians over the seeds: paths, the whole image's noise
(RMS of the pixels' standard errors, cd/m²), the region's, the camera pass's share of device time
and of the predicted variance; then each mode's fall of the region's noise from the first time to
the last, and balanced's efficiency over fixed at each time, (noise_fixed / noise_balanced)² (equal
time). The measurements are in docs/results/guiding.md.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys


def run(fen, scene, out, seed, seconds, mode, region):
    path = os.path.join(out, f"{mode}_t{seconds}_s{seed}.exr")
    cmd = [fen, "render", scene, "--out", path, "--time", str(seconds), "--seed", str(seed),
           "--camera-pass", mode, "--region", region, "--no-progress"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(path[:-4] + ".json") as f:
        j = json.load(f)
    name = region.split("=")[0]
    return {"paths": j["paths"], "noise": j["noise_std_err_cd_m2"],
            "region": j["regions"][name]["noise_std_err_cd_m2"],
            "time_share": j["camera_pass"]["device_time_share"], "error_share": j["camera_pass"]["error_share"],
            "samples": j["camera_samples_per_pixel"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="scenes/room.gltf")
    ap.add_argument("--times", default="15,60")
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--region", default="win=350,0,575,210")
    ap.add_argument("--out", default="out/camera_pass")
    ap.add_argument("--fenestra", default="build/fenestra")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    times = [int(t) for t in a.times.split(",")]
    seeds = [int(s) for s in a.seeds.split(",")]
    modes = ["fixed", "balanced"]
    res = {}
    for seed in seeds:
        for t in times:
            for m in (modes if seed % 2 else modes[::-1]):
                r = run(a.fenestra, a.scene, a.out, seed, t, m, a.region)
                res[(m, t, seed)] = r
                print(f"# {m} {t} s seed {seed}: {json.dumps(r)}", file=sys.stderr, flush=True)

    def med(m, t, key):
        return statistics.median(res[(m, t, s)][key] for s in seeds)

    name = a.region.split("=")[0]
    print(f"| mode | time (s) | paths (M) | image noise (cd/m²) | {name} noise (cd/m²) | camera samples / pixel "
          f"| camera device time | camera variance share |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for m in modes:
        for t in times:
            print(f"| {m} | {t} | {med(m, t, 'paths') / 1e6:.1f} | {med(m, t, 'noise'):.1f} | {med(m, t, 'region'):.1f} "
                  f"| {med(m, t, 'samples'):.1f} | {100 * med(m, t, 'time_share'):.1f} % "
                  f"| {100 * med(m, t, 'error_share'):.2f} % |")
    print()
    t0, t1 = times[0], times[-1]
    for m in modes:
        falls = [res[(m, t0, s)]["region"] / res[(m, t1, s)]["region"] for s in seeds]
        print(f"- {m}: the {name} box's noise falls {statistics.median(falls):.2f}× from {t0} s to {t1} s "
              f"(seeds: {', '.join(f'{x:.2f}' for x in falls)})")
    for t in times:
        eff = [(res[("fixed", t, s)]["noise"] / res[("balanced", t, s)]["noise"]) ** 2 for s in seeds]
        effr = [(res[("fixed", t, s)]["region"] / res[("balanced", t, s)]["region"]) ** 2 for s in seeds]
        print(f"- at {t} s, balanced over fixed: image efficiency {statistics.median(eff):.2f}× "
              f"(seeds: {', '.join(f'{x:.2f}' for x in eff)}), {name} box {statistics.median(effr):.2f}×")


if __name__ == "__main__":
    main()
