#!/usr/bin/env bash
# Runs raykit's driver checks and driver benchmarks on a machine with a GPU, from binaries already
# built (by scripts/test.sh or scripts/bench_*.sh: build/tests/gpu_parity_test,
# build/bench/bench_svo_gl, build/bench/bench_interior_gl, build/samples/svo_demo, build/samples/city),
# and leaves every result in one folder:
#   parity.log, parity.xml   the whole GPU parity suite (gtest) on that driver
#   svo_gl/                  bench_svo_gl: table.md, table.md.dat, log.txt, lod.png
#   interior/                bench_interior_gl: results.json, results.csv, table.md, console.txt, materials.png
#   deferred/, volumes/      samples/deferred_city --bench and samples/effects --bench (bench.txt, console.txt)
#   demo/                    every sample's images, rendered by that driver
#   machine.txt              the renderer, the CPU count, the date
# Report them on any machine (no GPU needed):
#   BENCH_SVO_GL_FROM=DIR/svo_gl BENCH_SVO_GL_DOC=docs/benchmarks_svo_gl_gpu.md \
#     BENCH_SVO_GL_IMG=docs/img/bench_svo_gl_gpu bash scripts/bench_svo_gl.sh
#   BENCH_INTERIOR_REPORT_ONLY=1 BENCH_INTERIOR_OUT=DIR/interior BENCH_INTERIOR_CPUS=<cpus> \
#     BENCH_INTERIOR_DOC=docs/benchmarks_interior_gpu.md \
#     BENCH_INTERIOR_PNG=docs/img/bench_interior_materials_gpu.png bash scripts/bench_interior.sh
#   BENCH_DEFERRED_FROM=DIR/deferred/bench.txt BENCH_DEFERRED_DOC=docs/benchmarks_deferred_gpu.md \
#     bash scripts/bench_deferred.sh
#   BENCH_VOLUMES_FROM=DIR/volumes BENCH_VOLUMES_DOC=docs/benchmarks_volumes_gpu.md bash scripts/bench_volumes.sh
# With RAYKIT_PARITY_DUMP=DIR2 set (an existing folder), the parity suite also writes its mismatching rows to DIR2
# (tests/gpu/parity.hpp; replay them anywhere with RAYKIT_PARITY_REPLAY=DIR2).
# Usage: bash scripts/bench_gpu.sh OUT_DIR [BUILD_DIR]
# Each step has a time limit (RAYKIT_GPU_STEP_TIMEOUT seconds, default 240) and a failing step does
# not stop the others; the exit status is that of the parity suite.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
OUT="${1:?usage: bench_gpu.sh OUT_DIR [BUILD_DIR]}"
BUILD="${2:-build}"
LIMIT="${RAYKIT_GPU_STEP_TIMEOUT:-240}"
mkdir -p "$OUT/svo_gl" "$OUT/interior" "$OUT/deferred" "$OUT/volumes" "$OUT/demo"

{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "cpus: $(nproc)"
  command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | sed 's/^/gpu: /'
} > "$OUT/machine.txt"

step() {  # step NAME COMMAND...: runs with a time limit, prints its wall time and status
  local name="$1"; shift
  local t0=$SECONDS
  timeout "$LIMIT" "$@"
  local rc=$?
  echo "bench_gpu: $name: exit $rc after $((SECONDS - t0)) s" | tee -a "$OUT/machine.txt" >&2
  return $rc
}

CI=true step parity "$BUILD/tests/gpu_parity_test" --gtest_output="xml:$OUT/parity.xml" > "$OUT/parity.log" 2>&1
parity=$?
grep -E "renderer|^\[  (PASSED|FAILED) " "$OUT/parity.log" | head -20

step svo_gl "$BUILD/bench/bench_svo_gl" --rounds "${RAYKIT_GPU_SVO_ROUNDS:-25}" --md "$OUT/svo_gl/table.md" \
  --png "$OUT/svo_gl/lod.png" > "$OUT/svo_gl/log.txt" 2>&1
head -1 "$OUT/svo_gl/log.txt" | tee -a "$OUT/machine.txt"

step interior "$BUILD/bench/bench_interior_gl" --width 1024 --height 768 --rounds 72 --poses 8 --warmup 2 \
  --json "$OUT/interior/results.json" --csv "$OUT/interior/results.csv" --md "$OUT/interior/table.md" \
  --png "$OUT/interior/materials.png" > "$OUT/interior/console.txt" 2>&1

if [ -x "$BUILD/samples/deferred_city" ]; then
  step deferred "$BUILD/samples/deferred_city" --bench --reps "${RAYKIT_GPU_DEFERRED_REPS:-9}" --size 960x540 \
    --bench-out "$OUT/deferred/bench.txt" > "$OUT/deferred/console.txt" 2>&1
fi
if [ -x "$BUILD/samples/effects" ]; then
  step volumes "$BUILD/samples/effects" --bench --reps "${RAYKIT_GPU_VOLUMES_REPS:-7}" --size 1024x768 \
    --bench-out "$OUT/volumes/bench.txt" > "$OUT/volumes/console.txt" 2>&1
fi

for demo in svo_demo city deferred_city effects fresnel_curves tonemap_gallery; do
  [ -x "$BUILD/samples/$demo" ] || continue
  case "$demo" in
    fresnel_curves|tonemap_gallery) arg="$OUT/demo/$demo.png" ;;  # these two take a file, the others a folder
    *) arg="$OUT/demo" ;;
  esac
  step "$demo" "$BUILD/samples/$demo" "$arg" > "$OUT/demo/$demo.log" 2>&1
done
exit $parity
