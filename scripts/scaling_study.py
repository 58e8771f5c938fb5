#!/usr/bin/env python3
"""scaling_study.py — paths per second against MPI ranks, and what each reduction costs
(docs/results/scaling.md; DESIGN.md §9).

Runs the same render (same seed and paths) as one process and under `mpirun -np N`, with PoCL
limited to T threads per process, interleaved over repetitions so that a busy machine slows every
configuration alike; checks that every run wrote the same image bytes; prints, per configuration,
the median paths per second over the repetitions, its ratio to one process of the same threads,
and the team's reductions: how many, bytes each, and their share of the render's wall time.

    scripts/scaling_study.py [--scene scenes/room.gltf] [--paths 8000000] [--reps 3]
                             [--configs 1x1,2x1,1x2,2x2,3x1] [--width 320] [-- more render args]

A configuration RxT is R processes (R = 1: no mpirun) of T PoCL threads each. Needs build/fenestra
built with MPI, and mpirun (Open MPI: run as root needs OMPI_ALLOW_RUN_AS_ROOT, set here).
"""
import argparse
import hashlib
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(cfg, args, out):
    ranks, threads = (int(x) for x in cfg.split("x"))
    env = dict(os.environ, POCL_MAX_PTHREAD_COUNT=str(threads), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.setdefault("POCL_CACHE_DIR", os.path.join(ROOT, "build", "pocl-cache"))
    cmd = [os.path.join(ROOT, "build", "fenestra"), "render"] + args + ["--out", out, "--no-progress"]
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"scaling_study: {cfg}: exit {p.returncode}: {p.stderr.strip()[-400:]}")
    j = json.load(open(out[:-4] + ".json"))
    image = hashlib.sha256(open(out, "rb").read()).hexdigest()
    return j, image


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="scenes/room.gltf")
    ap.add_argument("--paths", type=int, default=8_000_000)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--configs", default="1x1,2x1,1x2,2x2,3x1")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("rest", nargs="*")
    a = ap.parse_args()
    args = [os.path.join(ROOT, a.scene), "--paths", str(a.paths), "--width", str(a.width), "--seed", "7"] + a.rest
    configs = a.configs.split(",")
    results = {c: [] for c in configs}
    images = set()
    with tempfile.TemporaryDirectory() as tmp:
        for rep in range(a.reps):
            for c in configs:
                j, image = run(c, args, os.path.join(tmp, f"r{c}.exr"))
                images.add(image)
                results[c].append(j)
    print(f"scene {a.scene}, {a.paths} paths, width {a.width}, {a.reps} interleaved repetitions; "
          f"{'one image' if len(images) == 1 else str(len(images)) + ' DIFFERENT images'} over all runs")
    print("| processes x threads | Mpaths/s (median) | vs 1 process, same threads | reductions | MB each | "
          "reduction share of render time |")
    print("|---|---|---|---|---|---|")
    for c in configs:
        rate = statistics.median(j["paths_per_second"] for j in results[c]) * 1e-6
        ranks, threads = (int(x) for x in c.split("x"))
        base = f"1x{threads}"
        ratio = ""
        if base in results and c != base:
            ratio = f"{rate / (statistics.median(j['paths_per_second'] for j in results[base]) * 1e-6):.2f}"
        team = results[c][0].get("team")
        if team:
            share = statistics.median(j["team"]["seconds"] / j["seconds"]["render"] for j in results[c])
            cols = f"{team['reductions']} | {team['bytes_per_reduction'] / 1e6:.2f} | {100 * share:.1f} %"
        else:
            cols = "– | – | –"
        print(f"| {ranks} x {threads} | {rate:.2f} | {ratio} | {cols} |")
    if len(images) != 1:
        sys.exit("scaling_study: the runs wrote different images")


if __name__ == "__main__":
    main()
