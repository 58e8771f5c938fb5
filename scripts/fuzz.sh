#!/usr/bin/env bash
# fuzz.sh — builds one of the libFuzzer targets (tests/fuzz/, clang-14 with AddressSanitizer and
# UndefinedBehaviorSanitizer) in build-fuzz/, apart from build/, and runs it on its committed seeds
# (never written to) plus a working corpus in build-fuzz/: --target scene (the scene loader, the
# default; tests/fuzz/corpus/), options (the render command's options and names;
# tests/fuzz/corpus_options/), checkpoint (a checkpoint to resume; tests/fuzz/corpus_checkpoint/)
# or weather (an EPW weather file, its hours' sun and sky; tests/fuzz/corpus_weather/).
#
#   scripts/fuzz.sh                    run for 60 seconds
#   scripts/fuzz.sh --time 600         run for 600 seconds
#   scripts/fuzz.sh --runs 1000000     run exactly that many inputs
#   scripts/fuzz.sh --runs 1000 -- -seed=7   anything after -- goes to libFuzzer
#   scripts/fuzz.sh --target options --runs 1000000
#
# A crash, a sanitizer report, a leak or an exception other than fen::Error stops the run and
# leaves the input in build-fuzz/ (crash-*, leak-*, timeout-*); rerun one with
#   build-fuzz/tests/fuzz/fuzz_scene_load FILE
# Needs clang-14 and libclang-rt-14-dev (Debian 12); not part of setup.sh or CI.
set -euo pipefail
cd "$(dirname "$0")/.."

limit=(-max_total_time=60)
target=scene
while (($#)); do
  case "$1" in
    --time) limit=(-max_total_time="$2"); shift 2 ;;
    --runs) limit=(-runs="$2"); shift 2 ;;
    --target) target="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "fuzz.sh: unknown argument '$1' (--target scene|options|checkpoint|weather, --time SECONDS, --runs N, -- libFuzzer options)" >&2; exit 2 ;;
  esac
done
case "$target" in
  scene) binary=fuzz_scene_load; seeds=corpus; extra=(-dict=../tests/fuzz/gltf.dict) ;;
  options) binary=fuzz_render_options; seeds=corpus_options; extra=() ;;
  checkpoint) binary=fuzz_checkpoint; seeds=corpus_checkpoint; extra=() ;;
  weather) binary=fuzz_weather; seeds=corpus_weather; extra=() ;;
  *) echo "fuzz.sh: --target is scene, options, checkpoint or weather, not '$target'" >&2; exit 2 ;;
esac

for p in clang-14 libclang-rt-14-dev; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    echo "fuzz.sh: needs the Debian package $p (apt-get install clang-14 libclang-rt-14-dev)" >&2
    exit 1
  fi
done

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  -DFEN_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz --target "$binary" -j2
# The scene target keeps its working corpus where it always has (build-fuzz/corpus/).
work=corpus
[ "$target" = scene ] || work="corpus-$target"
mkdir -p "build-fuzz/$work"
cd build-fuzz
# -rss_limit_mb: an input that makes fenestra take gigabytes is a finding, as in the DAG case.
exec "tests/fuzz/$binary" "${extra[@]}" -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 "${limit[@]}" "$@" "$work" "../tests/fuzz/$seeds"
