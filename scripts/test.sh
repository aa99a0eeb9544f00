#!/usr/bin/env bash
# Sets up every dependency (Debian packages), builds raykit with tests, samples and benchmarks,
# and runs the whole test suite: CPU tests, shader validation, GPU parity on headless OpenGL
# (Mesa llvmpipe when there is no GPU), consumer builds, sample and bench smoke runs.
# This is the README's test command; .ci/run calls exactly it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
