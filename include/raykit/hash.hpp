// raykit — hash.hpp: the CPU build of shaders/raykit/hash.glsl (PCG3D, a single-word PCG hash and
// the exact uint-to-[0,1) mapping), bit-identical to the GPU build (tests/gpu/parity_interior.cpp).
#pragma once

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/hash.glsl"
}  // namespace raykit
