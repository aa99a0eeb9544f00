#!/usr/bin/env bash
# The thesis's volume protocol (van Dongen, "Interior Mapping", §6.4.2 and figure 6.23) on the GL
# driver: samples/effects --bench draws one particle system as billboards, 5 to 79 slices (8-bit and
# float colour buffers) and each raytraced primitive and opacity function, and reports each frame
# time as a ratio to the billboard frame (interleaved repetitions, medians), next to the thesis's
# frame counts. Writes docs/benchmarks_volumes.md, which scripts/bench_report.py quotes in
# docs/benchmarks.md. On a CPU driver (Mesa llvmpipe) only the ratios mean something.
#
# Usage: bash scripts/bench_volumes.sh
# Environment: BENCH_VOLUMES_BUILD (default build), BENCH_VOLUMES_SIZE (default 1024x768, the
# thesis's interior-mapping resolution; its volume chapter does not state one), BENCH_VOLUMES_REPS
# (default 7), BENCH_VOLUMES_DOC (default docs/benchmarks_volumes.md), BENCH_VOLUMES_FROM (report the
# folder DIR/volumes written by scripts/bench_gpu.sh instead of running). About two minutes on llvmpipe.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
BUILD="${BENCH_VOLUMES_BUILD:-build}"
SIZE="${BENCH_VOLUMES_SIZE:-1024x768}"
REPS="${BENCH_VOLUMES_REPS:-7}"
DOC="${BENCH_VOLUMES_DOC:-docs/benchmarks_volumes.md}"
TMP="$(mktemp)"
trap 'rm -f "$TMP" "$TMP.log"' EXIT
if [ -n "${BENCH_VOLUMES_FROM:-}" ]; then  # a run made elsewhere (scripts/bench_gpu.sh: DIR/volumes/)
  cp "$BENCH_VOLUMES_FROM/bench.txt" "$TMP"
  cp "$BENCH_VOLUMES_FROM/console.txt" "$TMP.log"
else
  cmake --build "$BUILD" --target effects -j"$(nproc)"
  "$BUILD/samples/effects" --bench --reps "$REPS" --size "$SIZE" --bench-out "$TMP" > "$TMP.log"
fi
RENDERER="$(grep -m1 '^\*\*Renderer' "$TMP.log" || true)"
{
  echo "# Volumes: billboards, slices and raytraced soft particles"
  echo
  echo "Written by \`bash scripts/bench_volumes.sh\` ($(date -u +%Y-%m-%d)): \`samples/effects --bench\`, the protocol of"
  echo "van Dongen's §6.4.2: one particle system (24 overlapping puffs over the ground and a wall,"
  echo "the scene's depth buffer and lighting included in every frame), drawn by each technique in"
  echo "turn. The thesis counted frames in 5 s on a GeForce 6600 GT (figure 6.23); here each frame is"
  echo "timed, billboard and technique alternating, and the median ratio is the technique's cost."
  echo "The billboard, slices and raytraced rows draw into an 8-bit colour buffer, the \"float\" rows"
  echo "into RGBA16F, as the thesis's did."
  echo
  echo "$RENDERER"
  echo
  cat "$TMP"
  echo
  echo "What the data show: see docs/volume.md (\"Cost\"). On a CPU driver the absolute times are the"
  echo "rasteriser's, not a GPU's: only the ratios carry over, and not exactly."
} > "$DOC"
echo "wrote $DOC"
