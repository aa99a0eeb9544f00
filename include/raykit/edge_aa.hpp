// raykit — edge_aa.hpp: the CPU build of shaders/raykit/edge_aa.glsl (depth and normal
// discontinuities of a G-buffer and the offsets of the four-tap edge blur).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_edge_aa.cpp checks that both builds agree on a real driver.
#pragma once

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/edge_aa.glsl"
}  // namespace raykit
