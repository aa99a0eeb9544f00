// raykit — interior_furniture.hpp: the CPU build of shaders/raykit/interior_furniture.glsl
// (furniture planes behind an interior-mapped facade: ray fraction, per-room UV and room index,
// UV derivatives, layer visibility, flipbook animation with a per-room phase).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_interior_shading.cpp checks that both builds agree on a real driver.
#pragma once

#include "raykit/interior_mapping.hpp"

namespace raykit {
#include "raykit/interior_furniture.glsl"
}  // namespace raykit
