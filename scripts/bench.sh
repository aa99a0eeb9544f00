#!/usr/bin/env bash
# Builds and runs raykit's CPU benchmarks (every bench/bench_*.cpp, one executable), then
# regenerates docs/benchmarks.md and docs/img/bench_<suite>_speed_error.png (bench_fresnel_...,
# bench_tonemap_..., bench_svo_build) from the results (scripts/bench_report.py).
# Usage: bash scripts/bench.sh        (from anywhere; about 20 minutes on 2 cores: the octree build
#                                     rows take 9, each further process about 1.5)
# Extra arguments are passed to raykit_bench, e.g. --benchmark_filter=schlick (the report then
# only holds what ran).
#
# The per-call suites run in RAYKIT_BENCH_PROCESSES (default 9) separate processes, one repetition
# each, so the spread the report quotes (the range of the per-process values) includes what changes
# from one process to the next (where the heap and the stack land, what else the machine runs), not
# only the noise inside one process. Nine, because a rerun's median then falls inside that range
# with probability 97 %, for any distribution of the values (scripts/rerun_stats.py; with 5 it is
# 83 %, and two runs agree both ways on only 71 % of the rows by chance alone). Use an odd count:
# the probability is then exact. The octree build rows run in the first process only.
# The previous run's merged JSON is kept as build/bench.prev.json; when it came from the same
# binary (same SHA-256), the report says how many rows of each run fall inside the other's range.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

# RAYKIT_BUILD_BENCH=ON explicitly: an existing build/ may have been configured without it.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRAYKIT_BUILD_BENCH=ON
cmake --build build --target raykit_bench -j2

processes="${RAYKIT_BENCH_PROCESSES:-9}"
if [ -f build/bench.json ]; then mv build/bench.json build/bench.prev.json; fi
rm -f build/bench.p?.json

# 0.2 s of timed passes per repetition is plenty at 4096 calls per iteration; each iteration also
# times the suite's baseline and the harness (bench_common.hpp, run_paired), so a repetition takes
# up to 0.6 s. Random interleaving puts the rows of one process in a random order, so a slow patch
# of the machine does not land on one family of rows in every process.
# The octree build rows (bench/bench_svo.cpp) run depths 6..11 (12..13 for the 1k mesh) only with
# RAYKIT_BENCH_SVO_FULL=1 (the bench.smoke ctest keeps them to depths 6..7); they set their own
# repetitions (1) and minimum time, since one build at depth 11 takes seconds.
jsons=()
for ((p = 1; p <= processes; p++)); do
  echo "== raykit_bench process $p of $processes"
  skip_svo=0
  if [ "$p" -gt 1 ]; then skip_svo=1; fi
  RAYKIT_BENCH_SVO_FULL="${RAYKIT_BENCH_SVO_FULL:-1}" RAYKIT_BENCH_SVO_SKIP="$skip_svo" \
    build/bench/raykit_bench \
    --benchmark_out_format=json \
    --benchmark_out="build/bench.p$p.json" \
    --benchmark_min_time=0.2 \
    --benchmark_repetitions=1 \
    --benchmark_enable_random_interleaving=true \
    "$@"
  jsons+=(--json "build/bench.p$p.json")
done

sha="$(sha256sum build/bench/raykit_bench | cut -d' ' -f1)"
previous=()
if [ -f build/bench.prev.json ]; then previous=(--previous build/bench.prev.json); fi
python3 scripts/bench_report.py "${jsons[@]}" --binary-sha256 "$sha" --merged-out build/bench.json \
  "${previous[@]}" --out-dir docs
