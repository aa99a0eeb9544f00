// raykit — envmap_correction.hpp: the CPU build of shaders/raykit/envmap_correction.glsl
// (reflection-vector correction for environment maps captured at a finite distance: Brennan's
// sphere, the thesis's street plane with its sigmoid, the exact ray-plane correction and the box
// projection).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_paraboloid.cpp checks that both builds agree on a real driver.
#pragma once

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/envmap_correction.glsl"
}  // namespace raykit
