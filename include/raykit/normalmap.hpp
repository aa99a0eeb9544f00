// raykit — normalmap.hpp: the CPU build of shaders/raykit/normalmap.glsl (tangent frames from a
// stored tangent or from derivatives, two-channel normal unpacking, parallax offset mapping).
// Per-vertex tangents for a mesh: tangents.hpp.
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_normalmap.cpp checks that both builds agree on a real driver.
#pragma once

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/normalmap.glsl"
}  // namespace raykit
