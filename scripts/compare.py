#!/usr/bin/env python3
"""compare.py — emission methods against each other on one scene, for equal wall time: error along the
way against a reference, a CSV, and charts (DESIGN.md §5: every claim charted as error against time).

    python3 scripts/compare.py SCENE.gltf --methods uniform,portal,adaptive --time 60 [--reference R.exr]
                               [--roi x0,y0,x1,y1] [--width W] [--seed S] [--out DIR] [--camera NAME]
                               [--reference-method adaptive] [--reference-time SECONDS]
                               [--region NAME=x0,y0,x1,y1 ...]

A method is METHOD[/BASE][@PORTALS][+OPTION=VALUE...]: `portal@gap` is portal emission through the
node `gap`, `adaptive/portal` adaptive emission over the scene's portals, `adaptive/portal@gap` over
the gap, `adaptive+adaptive-defensive=0.3` adaptive with `--adaptive-defensive 0.3`.

Without --reference, a long render of an unbiased method (--reference-method, default adaptive,
--reference-time, default 10 x --time, seed 1000) is made once and cached in out/compare/cache/,
keyed by the scene's bytes and the settings.

Writes to --out (default out/compare/<scene name>/):
  compare.csv          method, batches, paths, seconds, mean, noise, rmse, bias per batch
  summary.md, .json    per method: paths, mean ± s.e., bias against the reference (flagged when it
                       exceeds 4 combined standard errors), noise, the noisiest 1 % of pixels' share
                       of it (fireflies), RMSE, efficiency 1 / (RMSE² s)
  error_vs_time.png    RMSE (solid) and the noise estimate (dashed) against seconds, log-log
  efficiency.png       efficiency, the best unbiased method = 1; biased methods hatched
  strip.png            each method's image (preview) and its error map against the reference
  regions.md           with --region: each named region's mean, bias (in combined standard errors) and
                       RMSE per method -- a method can be right on the whole image and wrong on a wall

Needs matplotlib and numpy (Debian: python3-matplotlib, installed by scripts/setup.sh).
"""
import argparse
import csv
import hashlib
import json
import math
import os
import subprocess
import sys


def parse_method(spec):
    """METHOD[/BASE][@PORTALS][+OPTION=VALUE...] -> (label, fenestra arguments)."""
    spec_main, *options = spec.split("+")
    extra = []
    for o in options:
        k, eq, v = o.partition("=")
        if not k or not eq:
            sys.exit("compare.py: --methods: '%s': an option is +NAME=VALUE" % spec)
        extra += ["--" + k, v]
    rest, _, portals = spec_main.partition("@")
    method, _, base = rest.partition("/")
    if method not in ("uniform", "portal", "adaptive"):
        sys.exit("compare.py: --methods: '%s': expected uniform, portal or adaptive" % spec)
    args = ["--method", method]
    if base:
        if method != "adaptive" or base not in ("uniform", "portal"):
            sys.exit("compare.py: --methods: '%s': a base is adaptive/uniform or adaptive/portal" % spec)
        args += ["--base", base]
    if portals:
        args += ["--portals", portals]
    return spec, args + extra


def run(cmd):
    print("$", " ".join(cmd), flush=True)
    r = subprocess.run(cmd)
    if r.returncode != 0:
        sys.exit("compare.py: the render failed (exit %d)" % r.returncode)


