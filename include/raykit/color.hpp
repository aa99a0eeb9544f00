// raykit — color.hpp: the CPU build of shaders/raykit/color.glsl.
#pragma once

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/color.glsl"
}  // namespace raykit
