#!/usr/bin/env bash
# Builds and runs raykit_bench_trace (bench/trace/): CPU primary-ray throughput (Mrays/s, 1 and 2
# threads, 512 x 512 rays) of the ray tracers on the same meshes and cameras, Embree on the source
# triangles and OpenVDB's level-set ray intersector at depths 8..10 (8..12 with
# RAYKIT_BENCH_TRACE_FULL=1) next to raykit's own rows. The peers are bench-only Debian packages,
# installed here when missing (users and CI never need them: without them the executable has no
# peer rows and the bench.trace.smoke test is not registered). libboost-iostreams-dev is needed by
# OpenVDB's CMake module and headers, though Debian's libopenvdb-dev does not depend on it.
# Writes the JSON to <build>/bench_trace.json; the console keeps the readable table.
# Usage: bash scripts/bench_trace.sh [raykit_bench_trace arguments...]
#   e.g. --benchmark_filter=uv_sphere_5856, or --smoke for the quick check. Environment:
#   RAYKIT_BENCH_BUILD_DIR (default build), RAYKIT_BENCH_TRACE_FULL=1 (depths 11 and 12 too: minutes
#   and gigabytes), RAYKIT_BENCH_TRACE_MAX_BYTES (level sets estimated above it are skipped).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh libembree-dev libopenvdb-dev libboost-iostreams-dev

build="${RAYKIT_BENCH_BUILD_DIR:-build}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DRAYKIT_BUILD_BENCH=ON -DRAYKIT_BUILD_BENCH_TRACE=ON
cmake --build "$build" --target raykit_bench_trace raykit_svo_packet_ab -j2

exe="$build/bench/trace/raykit_bench_trace"
rows="$("$exe" --benchmark_list_tests)"
for peer in embree openvdb; do
  grep -q "/$peer/" <<<"$rows" || { echo "bench_trace: $exe was built without $peer (see the cmake output above)" >&2; exit 1; }
done

"$exe" --benchmark_out_format=json --benchmark_out="$build/bench_trace.json" "$@"
# rk_svo_trace, svo_trace_rays and svo_trace_packets paired in one process at depths 8, 10 and 12
# (the ratios docs/svo-traverse.md quotes).
for d in 8 10 12; do "$build/bench/trace/raykit_svo_packet_ab" "$d" 11; done
echo "bench_trace: results in $build/bench_trace.json (load average after the run: $(cut -d' ' -f1-3 /proc/loadavg))"
