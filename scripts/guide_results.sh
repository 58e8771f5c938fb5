#!/bin/sh
# guide_results.sh — the first-bounce guide (--adaptive-guide on) against adaptive without it, the
# same seed in turn, at equal time, on the scenes where light arrives off outside surfaces and on
# the three termination scenes. One line per render; docs/results/guide.md tabulates them.
# Usage: scripts/guide_results.sh [SEEDS] [OUT]   (default seeds "1 2 3", out out/guide)
set -eu
seeds=${1:-"1 2 3"}
out=${2:-out/guide}
mkdir -p "$out"
for s in $seeds; do
  for sc in "courtyard --width 160 --time 20" "house --width 160 --time 20" "house_snow --width 160 --time 20" \
            "room --width 320 --time 10" "bay_window --width 320 --time 10" "inner_room --width 320 --time 10 --roi 140,80,260,180"; do
    set -- $sc; name=$1; shift
    for g in off on; do
      build/fenestra render "scenes/$name.gltf" --method adaptive --adaptive-guide $g --seed "$s" "$@" \
        --out "$out/${name}_guide_${g}_$s.exr" --no-progress >/dev/null
      python3 - "$out/${name}_guide_${g}_$s.json" "$name" "$s" "$g" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
g = j["emission"].get("guide", {})
print(sys.argv[2], sys.argv[3], sys.argv[4], "mean %.4g" % j["mean_luminance_cd_m2"],
      "noise %.4g" % j["noise_std_err_cd_m2"], "top1 %.2f" % j["noise_top1_share"],
      "Mpaths/s %.3f" % (j["paths_per_second"] / 1e6), "rays/path %.2f" % (j["rays_per_second"] / j["paths_per_second"]),
      "learned %s/%s" % (g.get("learned_slots", "-"), g.get("candidate_slots", "-")))
PY
    done
  done
done
