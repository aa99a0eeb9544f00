#!/usr/bin/env bash
# Builds and runs raykit's CPU benchmarks (every bench/bench_*.cpp, one executable), then
# regenerates docs/benchmarks.md and docs/img/bench_<suite>_speed_error.png (bench_fresnel_...,
# bench_tonemap_...) from the results (scripts/bench_report.py).
# Usage: bash scripts/bench.sh        (from anywhere; takes about 1.5-2 minutes)
# Extra arguments are passed to raykit_bench, e.g. --benchmark_filter=schlick (the report then
# only holds what ran).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

# RAYKIT_BUILD_BENCH=ON explicitly: an existing build/ may have been configured without it.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRAYKIT_BUILD_BENCH=ON
cmake --build build --target raykit_bench -j2

# JSON goes to build/bench.json (what the report reads); the console keeps the readable table.
# 0.2 s of timed passes per repetition is plenty at 4096 calls per iteration; each iteration also
# times the suite's baseline and the harness (bench_common.hpp, run_paired), so a repetition takes
# up to 0.6 s. Every repetition is kept in the JSON: the report takes medians and ranges itself.
# Random interleaving spreads each benchmark's repetitions over the whole run, so the median the
# report uses shrugs off a slow patch (shared/virtual machines) instead of a whole benchmark eating it.
# The octree build rows (bench/bench_svo.cpp) run depths 6..11 (12..13 for the 1k mesh) only with
# RAYKIT_BENCH_SVO_FULL=1 (the bench.smoke ctest keeps them to depths 6..7); they set their own
# repetitions (1) and minimum time, since one build at depth 11 takes seconds.
RAYKIT_BENCH_SVO_FULL="${RAYKIT_BENCH_SVO_FULL:-1}" build/bench/raykit_bench \
  --benchmark_out_format=json \
  --benchmark_out=build/bench.json \
  --benchmark_min_time=0.2 \
  --benchmark_repetitions=5 \
  --benchmark_enable_random_interleaving=true \
  "$@"

python3 scripts/bench_report.py --json build/bench.json --out-dir docs
