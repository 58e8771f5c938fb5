#!/usr/bin/env bash
# fuzz.sh — builds the scene loader's libFuzzer target (tests/fuzz/, clang-14 with AddressSanitizer
# and UndefinedBehaviorSanitizer) in build-fuzz/, apart from build/, and runs it on the committed
# seeds (tests/fuzz/corpus/, never written to) plus a working corpus in build-fuzz/corpus/.
#
#   scripts/fuzz.sh                    run for 60 seconds
#   scripts/fuzz.sh --time 600         run for 600 seconds
#   scripts/fuzz.sh --runs 1000000     run exactly that many inputs
#   scripts/fuzz.sh --runs 1000 -- -seed=7   anything after -- goes to libFuzzer
#
# A crash, a sanitizer report, a leak or an exception other than fen::Error stops the run and
# leaves the input in build-fuzz/ (crash-*, leak-*, timeout-*); rerun one with
#   build-fuzz/tests/fuzz/fuzz_scene_load FILE
# Needs clang-14 and libclang-rt-14-dev (Debian 12); not part of setup.sh or CI.
set -euo pipefail
cd "$(dirname "$0")/.."

limit=(-max_total_time=60)
while (($#)); do
  case "$1" in
    --time) limit=(-max_total_time="$2"); shift 2 ;;
    --runs) limit=(-runs="$2"); shift 2 ;;
    --) shift; break ;;
    *) echo "fuzz.sh: unknown argument '$1' (--time SECONDS, --runs N, -- libFuzzer options)" >&2; exit 2 ;;
  esac
done

for p in clang-14 libclang-rt-14-dev; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    echo "fuzz.sh: needs the Debian package $p (apt-get install clang-14 libclang-rt-14-dev)" >&2
    exit 1
  fi
done

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  -DFEN_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz --target fuzz_scene_load -j2
mkdir -p build-fuzz/corpus
cd build-fuzz
# -rss_limit_mb: a scene that makes the loader take gigabytes is a finding, as in the DAG case.
exec tests/fuzz/fuzz_scene_load -dict=../tests/fuzz/gltf.dict -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 "${limit[@]}" "$@" corpus ../tests/fuzz/corpus
