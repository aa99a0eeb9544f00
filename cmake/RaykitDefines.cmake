# The feature-macro sets of raykit's C++ helpers, for CMake users (pass the result to
# raykit_compile_shaders(DEFINES ...)). Each function emits exactly what its C++ twin returns, in
# the same order (tests/test_cmake_defines.cpp compares them over many combinations):
#
# raykit_tonemap_defines(<out_var> OPERATOR <op> [AGX_LOOK <0|1|2|default|golden|punchy>])
#   raykit::tonemap_defines(op, agx_look); <op> is a ToneOperator name: clamp reinhard
#   aces_narkowicz aces_hill agx pbr_neutral hable lottes uchimura.
#
# raykit_interior_defines(<out_var> [TEXTURES four_textures|texture_array|padded_atlas|cube_per_room]
#     [GLASS fresnel|thesis_additive] [ROOM_LIGHTS] [FURNITURE_LAYERS <0..4>] [NO_FURNITURE_FLIPBOOK]
#     [VARYING_WALLS] [REFLECTIONS] [FADE] [TEXTURED_FACADE] [TONEMAP_OUTPUT])
#   raykit::interior_defines(InteriorSceneDesc): TEXTURES defaults to texture_array (as the
#   struct), FADE stands for a fade_distance > 0.
#
# Unknown arguments and values are errors that list the valid ones.

function(raykit_tonemap_defines out_var)
  # (lists inside the functions: variables of add_subdirectory(raykit) do not reach the caller)
  set(RAYKIT_TONEMAP_OPERATORS clamp reinhard aces_narkowicz aces_hill agx pbr_neutral hable lottes uchimura)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "OPERATOR;AGX_LOOK" "")
  if(ARG_UNPARSED_ARGUMENTS OR ARG_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "raykit_tonemap_defines: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}${ARG_KEYWORDS_MISSING_VALUES}' (takes OPERATOR <op> [AGX_LOOK <look>])")
  endif()
  list(FIND RAYKIT_TONEMAP_OPERATORS "${ARG_OPERATOR}" op)
  if(op LESS 0)
    message(FATAL_ERROR "raykit_tonemap_defines: OPERATOR must be one of ${RAYKIT_TONEMAP_OPERATORS}, not '${ARG_OPERATOR}'")
  endif()
  set(looks default golden punchy)
  if(NOT DEFINED ARG_AGX_LOOK)
    set(look 0)
  elseif(ARG_AGX_LOOK MATCHES "^[0-2]$")
    set(look ${ARG_AGX_LOOK})
  else()
    list(FIND looks "${ARG_AGX_LOOK}" look)
    if(look LESS 0)
      message(FATAL_ERROR "raykit_tonemap_defines: AGX_LOOK must be 0|1|2 or default|golden|punchy, not '${ARG_AGX_LOOK}'")
    endif()
  endif()
  set(defs "RK_TONEMAP_OPERATOR=${op}")
  if(ARG_OPERATOR STREQUAL "agx")
    list(APPEND defs "RK_AGX_LOOK=${look}")
  endif()
  set(${out_var} ${defs} PARENT_SCOPE)
endfunction()

function(raykit_interior_defines out_var)
  set(RAYKIT_INTERIOR_TEXTURES four_textures texture_array padded_atlas cube_per_room)
  cmake_parse_arguments(PARSE_ARGV 1 ARG
    "ROOM_LIGHTS;NO_FURNITURE_FLIPBOOK;VARYING_WALLS;REFLECTIONS;FADE;TEXTURED_FACADE;TONEMAP_OUTPUT"
    "TEXTURES;GLASS;FURNITURE_LAYERS" "")
  if(ARG_UNPARSED_ARGUMENTS OR ARG_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "raykit_interior_defines: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}${ARG_KEYWORDS_MISSING_VALUES}' "
      "(takes TEXTURES GLASS FURNITURE_LAYERS with a value; ROOM_LIGHTS NO_FURNITURE_FLIPBOOK VARYING_WALLS REFLECTIONS FADE TEXTURED_FACADE TONEMAP_OUTPUT)")
  endif()
  if(NOT DEFINED ARG_TEXTURES)
    set(ARG_TEXTURES texture_array)
  endif()
  list(FIND RAYKIT_INTERIOR_TEXTURES "${ARG_TEXTURES}" shading)
  if(shading LESS 0)
    message(FATAL_ERROR "raykit_interior_defines: TEXTURES must be one of ${RAYKIT_INTERIOR_TEXTURES}, not '${ARG_TEXTURES}'")
  endif()
  set(glass 0)
  if(DEFINED ARG_GLASS)
    if(ARG_GLASS STREQUAL "fresnel")
      set(glass 0)
    elseif(ARG_GLASS STREQUAL "thesis_additive")
      set(glass 1)
    else()
      message(FATAL_ERROR "raykit_interior_defines: GLASS must be fresnel or thesis_additive, not '${ARG_GLASS}'")
    endif()
  endif()
  set(layers 0)
  if(DEFINED ARG_FURNITURE_LAYERS)
    if(NOT ARG_FURNITURE_LAYERS MATCHES "^[0-4]$")
      message(FATAL_ERROR "raykit_interior_defines: FURNITURE_LAYERS must be 0..4, not '${ARG_FURNITURE_LAYERS}'")
    endif()
    set(layers ${ARG_FURNITURE_LAYERS})
  endif()
  set(flipbook 0)
  if(layers GREATER 0 AND NOT ARG_NO_FURNITURE_FLIPBOOK)
    set(flipbook 1)
  endif()
  macro(_rk_bool var flag)
    if(${flag})
      set(${var} 1)
    else()
      set(${var} 0)
    endif()
  endmacro()
  _rk_bool(lights ARG_ROOM_LIGHTS)
  _rk_bool(walls ARG_VARYING_WALLS)
  _rk_bool(refl ARG_REFLECTIONS)
  _rk_bool(fade ARG_FADE)
  _rk_bool(facade ARG_TEXTURED_FACADE)
  _rk_bool(output ARG_TONEMAP_OUTPUT)
  set(${out_var}
    RK_IM_SHADING=${shading} RK_IM_COMPOSE_MODE=${glass} RK_IM_ROOM_LIGHTS=${lights}
    RK_IM_FURNITURE_LAYERS=${layers} RK_IM_FURNITURE_FLIPBOOK=${flipbook} RK_IM_VARYING_WALLS=${walls}
    RK_IM_REFLECTION=${refl} RK_IM_FADE=${fade} RK_IM_BUILDING_FACADE=${facade} RK_IM_BUILDING_OUTPUT=${output}
    PARENT_SCOPE)
endfunction()
