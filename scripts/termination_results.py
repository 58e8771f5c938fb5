#!/usr/bin/env python3
"""termination_results.py — when Russian roulette should start (--roulette-depth), measured as
efficiency, written to docs/results/termination.md.

Before interaction K a path always goes on (weight *= albedo); from K on it survives with
probability max(albedo) (weight *= albedo / q). Both are unbiased (tests: Analytic.*, furnace);
what changes is how many camera connections a path makes for its cost. Each scene and method is
rendered for equal time with each K, seeds 1 and 2; efficiency = 1 / (noise² × seconds), noise the
batch estimate of the per-pixel standard error (an unbiased method's RMSE without a reference),
relative to K = 0 (roulette from the first interaction), median of the seeds.

Run from the repository root after building (`scripts/setup.sh`), on an otherwise idle machine:

    python3 scripts/termination_results.py [--seconds 20] [--depths 0,2,4,8] [--table-only]

Standard library only.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

OUT = "out/termination"
SCENES = [  # (label, file, options)
    ("inner room, rectangle", "scenes/inner_room.gltf", ["--roi", "140,80,260,180"]),  # the rectangle at 320 x 240
    ("room", "scenes/room.gltf", []),
    ("bay window", "scenes/bay_window.gltf", []),
]
METHODS = [("uniform", ["--method", "uniform"]), ("portal", ["--method", "portal"]),
           ("adaptive", ["--method", "adaptive"])]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=float, default=20.0)
    ap.add_argument("--depths", default="0,2,4,8")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--methods", default="uniform,portal,adaptive")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--table-only", action="store_true")
    ap.add_argument("--data", default="docs/results/termination_data.md", help="where the table goes")
    a = ap.parse_args()
    depths = [int(d) for d in a.depths.split(",")]
    seeds = [int(s) for s in a.seeds.split(",")]
    os.makedirs(OUT, exist_ok=True)
    res = {}
    # Interleaved: seed, then scene, method and depth, so that drift of a shared machine spreads
    # over all settings alike.
    for seed in seeds:
        for si, (label, scene, opts) in enumerate(SCENES):
            for mname, margs in [m for m in METHODS if m[0] in a.methods.split(",")]:
                for d in depths:
                    name = "%d_%s_%s_rr%d_s%d" % (si, os.path.splitext(os.path.basename(scene))[0], mname, d, seed)
                    path = os.path.join(OUT, name + ".exr")
                    if not a.table_only:
                        cmd = ["build/fenestra", "render", scene, "--out", path, "--time", str(a.seconds),
                               "--seed", str(seed), "--width", str(a.width), "--no-progress",
                               "--roulette-depth", str(d)] + margs + opts
                        print("$", " ".join(cmd), flush=True)
                        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
                    with open(os.path.join(OUT, name + ".json")) as f:
                        res[(si, mname, d, seed)] = json.load(f)

    lines = ["# When Russian roulette starts: efficiency\n",
             "Each scene and method rendered for %g s (%d px wide) with Russian roulette from interaction K on "
             "(`--roulette-depth K`; before it every path goes on with its weight times the albedo), seeds %s. "
             "*Efficiency* 1 / (noise² × seconds) relative to the first K (median over the seeds; noise: the batch estimate "
             "of each pixel's standard error, RMS over the region), *rays/path* extension rays per emitted path, "
             "*conn/path* camera connections per path. Regenerate: `python3 scripts/termination_results.py "
             "--seconds %g --depths %s`.\n" % (a.seconds, a.width, ", ".join(map(str, seeds)), a.seconds,
                                               ",".join(map(str, depths)))]
    head = "| scene | method | " + " | ".join("K = %d" % d for d in depths) + " |"
    lines += [head, "|---|---|" + "---|" * len(depths)]
    for si, (label, _, _) in enumerate(SCENES):
        for mname, _ in [m for m in METHODS if m[0] in a.methods.split(",")]:
            def eff(d, seed):
                j = res[(si, mname, d, seed)]
                return 1.0 / (j["noise_std_err_cd_m2"] ** 2 * j["seconds"]["render"])
            cells = []
            for d in depths:
                rel = statistics.median(eff(d, s) / eff(depths[0], s) for s in seeds)
                j = res[(si, mname, d, seeds[0])]
                rays = j["rays"]["extension"] / max(1, j["paths"])
                conn = j["rays"]["shadow"] / max(1, j["paths"])
                cells.append("%.2fx (%.2f rays, %.3f conn/path)" % (rel, rays, conn))
            lines.append("| %s | %s | %s |" % (label, mname, " | ".join(cells)))
    lines.append("")
    any_j = next(iter(res.values()))
    lines.append("Machine: %s; %s kernels.\n" % (any_j["device"], any_j.get("kernel_mode", "wavefront")))
    with open(a.data, "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
