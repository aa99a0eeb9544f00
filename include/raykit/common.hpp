// raykit — common.hpp: the CPU build of shaders/raykit/common.glsl.
#pragma once

#include "raykit/detail/glsl_compat.hpp"

namespace raykit {
#include "raykit/common.glsl"
}  // namespace raykit
