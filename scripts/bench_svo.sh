#!/usr/bin/env bash
# Runs only the octree build benchmarks (bench/bench_svo.cpp, suite "svo") at full settings and
# writes their report to a scratch directory, for iterating on the builder without touching docs/.
# docs/benchmarks.md is written only by scripts/bench.sh (every suite in one run).
# Usage: bash scripts/bench_svo.sh [OUT_DIR] [raykit_bench arguments...]
#   OUT_DIR defaults to build/bench_svo_report (report: OUT_DIR/benchmarks.md, plot:
#   OUT_DIR/img/bench_svo_build.png, JSON: OUT_DIR/bench_svo.json). Extra arguments go to
#   raykit_bench, e.g. --benchmark_filter=svo/icosphere3. Environment: RAYKIT_BENCH_SVO_MAX_DEPTH
#   caps the depth (e.g. 10 for a quick run), RAYKIT_BENCH_SVO_MAX_BYTES the memory estimate above
#   which a row is skipped (default 8 GiB, and never above half of MemAvailable).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

out_dir="${1:-build/bench_svo_report}"
if [[ $# -gt 0 ]]; then shift; fi
case "$(realpath -m "$out_dir")" in
  "$(realpath -m docs)") echo "bench_svo.sh: refusing to write a partial report over docs/ (use scripts/bench.sh)" >&2; exit 2 ;;
esac
mkdir -p "$out_dir"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRAYKIT_BUILD_BENCH=ON
cmake --build build --target raykit_bench -j2

RAYKIT_BENCH_SVO_FULL=1 build/bench/raykit_bench \
  --benchmark_filter=BM_svo \
  --benchmark_out_format=json \
  --benchmark_out="$out_dir/bench_svo.json" \
  "$@"

python3 scripts/bench_report.py --json "$out_dir/bench_svo.json" --out-dir "$out_dir"
