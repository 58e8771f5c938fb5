#!/bin/bash
# guide_resolution_study.sh — the guide whose resolution follows the light (docs/results/guiding.md,
# "A guide whose resolution follows the light") against the fixed 8 x 8 guide over hashed R/4 voxels
# it replaced: two builds, adaptive emission with each one's default guide, the same seed in turn at
# equal time; uniform on the house beside them. Prints the summary the page tabulates.
#
#   scripts/guide_resolution_study.sh OLD_BINARY NEW_BINARY OUT_DIR
#
# OLD_BINARY is a build of edbfc72 (git worktree add /tmp/old edbfc72 && cmake -S /tmp/old -B
# /tmp/old/build -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/old/build -j2). About 25 minutes on
# 2 cores; nothing else may run meanwhile.
set -eu
old=$1; new=$2; out=$3
mkdir -p "$out"
run() { # binary method scene seed tag extra...
  local bin=$1 m=$2 sc=$3 s=$4 tag=$5; shift 5
  "$bin" render "scenes/$sc.gltf" --method "$m" --seed "$s" "$@" --out "$out/${sc}_${tag}_$s.exr" --no-progress \
    >/dev/null 2>&1
}
for s in 1 2 3 4 5 6; do
  for sc in house house_snow courtyard; do
    run "$old" adaptive "$sc" "$s" old --width 160 --time 20
    run "$new" adaptive "$sc" "$s" new --width 160 --time 20
  done
  run "$new" uniform house "$s" uninew --width 160 --time 20
  if [ "$s" -le 2 ]; then run "$old" uniform house "$s" uniold --width 160 --time 20; fi
  if [ "$s" -le 3 ]; then
    for sc in room bay_window; do
      run "$old" adaptive "$sc" "$s" old --width 320 --time 10
      run "$new" adaptive "$sc" "$s" new --width 320 --time 10
    done
    run "$old" adaptive inner_room "$s" old --width 320 --time 10 --roi 140,80,260,180
    run "$new" adaptive inner_room "$s" new --width 320 --time 10 --roi 140,80,260,180
  fi
done
python3 - "$out" <<'PY'
import collections, glob, json, statistics, sys
R = collections.defaultdict(dict)
for f in glob.glob(sys.argv[1] + "/*.json"):
    scene, tag, seed = f.split("/")[-1][:-5].rsplit("_", 2)
    R[(scene, int(seed))][tag] = json.load(open(f))
noise = lambda j: j["noise_std_err_cd_m2"]
for scene in ["house", "house_snow", "courtyard", "room", "bay_window", "inner_room"]:
    eff, speed = [], []
    for (sc, s), r in sorted(R.items()):
        if sc != scene or "old" not in r or "new" not in r:
            continue
        o, n = r["old"], r["new"]
        eff.append(noise(o) ** 2 * o["seconds"]["render"] / (noise(n) ** 2 * n["seconds"]["render"]))
        speed.append(n["paths_per_second"] / o["paths_per_second"])
        g = n["emission"]["guide"]
        print(f"  {scene} seed {s}: noise {noise(o):.4g} -> {noise(n):.4g}, mean {o['mean_luminance_cd_m2']:.5g} -> "
              f"{n['mean_luminance_cd_m2']:.5g} (s.e. {o['mean_std_err_cd_m2']:.3g}, {n['mean_std_err_cd_m2']:.3g}), "
              f"top 1 % {o['noise_top1_share']:.2f} -> {n['noise_top1_share']:.2f}, learned slots "
              f"{o['emission']['guide']['learned_slots']} -> {g['learned_slots']}, spatial leaves {g['spatial_leaves']}, "
              f"direction leaves {g['leaves']}, memory {g['memory_used_bytes'] / 2**20:.1f} MiB, learning {g['learn_seconds']:.2f} s")
    if eff:
        print(f"{scene}: efficiency new/old {[round(x, 2) for x in eff]}, median {statistics.median(eff):.2f}; "
              f"paths/s new/old median {statistics.median(speed):.3f}")
for tag in ["old", "new"]:
    q = [noise(R[("house", s)]["uninew"]) / noise(R[("house", s)][tag]) for s in range(1, 7)
         if tag in R.get(("house", s), {}) and "uninew" in R[("house", s)]]
    if q:
        print(f"house, uniform noise / adaptive ({tag}) noise: {[round(x, 2) for x in q]}, median {statistics.median(q):.2f}")
for s in (1, 2):
    r = R.get(("house", s), {})
    if "uniold" in r and "uninew" in r:
        print(f"house uniform seed {s}: paths/s {r['uniold']['paths_per_second'] / 1e6:.2f} M -> "
              f"{r['uninew']['paths_per_second'] / 1e6:.2f} M")
PY
