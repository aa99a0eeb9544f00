# raykit_compile_shaders(<target>
#     SOURCES <file>...                 shader sources (.vert .frag .comp .geom .tesc .tese, or
#                                       <name>.<stage>.glsl)
#     [TARGET_ENV vulkan1.0|vulkan1.1|vulkan1.2|vulkan1.3|opengl]   default vulkan1.2
#     [DEFINES NAME[=VALUE]...]         e.g. RK_FRESNEL_WINDOW_MODE=3
#     [INCLUDE_DIRS <dir>...]           searched after the including file's folder and raykit
#     [OUTPUT_DIR <dir>]                default ${CMAKE_CURRENT_BINARY_DIR}/spirv
#     [OUT_VAR <var>])                  receives the list of .spv files
#
# Compiles shaders that `#include "raykit/<x>.glsl"` offline to SPIR-V with glslangValidator.
# The shader itself enables the include extension:
#     #extension GL_GOOGLE_include_directive : require
# Each output gets a depfile, so editing any included file rebuilds it (Ninja, and Makefiles
# with CMake >= 3.20). If <target> exists, a <target>_spirv custom target is added as its
# dependency; otherwise <target> is created as a custom target built by `all`.
# RAYKIT_SHADER_DIR is set by add_subdirectory(raykit) and by find_package(raykit).
function(raykit_compile_shaders target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "TARGET_ENV;OUTPUT_DIR;OUT_VAR" "SOURCES;DEFINES;INCLUDE_DIRS")
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "raykit_compile_shaders(${target}): no SOURCES given")
  endif()
  if(NOT ARG_TARGET_ENV)
    set(ARG_TARGET_ENV vulkan1.2)
  endif()
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR "${CMAKE_CURRENT_BINARY_DIR}/spirv")
  endif()
  if(NOT RAYKIT_SHADER_DIR)
    message(FATAL_ERROR "raykit_compile_shaders: RAYKIT_SHADER_DIR is not set; use find_package(raykit) or add_subdirectory(raykit) first")
  endif()
  find_program(RAYKIT_GLSLANG_VALIDATOR NAMES glslangValidator glslang REQUIRED)

  if(ARG_TARGET_ENV STREQUAL "opengl")
    set(env_flags -G --target-env opengl)
  elseif(ARG_TARGET_ENV MATCHES "^vulkan1\\.[0-3]$")
    set(env_flags -V --target-env ${ARG_TARGET_ENV})
  else()
    message(FATAL_ERROR "raykit_compile_shaders: TARGET_ENV must be vulkan1.0..vulkan1.3 or opengl, not '${ARG_TARGET_ENV}'")
  endif()
  set(flags ${env_flags} "-I${RAYKIT_SHADER_DIR}")
  foreach(dir IN LISTS ARG_INCLUDE_DIRS)
    get_filename_component(dir "${dir}" ABSOLUTE)
    list(APPEND flags "-I${dir}")
  endforeach()
  foreach(def IN LISTS ARG_DEFINES)
    list(APPEND flags "-D${def}")
  endforeach()

  file(MAKE_DIRECTORY "${ARG_OUTPUT_DIR}")
  set(outputs)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(src "${src}" ABSOLUTE)
    get_filename_component(name "${src}" NAME)
    set(stage_flags)
    if(name MATCHES "\\.(vert|frag|comp|geom|tesc|tese|rgen|rchit|rmiss|rahit|rint|rcall|mesh|task)\\.glsl$")
      set(stage_flags -S ${CMAKE_MATCH_1})
    endif()
    set(out "${ARG_OUTPUT_DIR}/${name}.spv")
    add_custom_command(
      OUTPUT "${out}"
      COMMAND "${RAYKIT_GLSLANG_VALIDATOR}" ${flags} ${stage_flags} --depfile "${out}.d" -o "${out}" "${src}"
      MAIN_DEPENDENCY "${src}"
      DEPFILE "${out}.d"
      COMMENT "raykit: compiling ${name} to SPIR-V (${ARG_TARGET_ENV})"
      VERBATIM)
    list(APPEND outputs "${out}")
  endforeach()

  if(TARGET ${target})
    add_custom_target(${target}_spirv DEPENDS ${outputs})
    add_dependencies(${target} ${target}_spirv)
  else()
    add_custom_target(${target} ALL DEPENDS ${outputs})
  endif()
  if(ARG_OUT_VAR)
    set(${ARG_OUT_VAR} ${outputs} PARENT_SCOPE)
  endif()
endfunction()
