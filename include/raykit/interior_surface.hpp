// raykit — interior_surface.hpp: the CPU build of shaders/raykit/interior_surface.glsl (which
// texel a room hit samples: surface kind, per-face variant, texture-array layer, padded-atlas
// coordinate and LOD clamp, per-room cube-map direction, rotation and layer).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_interior.cpp checks that both builds agree on a real driver, and
// tests/test_interior_surface.cpp checks them against float64 brute force.
#pragma once

#include "raykit/interior_compose.hpp"
#include "raykit/interior_mapping.hpp"

namespace raykit {
#include "raykit/interior_surface.glsl"
}  // namespace raykit
