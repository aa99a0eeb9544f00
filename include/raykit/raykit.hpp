// raykit — umbrella header: every CPU-side part of the kit.
#pragma once

#include "raykit/bloom.hpp"
#include "raykit/color.hpp"
#include "raykit/common.hpp"
#include "raykit/envmap_correction.hpp"
#include "raykit/exposure.hpp"
#include "raykit/fresnel.hpp"
#include "raykit/hash.hpp"
#include "raykit/interior_compose.hpp"
#include "raykit/interior_features.hpp"
#include "raykit/interior_furniture.hpp"
#include "raykit/interior_mapping.hpp"
#include "raykit/interior_surface.hpp"
#include "raykit/paraboloid.hpp"
#include "raykit/shader_source.hpp"
#include "raykit/tonemap.hpp"
#include "raykit/window_glass.hpp"
