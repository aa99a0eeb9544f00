#!/usr/bin/env bash
# Forward against deferred shading as the number of point lights grows (samples/deferred_city
# --bench: the night view of the deferred city, forward and deferred frames interleaved, medians),
# plus the bytes per pixel of raykit's G-buffer presets; writes docs/benchmarks_deferred.md, which
# scripts/bench_report.py quotes in docs/benchmarks.md. On a CPU driver (Mesa llvmpipe) only the
# ratios mean something; absolute times come from a GPU.
#
# Usage: bash scripts/bench_deferred.sh
# Environment: BENCH_DEFERRED_BUILD (build folder, default build), BENCH_DEFERRED_SIZE (default
# 960x540), BENCH_DEFERRED_REPS (default 9), BENCH_DEFERRED_DOC (default docs/benchmarks_deferred.md),
# BENCH_DEFERRED_FROM (report a bench.txt written elsewhere, e.g. by scripts/bench_gpu.sh, instead of running).
# About two minutes on Mesa llvmpipe with 2 cores.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
BUILD="${BENCH_DEFERRED_BUILD:-build}"
SIZE="${BENCH_DEFERRED_SIZE:-960x540}"
REPS="${BENCH_DEFERRED_REPS:-9}"
DOC="${BENCH_DEFERRED_DOC:-docs/benchmarks_deferred.md}"
TMP="$(mktemp)"
trap 'rm -f "$TMP"' EXIT
if [ -n "${BENCH_DEFERRED_FROM:-}" ]; then  # a run made elsewhere (scripts/bench_gpu.sh: DIR/deferred/bench.txt)
  cp "$BENCH_DEFERRED_FROM" "$TMP"
else
  cmake --build "$BUILD" --target deferred_city -j"$(nproc)"
  "$BUILD/samples/deferred_city" --bench --reps "$REPS" --size "$SIZE" --bench-out "$TMP" >/dev/null
fi
{
  echo "# Forward against deferred shading: frame time by light count"
  echo
  echo "Written by \`bash scripts/bench_deferred.sh\` ($(date -u +%Y-%m-%d)): \`samples/deferred_city --bench\`."
  echo "The night view of the deferred city (6,560 triangles, 660 street lamps, of which the first N"
  echo "in a fixed shuffled order are used). Forward: one pass, every fragment loops over every light"
  echo "(overdraw included). Deferred: the compact G-buffer, one full-screen pass for the sun and sky,"
  echo "then one instanced draw of light volumes (light_volume_sphere) per cull mode. Both shade with the"
  echo "same functions (samples/deferred_city/dc_common.glsl); the sun's four cascades are rendered once"
  echo "per light count, outside the timing. Forward and deferred frames alternate, the first pair is a"
  echo "warm-up, and each cell is the median of the rest; the spread is the largest over the smallest"
  echo "per-repetition ratio."
  echo
  cat "$TMP"
  echo
  echo "What the data show: see docs/deferred.md (\"Forward against deferred\"). On a CPU driver the"
  echo "absolute times are the rasteriser's, not a GPU's: only the ratios carry over, and not exactly."
} > "$DOC"
echo "wrote $DOC"
