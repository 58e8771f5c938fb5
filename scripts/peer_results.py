#!/usr/bin/env python3
"""peer_results.py — fenestra's light tracer against Mitsuba 3's (`ptracer`) on one scene, equal
time, interleaved by seed: image means, per-pixel noise and efficiency (docs/results/peer.md).

    pip install mitsuba      # not a dependency of fenestra; only this script uses it
    python3 scripts/peer_results.py scenes/inner_room.gltf --roi 140,80,260,180 --seconds 10 \
        --seeds 1-8 --fenestra "uniform,uniform+roulette-depth=0" --out out/peer/inner_room

Every configuration renders once per seed for about --seconds (Mitsuba: a sample count calibrated
to that time). Noise is measured the same way for both renderers, with no batch estimator: the
per-pixel variance of one render across the seeds, averaged over the region. Efficiency is
M² / (variance × render seconds), M the whole image's mean over all
seeds (more precise than the region's), so that a uniform difference of brightness between the two
conversions (the thin glass, scripts/mitsuba_peer.py) does not count; it is printed relative to
the first fenestra configuration. Mitsuba renders with a box pixel filter (fenestra's: a camera
connection lands in one pixel) and with its default, a Gaussian of standard deviation 0.5 px,
which spreads each connection over about 3 pixels' worth of area and so trades resolution for
noise. `--integrator path` races Mitsuba's path tracer instead (the sky seen directly shown; a
scene whose sun comes through thin glass needs its glass made an opening first, since a path
tracer cannot reach a directional light through a specular sheet: scripts/scene_variant.py
--opening).
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_peer  # noqa: E402

LUMA = np.array([0.2126, 0.7152, 0.0722])


def seeds_of(text):
    if "-" in text:
        a, b = text.split("-")
        return list(range(int(a), int(b) + 1))
    return [int(s) for s in text.split(",")]


def fenestra_args(config):
    """'uniform+roulette-depth=0' -> ['--method', 'uniform', '--roulette-depth', '0']"""
    parts = config.split("+")
    args = ["--method", parts[0]]
    for p in parts[1:]:
        k, _, v = p.partition("=")
        args += ["--" + k] + ([v] if v else [])
    return args


def luminance(mi, path):
    return np.array(mi.Bitmap(path))[..., :3].astype(float) @ LUMA


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--roi", help="x0,y0,x1,y1 (x1, y1 exclusive); whole image when absent")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--seconds", type=float, default=10)
    ap.add_argument("--seeds", default="1-8")
    ap.add_argument("--fenestra", default="uniform", help="comma-separated configurations")
    ap.add_argument("--filters", default="box,gaussian")
    ap.add_argument("--binary", default="build/fenestra")
    ap.add_argument("--norm-roi", help="region whose mean sets each renderer's brightness scale "
                    "(default: the whole image); use it where the renderers differ outside --roi")
    ap.add_argument("--table-only", action="store_true", help="reuse the renders already in --out")
    ap.add_argument("--integrator", default="ptracer", choices=("ptracer", "path"),
                    help="Mitsuba's light tracer (default) or its path tracer")
    ap.add_argument("--out", required=True, help="output folder")
    a = ap.parse_args()

    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    os.makedirs(a.out, exist_ok=True)
    seeds = seeds_of(a.seeds)
    fen = a.fenestra.split(",")
    filters = a.filters.split(",")

    if a.table_only:
        return table(a, mi, seeds, fen, filters)
    scenes = {}
    for f in filters:
        d = mitsuba_peer.scene_dict(mi, a.scene, a.width, 1, f, os.path.join(a.out, "meshes"))
        d["integrator"] = {"type": a.integrator, "max_depth": -1, "rr_depth": 5,
                           "hide_emitters": a.integrator == "ptracer"}
        scenes[f] = (d, mi.load_dict(d))
    # Calibrate Mitsuba's sample count to --seconds with a short render.
    d, sc = scenes[filters[0]]
    t0 = time.perf_counter()
    mi.render(sc, seed=10**6, spp=8)
    spp = max(1, int(round(8 * a.seconds / (time.perf_counter() - t0))))
    print(f"Mitsuba {mi.__version__} {a.integrator}: {spp} samples per pixel per render", flush=True)

    for s in seeds:
        for c in fen:
            exr = os.path.join(a.out, f"fen_{c.replace('+', '_').replace('=', '')}_{s}.exr")
            cmd = [a.binary, "render", a.scene, *fenestra_args(c), "--time", str(a.seconds),
                   "--width", str(a.width), "--seed", str(s), "--out", exr]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for f in filters:
            _, sc = scenes[f]
            t0 = time.perf_counter()
            img = mi.render(sc, seed=s, spp=spp)
            secs = time.perf_counter() - t0
            exr = os.path.join(a.out, f"mitsuba_{f}_{s}.exr")
            mi.Bitmap(img).write(exr)
            with open(exr[:-4] + ".json", "w") as fj:
                json.dump({"seconds": {"render": secs}, "paths": spp * a.width * img.shape[0],
                           "spp": spp, "mitsuba": mi.__version__}, fj)
        print(f"seed {s} done", flush=True)
    table(a, mi, seeds, fen, filters)


def region_of(roi):
    if not roi:
        return (slice(None), slice(None))
    x0, y0, x1, y1 = (int(v) for v in roi.split(","))
    return (slice(y0, y1), slice(x0, x1))


def table(a, mi, seeds, fen, filters):
    runs = {}  # label -> list of (image path, seconds, paths)
    for s in seeds:
        for c in fen:
            runs.setdefault("fenestra " + c, []).append(
                os.path.join(a.out, f"fen_{c.replace('+', '_').replace('=', '')}_{s}.exr"))
        for f in filters:
            runs.setdefault(f"Mitsuba {a.integrator}, " + f, []).append(
                os.path.join(a.out, f"mitsuba_{f}_{s}.exr"))

    region = region_of(a.roi)
    norm = region_of(a.norm_roi)
    rows = []
    for name, exrs in runs.items():
        full = np.stack([luminance(mi, p) for p in exrs])
        scale = float(full[(slice(None),) + norm].mean())
        imgs = full[(slice(None),) + region]
        js = [json.load(open(p[:-4] + ".json")) for p in exrs]
        secs = float(np.mean([j["seconds"]["render"] for j in js]))
        paths = float(np.mean([j["paths"] for j in js]))
        var = float(imgs.var(axis=0, ddof=1).mean())
        mean = float(imgs.mean())
        se = float(imgs.mean(axis=(1, 2)).std(ddof=1) / np.sqrt(len(exrs)))
        rows.append((name, mean, se, var ** 0.5, secs, paths / secs, scale * scale / (var * secs)))
    base = rows[0][6]
    lines = [f"{a.scene}, region {a.roi or 'whole image'}, brightness scale from "
             f"{a.norm_roi or 'the whole image'}, {len(seeds)} seeds ({a.seeds}), "
             f"{a.seconds:g} s each, {a.width} px wide",
             "",
             "| renderer | mean ± s.e. (cd/m²) | per-pixel noise of one render | render s | Mpaths/s | efficiency |",
             "|---|---|---|---|---|---|"]
    for name, mean, se, noise, secs, pps, eff in rows:
        lines.append(f"| {name} | {mean:.4g} ± {se:.2g} | {noise:.4g} | {secs:.2f} | "
                     f"{pps / 1e6:.2f} | {eff / base:.2f}× |")
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
