#!/usr/bin/env python3
"""Weight windows (--adaptive-window) against adaptive without them, at equal time.

For each scene and seed, the variants run one after another (interleaved, so that a busy machine
slows them alike), adaptive emission, the same seed, the same time; efficiency of a variant =
(noise_b^2 * seconds_b) / (noise^2 * seconds), b the --baseline variant (off); noise = the JSON's
noise_std_err_cd_m2 (the per-pixel standard error over the ROI); seconds = the render's, or with
--charge-calibration its calibration's too (a variant that calibrates longer, as
--adaptive-openings-share auto does for its race, pays for it). Prints one line per render and the
median efficiency per scene and variant; every line also goes to --data.

    python3 scripts/window_study.py --scenes house,house_snow,courtyard --seeds 1,2,3 \\
        --variants off,mean,mean_cull50,mean_cull05 --width 160 --time 20 --out out/window \\
        --data docs/results/window_data.txt

Variants (--variants, comma-separated names): off (no windows); mean and moment (the
two rules' windows, splitting and never culling; moment is the default); mean_cull50, moment_cull50 (also culling, the
survival at least 0.5) and mean_cull05, moment_cull05 (at least 0.05). Any other option set is a
variant of its own with --variant NAME 'OPTIONS' (repeatable; then list NAME in --variants), e.g.

    python3 scripts/window_study.py --variants off,ss1024 \\
        --variant ss1024 '--adaptive-guide-space-split 1024'

`default` is the options as they are; with --baseline default another option is measured against
them, e.g. --variants default,def03 --variant def03 '--adaptive-defensive 0.3' --baseline default.
A variant may also run edited kernels: --variant-kernels NAME DIR sets FEN_KERNEL_DIR=DIR for it
(with no options of its own unless --variant NAME gives some), e.g. the bound of
scripts/aim_oracle.py.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

VARIANTS = {"off": ["--adaptive-window", "off"]}
for rule in ("mean", "moment"):
    VARIANTS[rule] = ["--adaptive-window", rule]  # split, never cull (the default survival, 1)
    VARIANTS[rule + "_cull50"] = ["--adaptive-window", rule, "--adaptive-window-survival", "0.5"]
    VARIANTS[rule + "_cull05"] = ["--adaptive-window", rule, "--adaptive-window-survival", "0.05"]
VARIANTS["default"] = []  # the default options as they are


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fenestra", default="build/fenestra")
    ap.add_argument("--scenes", default="house")
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--variants", default="off,mean,moment,moment_cull50")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--time", type=float, default=20.0)
    ap.add_argument("--out", default="out/window")
    ap.add_argument("--data", default=None, help="append every line to this file")
    ap.add_argument("--variant", nargs=2, action="append", default=[], metavar=("NAME", "OPTIONS"),
                    help="a variant of fenestra's own options, split at spaces")
    ap.add_argument("--variant-kernels", nargs=2, action="append", default=[], metavar=("NAME", "DIR"),
                    help="run variant NAME with FEN_KERNEL_DIR=DIR (edited kernels)")
    ap.add_argument("--baseline", default="off", help="the variant the others' efficiency is over (default off)")
    ap.add_argument("--charge-calibration", action="store_true",
                    help="count each render's calibration seconds with its render seconds")
    ap.add_argument("--common", default="", help="options for every run, split at spaces (e.g. '--roi X0,Y0,X1,Y1')")
    a = ap.parse_args()
    for name, options in a.variant:
        VARIANTS[name] = options.split()
    kernels = {}
    for name, folder in a.variant_kernels:
        if not os.path.isdir(os.path.join(folder, "lib")):
            sys.exit(f"window_study.py: --variant-kernels {name}: '{folder}' holds no kernels (no lib/)")
        kernels[name] = os.path.abspath(folder)
        VARIANTS.setdefault(name, [])
    os.makedirs(a.out, exist_ok=True)
    variants = a.variants.split(",")
    for v in variants:
        if v not in VARIANTS:
            sys.exit(f"window_study.py: unknown variant '{v}' (known: {', '.join(VARIANTS)})")
    data = open(a.data, "a") if a.data else None
    eff = {}

    def emit(line):
        print(line, flush=True)
        if data:
            data.write(line + "\n")
            data.flush()

    def efficiency(scene, v, runs):
        """Variant v's efficiency over the baseline for this seed, also kept for the medians."""
        (n0, t0), (n, t) = runs[a.baseline], runs[v]
        e = (n0 * n0 * t0) / (n * n * t)
        eff.setdefault((scene, v), []).append(e)
        return e
    for scene in a.scenes.split(","):
        for seed in a.seeds.split(","):
            runs = {}
            for v in variants:
                stem = os.path.join(a.out, f"{scene}_{v}_{seed}")
                # adaptive unless the variant names its own method (e.g. --variant uniform '--method uniform')
                method = [] if "--method" in VARIANTS[v] else ["--method", "adaptive"]
                cmd = [a.fenestra, "render", f"scenes/{scene}.gltf", *method, "--seed", seed,
                       "--width", str(a.width), "--time", str(a.time), "--no-progress", "--out", stem + ".exr"]
                env = dict(os.environ)
                env.pop("FEN_KERNEL_DIR", None)
                if v in kernels:
                    env["FEN_KERNEL_DIR"] = kernels[v]
                subprocess.run(cmd + a.common.split() + VARIANTS[v], check=True, stdout=subprocess.DEVNULL, env=env)
                j = json.load(open(stem + ".json"))
                c = j["counters"]
                seconds = j["seconds"]["render"] + (j["seconds"]["calibration"] if a.charge_calibration else 0.0)
                runs[v] = (j["noise_std_err_cd_m2"], seconds)
                line = (f"{scene} seed {seed} {v:7s} noise {j['noise_std_err_cd_m2']:8.3f} "
                        f"mean {j['mean_luminance_cd_m2']:9.3f} +- {j['mean_std_err_cd_m2']:.3f} "
                        f"top1 {j['noise_top1_share']:.2f} paths {j['paths'] / 1e6:7.1f}M "
                        f"render {j['seconds']['render']:5.1f}s calibration {j['seconds']['calibration']:4.1f}s "
                        f"split {c['split_branches'] / 1e6:6.1f}M "
                        f"culls {c['window_culls'] / 1e6:6.1f}M "
                        f"window_slots {j['emission'].get('guide', {}).get('window_slots', 0)}")
                if a.baseline in runs and v != a.baseline:
                    line += f" efficiency {efficiency(scene, v, runs):.2f}"
                emit(line)
            # variants that ran before the baseline get their efficiency once it has run
            if a.baseline in runs:
                for v in variants[:variants.index(a.baseline)]:
                    emit(f"{scene} seed {seed} {v:7s} efficiency {efficiency(scene, v, runs):.2f} "
                         f"(over {a.baseline}, which ran after it)")
    for (scene, v), es in sorted(eff.items()):
        emit(f"{scene} {v}: median efficiency {statistics.median(es):.2f} ({', '.join(f'{e:.2f}' for e in es)})")


if __name__ == "__main__":
    main()
