#!/usr/bin/env python3
"""house_results.py — regenerates docs/results/house.md: the paper's Table 2 (the House) and the
scenes where portal emission fails, each method rendered for equal time against a long reference
(scripts/compare.py does the rendering, the CSV and the charts; this script runs it per scene and
writes the page, with the charts copied to docs/results/house/).

Run from the repository root after building (`scripts/setup.sh`), on an otherwise idle machine:

    python3 scripts/house_results.py [--seconds 60] [--reference-seconds 600] [--width 160]
                                     [--scenes house,house_snow,courtyard] [--table-only]

--table-only rewrites the page from the summaries of an earlier run (out/compare/<scene>/).
The references are cached (out/compare/cache/), so a rerun with the same settings reuses them.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

METHODS = "uniform,portal,adaptive,adaptive/portal"
PAPER = {"uniform": (266, 1425), "adaptive": (203, 335)}  # Table 2: mean, RMS error (cd/m^2)
ABOUT = {
    "house": "the paper's House (`scenes/house.gltf`): upstairs north-west room, 16 marked windows, "
             "a grey ground (albedo 0.2)",
    "house_snow": "the same house under snow (`scenes/house_snow.gltf`, ground albedo 0.9): much of "
                  "the light enters off the ground",
    "courtyard": "a room facing a sunlit neighbouring wall across a courtyard (`scenes/courtyard.gltf`): "
                 "lit mostly by reflection from outside",
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--reference-seconds", type=float, default=600.0)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--scenes", default="house,house_snow,courtyard")
    ap.add_argument("--table-only", action="store_true")
    a = ap.parse_args()
    scenes = [s for s in a.scenes.split(",") if s]
    docs = os.path.join("docs", "results")
    charts = os.path.join(docs, "house")
    os.makedirs(charts, exist_ok=True)
    results = {}
    for name in scenes:
        out = os.path.join("out", "compare", name)
        if not a.table_only:
            cmd = [sys.executable, "scripts/compare.py", os.path.join("scenes", name + ".gltf"), "--methods", METHODS,
                   "--time", str(a.seconds), "--reference-time", str(a.reference_seconds), "--width",
                   str(a.width), "--out", out]
            print("$", " ".join(cmd), flush=True)
            subprocess.run(cmd, check=True)
        with open(os.path.join(out, "summary.json")) as f:
            results[name] = json.load(f)
        for png in ("error_vs_time.png", "efficiency.png", "strip.png"):
            shutil.copy(os.path.join(out, png), os.path.join(charts, "%s_%s" % (name, png)))

    lines = ["# The House, and where portal emission fails: equal time\n"]
    lines.append("Each method renders for the same wall time (%g s, %d px wide, seed 1) and is compared with a "
                 "long render of adaptive emission (%g s, seed 1000), made once and cached. Statistics over the "
                 "whole image, luminance in cd/m². Regenerate: `python3 scripts/house_results.py --seconds %g "
                 "--reference-seconds %g --width %d` (after `scripts/setup.sh`; about %d minutes on 2 cores).\n"
                 % (a.seconds, a.width, a.reference_seconds, a.seconds, a.reference_seconds, a.width,
                    round(len(scenes) * (4 * a.seconds + a.reference_seconds) / 60)))
    lines.append("Columns: *mean ± s.e.* the image's mean and its standard error from the 16 batches; *bias* "
                 "that mean minus the reference's, in combined standard errors (**biased** beyond 4 σ); *RMS* "
                 "the pixels' spread around the mean (the paper's \"RMS\", which counts real variation as well as "
                 "noise); *noise* each pixel's standard error from its batches, root mean square over the image "
                 "(an estimate of the RMSE without a reference); *RMSE* against the reference (its own noise "
                 "included); *efficiency* 1 / (RMSE² × seconds), the best unbiased method = 1.\n")
    for name in scenes:
        r = results[name]
        ref = r.get("reference_json", {})
        lines.append("## %s\n" % name)
        lines.append(ABOUT.get(name, name) + ".\n")
        lines.append("| method | paths | paths/s | mean ± s.e. | bias | RMS | noise | RMSE | noise vs uniform | "
                     "efficiency |")
        lines.append("|---|---|---|---|---|---|---|---|---|---|")
        u = next((m for m in r["methods"] if m["method"] == "uniform"), None)
        for m in r["methods"]:
            lines.append("| %s | %.0fM | %.2fM | %.4g ± %.2g | %+.1f σ%s | %.4g | %.3g | %.3g | %s | %.2f%s |" % (
                m["method"], m["paths"] / 1e6, m.get("paths_per_second", 0.0) / 1e6, m["mean_cd_m2"],
                m["mean_std_err_cd_m2"], m["bias_sigmas"], " **biased**" if m["biased"] else "",
                m.get("rms_cd_m2", float("nan")), m["noise_cd_m2"], m["rmse_cd_m2"],
                "%.2fx" % (u["noise_cd_m2"] / m["noise_cd_m2"]) if u else "",
                m["relative_efficiency"], " (biased)" if m["biased"] else ""))
        if name == "house":
            lines.append("| *paper: no optimisation* | | | *266* | | *1425* | | | *1x* | |")
            lines.append("| *paper: adaptive* | | | *203* | | *335* | | | *4.25x* | |")
        lines.append("")
        if ref:
            lines.append("Reference: %s, %.0f s, %.0fM paths, mean %.4g cd/m², noise %.3g per pixel.\n" % (
                ref.get("method"), (ref.get("seconds") or {}).get("render", 0.0), (ref.get("paths") or 0) / 1e6,
                ref.get("mean_luminance_cd_m2") or 0.0, ref.get("noise_std_err_cd_m2") or 0.0))
        lines.append("![error against time](house/%s_error_vs_time.png) ![efficiency](house/%s_efficiency.png)\n"
                     % (name, name))
        lines.append("![images and error maps](house/%s_strip.png)\n" % name)
    any_ref = next(iter(results.values())).get("reference_json", {})
    lines.append("Machine: %s.\n" % (any_ref.get("device") or "see the JSON reports"))
    with open(os.path.join(docs, "house_data.md"), "w") as f:
        f.write("\n".join(lines))
    print("wrote docs/results/house_data.md")


if __name__ == "__main__":
    sys.exit(main())
