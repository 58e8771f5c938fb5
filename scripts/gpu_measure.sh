#!/usr/bin/env bash
# gpu_measure.sh OUTDIR [DEVICE] — the GPU measurements of docs/results/gpu.md, as one script.
# Expects built binaries (scripts/setup.sh): build/fenestra (Release). Writes into OUTDIR:
#   devices.txt        fenestra devices
#   guide.txt          the default (adaptive, guided) against uniform at equal time on the house, the
#                      snow house and the courtyard, 3 seeds; and where a default render's time goes
#                      (the kernels on the device, the learning on the host)
#   bench_room.json    traversal, procedural room (110k triangles), every BVH layout, vs Embree
#   bench_spheres.json traversal, spheres (1.09M triangles), every BVH layout, vs Embree
#   render_bench.txt   bench --render: render rays/s over closest-hit traversal, uniform and portal
#   sweep.txt          pool size, BVH layout and kernel mode for a render of scenes/room.gltf
#   team.txt           two MPI ranks on the device against one process: the same image bytes (the
#                      team's sums on NVIDIA's driver), and the reductions' seconds at 1920 px
# Every step has its own time limit, so one that hangs or fails leaves the rest measured.
set -u
out=${1:?usage: gpu_measure.sh OUTDIR [DEVICE]}
dev=${2:-nvidia}
mkdir -p "$out"
fen=${FEN_BIN:-build/fenestra}
step() { local limit=$1; shift; echo "+ $*" >&2; timeout "$limit" "$@"; echo "exit $?" >&2; }

step 20 "$fen" devices > "$out/devices.txt" 2>&1
{
    # docs/results/guiding.md, "On a GPU": a device this fast waits for the host's learning
    step 240 python3 scripts/window_study.py --fenestra "$fen" --scenes house,house_snow,courtyard \
        --seeds 1,2,3 --variants uniform,default --variant uniform '--method uniform' --baseline uniform \
        --width 160 --time "${FEN_STUDY_SECONDS:-6}" --out "$out/study_tmp" --common "--device $dev" 2>&1 |
        grep -v '^\s*$'
    step 40 "$fen" render scenes/house.gltf --device "$dev" --width 160 --time "${FEN_STUDY_SECONDS:-6}" \
        --no-progress --out "$out/house_tmp.exr" 2>&1 | tail -1
    python3 - "$out/house_tmp.json" <<'PY' || cat "$out/house_tmp.json"
import json, sys
j = json.load(open(sys.argv[1]))
e = j["emission"]; g = e["guide"]
print("house, default: paths %d in %d batches, render %.2f s; the kernels on the device %.2f s %s"
      % (j["paths"], j["batches"], j["seconds"]["render"],
         sum(v["device_seconds"] for v in j["kernels"].values()),
         {k: round(v["device_seconds"], 3) for k, v in j["kernels"].items()}))
print("    learning on the host: emission %.2f s, of which the guide %.2f s in %d passes (the last %.1f ms, %d leaves in %d slots)"
      % (e["learn_seconds"], g["learn_seconds"], e["passes"], 1e3 * g["learn_seconds_last_pass"], g["leaves"], g["slots"]))
PY
    rm -rf "$out/study_tmp" "$out"/house_tmp.*
} > "$out/guide.txt" 2>&1
step 60 "$fen" bench --device "$dev" --layout all --rays 16777216 --runs 5 --json \
    > "$out/bench_room.json" 2> "$out/bench_room.err"
step 100 "$fen" bench spheres --device "$dev" --layout all --rays 16777216 --runs 3 --json \
    > "$out/bench_spheres.json" 2> "$out/bench_spheres.err"
{
    for args in "room --render-method uniform" "scenes/room.gltf --render-method uniform" \
                "scenes/room.gltf --render-method portal" "scenes/inner_room.gltf --render-method uniform" \
                "scenes/inner_room.gltf --render-method portal"; do
        echo "== bench $args"
        # shellcheck disable=SC2086
        step 45 "$fen" bench $args --device "$dev" --no-embree --render --render-time 5 --runs 3 \
            --rays 16777216 2>&1 | grep -v '^\s*$'
    done
} > "$out/render_bench.txt" 2>&1
{
    run() {
        local name=$1; shift
        echo "== $name: $*"
        step 30 "$fen" render scenes/room.gltf --out "$out/sweep_tmp.exr" --time 5 --device "$dev" \
            --no-progress "$@" 2>&1 | tail -3
        python3 - "$out/sweep_tmp.json" <<'PY' || cat "$out/sweep_tmp.json"
import json, sys
j = json.load(open(sys.argv[1]))
eff = 1.0 / (j["noise_std_err_cd_m2"] ** 2 * j["seconds"]["render"])
print("    paths %d  seconds %.2f  Mrays/s %.1f  Mpaths/s %.2f  kernels %s  layout %s  mean %.1f  noise %.3g  1/(noise^2 s) %.3g"
      % (j["paths"], j["seconds"]["render"], j["rays_per_second"] * 1e-6, j["paths_per_second"] * 1e-6,
         j["kernel_mode"], j["bvh_layout"], j["mean_luminance_cd_m2"], j["noise_std_err_cd_m2"], eff))
print("    kernel build s %.2f, device seconds:" % j["seconds"]["kernel_build"], {k: round(v["device_seconds"], 3) for k, v in j["kernels"].items()})
PY
    }
    for p in 18 19 20 21 22 23; do run "pool 2^$p bvh2" --method uniform --pool $((1 << p)) --layout bvh2; done
    for l in bvh4 bvh8; do run "pool 2^21 $l" --method uniform --pool $((1 << 21)) --layout $l; done
    run "fused kernel" --method uniform --kernels fused
    run "adaptive, the default method" --method adaptive
    rm -f "$out"/sweep_tmp.*
} > "$out/sweep.txt" 2>&1
if ! command -v mpirun > /dev/null; then
    echo "no mpirun on this machine: the team's step is not measured" > "$out/team.txt"
else {
    # Both ranks on the one device: what is checked is that the team's kernels (team_sums.cl) sum
    # exactly on this driver, and what a reduction of a 1920 px film costs where the device is fast.
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    for m in uniform adaptive; do
        args=(render scenes/room.gltf --device "$dev" --method "$m" --width 1920 --paths 100000000 --batches 8
              --no-progress)
        step 120 "$fen" "${args[@]}" --out "$out/team_one.exr" 2>&1 | tail -1
        step 120 mpirun --oversubscribe -np 2 "$fen" "${args[@]}" --out "$out/team_two.exr" 2>&1 | tail -1
        if cmp -s "$out/team_one.exr" "$out/team_two.exr"; then echo "== $m: same bytes"; else echo "== $m: DIFFERENT"; fi
        python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print("   ", j.get("team"), "render s", j["seconds"]["render"])' \
            "$out/team_two.json"
    done
    rm -f "$out"/team_one.* "$out"/team_two.*
} > "$out/team.txt" 2>&1
fi
