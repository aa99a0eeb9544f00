// raykit — window_glass.hpp: the CPU build of shaders/raykit/window_glass.glsl (a window pane:
// environment reflection weighted by the pane's Fresnel reflectance, plus the tinted interior).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_paraboloid.cpp checks that both builds agree on a real driver. The
// RK_WINDOW_GLASS_FRESNEL and RK_FRESNEL_WINDOW_MODE macros select the model at compile time, in
// C++ as in GLSL: define them before including this header (and fresnel.hpp).
#pragma once

#include "raykit/color.hpp"
#include "raykit/fresnel.hpp"

namespace raykit {
#include "raykit/window_glass.glsl"
}  // namespace raykit