def load(path):
    with open(path) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--methods", default="uniform,portal,adaptive")
    ap.add_argument("--time", type=float, required=True, help="seconds per method")
    ap.add_argument("--reference")
    ap.add_argument("--reference-method", default="adaptive")
    ap.add_argument("--reference-time", type=float)
    ap.add_argument("--roi", default="")
    ap.add_argument("--width", type=int, default=0)
    ap.add_argument("--camera", default="")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out")
    ap.add_argument("--fenestra", default="build/fenestra")
    ap.add_argument("--region", action="append", default=[], help="NAME=x0,y0,x1,y1, repeatable")
    a = ap.parse_args()

    name = os.path.splitext(os.path.basename(a.scene))[0]
    out = a.out or os.path.join("out", "compare", name)
    os.makedirs(out, exist_ok=True)
    common = ["--no-progress"]
    if a.width:
        common += ["--width", str(a.width)]
    if a.camera:
        common += ["--camera", a.camera]
    if a.roi:
        common += ["--roi", a.roi]

    # The reference: given, or made once and cached.
    ref = a.reference
    if not ref:
        ref_time = a.reference_time or 10.0 * a.time
        with open(a.scene, "rb") as f:
            key = hashlib.sha256(f.read() + json.dumps([common, a.reference_method, ref_time]).encode()).hexdigest()[:16]
        cache = os.path.join("out", "compare", "cache")
        os.makedirs(cache, exist_ok=True)
        ref = os.path.join(cache, "%s-%s.exr" % (name, key))
        if not os.path.exists(ref):
            _, margs = parse_method(a.reference_method)
            run([a.fenestra, "render", a.scene, "--out", ref, "--time", str(ref_time), "--seed", "1000"]
                + margs + common + sum((["--region", g] for g in a.region), []))
    ref_json = os.path.splitext(ref)[0] + ".json"
    ref_se = load(ref_json)["mean_std_err_cd_m2"] if os.path.exists(ref_json) else 0.0

    # The methods, equal time.
    results = []
    for spec in [m for m in a.methods.split(",") if m]:
        label, margs = parse_method(spec)
        path = os.path.join(out, label.replace("/", "_over_").replace("@", "_at_").replace("+", "_").replace("=", "") + ".exr")
        run([a.fenestra, "render", a.scene, "--out", path, "--time", str(a.time), "--seed", str(a.seed),
             "--reference", ref] + margs + common + sum((["--region", g] for g in a.region), []))
        results.append((label, path, load(os.path.splitext(path)[0] + ".json")))

    with open(os.path.join(out, "compare.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["method", "batches", "paths", "seconds", "mean_cd_m2", "noise_cd_m2", "rmse_cd_m2", "bias_cd_m2"])
        for label, _, j in results:
            for p in j["progress"]:
                w.writerow([label, p["batches"], p["paths"], "%.4f" % p["seconds"], "%.6g" % p["mean_luminance_cd_m2"],
                            "%.6g" % p["noise_std_err_cd_m2"] if "noise_std_err_cd_m2" in p else "",
                            "%.6g" % p["rmse_cd_m2"], "%.6g" % p["bias_cd_m2"]])

    # Summary: bias flagged beyond 4 combined standard errors; efficiency against the best unbiased.
    summary = []
    for label, path, j in results:
        se = math.hypot(j["mean_std_err_cd_m2"], ref_se)
        seconds = j["seconds"]["render"] + j["seconds"]["calibration"]
        summary.append({
            "method": label, "paths": j["paths"], "seconds": seconds,
            "mean_cd_m2": j["mean_luminance_cd_m2"], "mean_std_err_cd_m2": j["mean_std_err_cd_m2"],
            "bias_cd_m2": j["bias_cd_m2"], "bias_sigmas": j["bias_cd_m2"] / se if se > 0 else 0.0,
            "biased": abs(j["bias_cd_m2"]) > 4.0 * se,
            "noise_cd_m2": j["noise_std_err_cd_m2"], "rmse_cd_m2": j["rmse_cd_m2"],
            "noise_top1_share": j.get("noise_top1_share"),
            "rms_cd_m2": j["rms_luminance_cd_m2"], "paths_per_second": j["paths_per_second"],
            "efficiency": 1.0 / (j["rmse_cd_m2"] ** 2 * seconds),
            "png": os.path.splitext(path)[0] + ".png", "error_png": os.path.splitext(path)[0] + ".error.png"})
    unbiased = [s["efficiency"] for s in summary if not s["biased"]] or [s["efficiency"] for s in summary]
    best = max(unbiased)
    for s in summary:
        s["relative_efficiency"] = s["efficiency"] / best
    with open(os.path.join(out, "summary.json"), "w") as f:
        ref_j = load(ref_json) if os.path.exists(ref_json) else {}
        json.dump({"scene": a.scene, "reference": ref, "reference_mean_std_err_cd_m2": ref_se, "roi": a.roi,
                   "reference_json": {k: ref_j.get(k) for k in ("method", "paths", "seconds", "seed",
                                                                 "mean_luminance_cd_m2", "noise_std_err_cd_m2",
                                                                 "device", "width", "height")},
                   "seconds_per_method": a.time, "methods": summary}, f, indent=1)
    lines = ["| method | paths | mean ± s.e. (cd/m²) | bias vs reference | noise | noisiest 1 %'s share | RMSE | efficiency (best = 1) |",
             "|---|---|---|---|---|---|---|---|"]
    for s in summary:
        top = s["noise_top1_share"]
        lines.append("| %s | %.3gM | %.4g ± %.2g | %+.3g (%+.1f σ)%s | %.3g | %s | %.3g | %.2f%s |" % (
            s["method"], s["paths"] / 1e6, s["mean_cd_m2"], s["mean_std_err_cd_m2"], s["bias_cd_m2"],
            s["bias_sigmas"], " **biased**" if s["biased"] else "", s["noise_cd_m2"],
            "%.0f %%" % (100 * top) if top is not None else "–", s["rmse_cd_m2"],
            s["relative_efficiency"], " (biased)" if s["biased"] else ""))
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if a.region:
        # The reference's own region errors when it was rendered with the regions (else 0).
        ref_regions = load(ref_json).get("regions", {}) if os.path.exists(ref_json) else {}
        rl = ["| region | reference mean (cd/m²) | " + " | ".join("%s: mean, bias, RMSE" % s["method"] for s in summary) + " |",
              "|---|---|" + "---|" * len(summary)]
        for g in a.region:
            gname = g.partition("=")[0]
            cells, ref_mean = [], None
            for _, _, j in results:
                r = j["regions"][gname]
                ref_mean = r["reference_mean_luminance_cd_m2"]
                se = math.hypot(r["mean_std_err_cd_m2"], ref_regions.get(gname, {}).get("mean_std_err_cd_m2", 0.0))
                sig = r["bias_cd_m2"] / se if se > 0 else 0.0
                cells.append("%.4g, %+.1f %% (%+.1f σ)%s, %.3g" % (
                    r["mean_luminance_cd_m2"], 100.0 * r["bias_cd_m2"] / ref_mean if ref_mean else 0.0, sig,
                    " **biased**" if abs(sig) > 4.0 else "", r["rmse_cd_m2"]))
            rl.append("| %s (%s) | %.4g | %s |" % (gname, g.partition("=")[2], ref_mean, " | ".join(cells)))
        with open(os.path.join(out, "regions.md"), "w") as f:
            f.write("\n".join(rl) + "\n")
        print("\n".join(rl))
    charts(out, results, summary)


def charts(out, results, summary):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.image as mpimg

    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, ((label, _, j), s) in enumerate(zip(results, summary)):
        c = colours[k % len(colours)]
        t = [p["seconds"] for p in j["progress"]]
        ax.loglog(t, [p["rmse_cd_m2"] for p in j["progress"]], "-o", color=c, ms=3,
                  label=label + (" (biased)" if s["biased"] else ""))
        tn = [p["seconds"] for p in j["progress"] if "noise_std_err_cd_m2" in p]
        ax.loglog(tn, [p["noise_std_err_cd_m2"] for p in j["progress"] if "noise_std_err_cd_m2" in p], "--",
                  color=c, alpha=0.6)
    ax.set_xlabel("seconds")
    ax.set_ylabel("error (cd/m²): RMSE vs reference —, noise estimate - -", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    # below the axes: a method's label may be long (its options), and must not hide a curve
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), fontsize=8, frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "error_vs_time.png"), dpi=100, bbox_inches="tight")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 3.5))
    names = [s["method"].replace("+", "\n+") for s in summary]  # one option a line
    bars = ax.bar(names, [s["relative_efficiency"] for s in summary],
                  color=[colours[k % len(colours)] for k in range(len(summary))])
    for b, s in zip(bars, summary):
        if s["biased"]:
            b.set_hatch("//")
            b.set_alpha(0.5)
            ax.annotate("biased", (b.get_x() + b.get_width() / 2, b.get_height()), ha="center", va="bottom")
    ax.set_ylabel("efficiency 1/(RMSE² × s), best unbiased = 1", fontsize=8)
    ax.set_yscale("log")
    ax.tick_params(axis="x", labelsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "efficiency.png"), dpi=100, bbox_inches="tight")
    plt.close(fig)

    n = len(summary)
    fig, axes = plt.subplots(2, n, figsize=(3.2 * n, 5.0), squeeze=False)
    for k, s in enumerate(summary):
        axes[0][k].imshow(mpimg.imread(s["png"]))
        axes[0][k].set_title(s["method"] + ("\n(biased)" if s["biased"] else ""), fontsize=9)
        if os.path.exists(s["error_png"]):
            axes[1][k].imshow(mpimg.imread(s["error_png"]), cmap="magma", vmin=0.0, vmax=1.0)
        axes[1][k].set_title("|error| / mean: 1e-3 .. 1", fontsize=8)
        for r in range(2):
            axes[r][k].axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "strip.png"), dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
