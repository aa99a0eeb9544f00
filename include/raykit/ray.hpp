// raykit — ray.hpp: the CPU build of shaders/raykit/ray.glsl: a ray against a plane (half-space),
// a sphere, an axis-aligned box and ellipsoids (axis-aligned, or any linear map of a unit sphere),
// each as the interval (t_enter, t_exit) of the ray inside the solid, and the impostor helpers
// (a sphere or an oriented box raycast from a rasterised proxy, with the hit's window depth).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_ray.cpp checks that both builds agree on a real driver. docs/ray.md lists the
// functions and their measured errors.
#pragma once

#include "raykit/common.hpp"
#include "raykit/gbuffer.hpp"

namespace raykit {
#include "raykit/ray.glsl"
}  // namespace raykit
