#!/usr/bin/env bash
# Installs every build, test, sample and benchmark dependency of raykit from Debian packages.
# Idempotent: packages already present are skipped, so running it twice costs one dpkg query.
# Usage: bash scripts/setup.sh [extra-package ...]   (uses sudo when not root; scripts that need
#        bench-only packages, e.g. scripts/bench_trace.sh, pass them as arguments)
set -euo pipefail

PKGS=(
  build-essential cmake pkg-config
  libglm-dev                                  # the only dependency of the raykit::raykit target
  glslang-tools glslang-dev spirv-tools       # shader validation + raykit_compile_shaders
  spirv-cross                                 # tests: GLSL -> HLSL / MSL through SPIRV-Cross
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0   # headless OpenGL 4.5 (llvmpipe)
  mesa-vulkan-drivers libvulkan-dev           # lavapipe, for users' Vulkan SPIR-V smoke runs
  libglfw3-dev                                # windowed samples (optional at build time)
  libtinygltf-dev nlohmann-json3-dev libstb-dev   # glTF loading (tinygltf needs nlohmann/json), PNG output
  libgtest-dev libbenchmark-dev               # tests, bench
  gnuplot-nox python3                         # docs/benchmarks.md table + speed-vs-error plot
)
PKGS+=("$@")

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PKGS[@]} packages already installed"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
