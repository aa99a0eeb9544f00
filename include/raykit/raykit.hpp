// raykit — umbrella header: every CPU-side part of the kit.
#pragma once

#include "raykit/color.hpp"
#include "raykit/common.hpp"
#include "raykit/fresnel.hpp"
#include "raykit/shader_source.hpp"
#include "raykit/tonemap.hpp"
