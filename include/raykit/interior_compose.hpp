// raykit — interior_compose.hpp: the CPU build of shaders/raykit/interior_compose.glsl (window
// mask convention, Fresnel glass or the thesis's additive window, per-room lights, distance fade).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_interior_shading.cpp checks that both builds agree on a real driver. The
// RK_IM_COMPOSE_MODE, RK_WINDOW_GLASS_FRESNEL and RK_FRESNEL_WINDOW_MODE macros select the model at
// compile time, in C++ as in GLSL: define them before including this header.
#pragma once

#include "raykit/interior_mapping.hpp"
#include "raykit/window_glass.hpp"

namespace raykit {
#include "raykit/interior_compose.glsl"
}  // namespace raykit
