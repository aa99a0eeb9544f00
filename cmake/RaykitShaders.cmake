# raykit_interior_defines() and raykit_tonemap_defines(): the C++ helpers' define lists.
include("${CMAKE_CURRENT_LIST_DIR}/RaykitDefines.cmake")

# raykit_compile_shaders(<target>
#     SOURCES <file>...                 shader sources (.vert .frag .comp .geom .tesc .tese, or
#                                       <name>.<stage>.glsl)
#     [TARGET_ENV vulkan1.0|vulkan1.1|vulkan1.2|vulkan1.3|opengl]   default vulkan1.2
#     [DEFINES NAME[=VALUE]...]         e.g. RK_FRESNEL_WINDOW_MODE=3, or the list that
#                                       raykit_interior_defines() / raykit_tonemap_defines() give
#     [FLAGS <glslang flag>...]         extra glslangValidator flags (e.g. -g, -Os, --auto-map-bindings)
#     [VARIANT <name>]                  names the outputs <source>.<name>.spv
#     [INCLUDE_DIRS <dir>...]           searched after the including file's folder and raykit
#     [OUTPUT_DIR <dir>]                default ${CMAKE_CURRENT_BINARY_DIR}/spirv
#     [OUT_VAR <var>])                  receives the list of .spv files
#
# Compiles shaders that `#include "raykit/<x>.glsl"` offline to SPIR-V with glslangValidator.
# The shader itself enables the include extension:
#     #extension GL_GOOGLE_include_directive : require
# Each output gets a depfile, so editing any included file rebuilds it (Ninja, and Makefiles
# with CMake >= 3.20). If <target> exists, a custom target <target>_spirv (then _spirv_2, ...: the
# function may be called several times for one target) is added as its dependency; otherwise
# <target> is created as a custom target built by `all`.
# Outputs: <source>.spv without DEFINES, FLAGS and VARIANT; <source>.<VARIANT>.spv; otherwise
# <source>.<first 8 hex digits of the SHA-1 of the defines and flags>.spv, so the same source with
# different DEFINES gives distinct files. Two calls that would still write one file with different
# commands (e.g. two TARGET_ENVs into one OUTPUT_DIR) are an error, as are unknown arguments and
# malformed DEFINES. RAYKIT_SHADER_DIR is set by add_subdirectory(raykit) and find_package(raykit).
function(raykit_compile_shaders target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "TARGET_ENV;OUTPUT_DIR;OUT_VAR;VARIANT" "SOURCES;DEFINES;INCLUDE_DIRS;FLAGS")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "raykit_compile_shaders(${target}): unknown arguments '${ARG_UNPARSED_ARGUMENTS}' "
      "(takes SOURCES TARGET_ENV DEFINES FLAGS VARIANT INCLUDE_DIRS OUTPUT_DIR OUT_VAR)")
  endif()
  if(ARG_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "raykit_compile_shaders(${target}): no value after ${ARG_KEYWORDS_MISSING_VALUES}")
  endif()
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "raykit_compile_shaders(${target}): no SOURCES given")
  endif()
  foreach(def IN LISTS ARG_DEFINES)
    if(NOT def MATCHES "^[A-Za-z_][A-Za-z0-9_]*(=.*)?$")
      message(FATAL_ERROR "raykit_compile_shaders(${target}): malformed DEFINES entry '${def}' (NAME or NAME=VALUE)")
    endif()
  endforeach()
  if(DEFINED ARG_VARIANT AND NOT ARG_VARIANT MATCHES "^[A-Za-z0-9_.-]+$")
    message(FATAL_ERROR "raykit_compile_shaders(${target}): VARIANT '${ARG_VARIANT}' must be letters, digits, _ . -")
  endif()
  if(NOT ARG_TARGET_ENV)
    set(ARG_TARGET_ENV vulkan1.2)
  endif()
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR "${CMAKE_CURRENT_BINARY_DIR}/spirv")
  endif()
  get_filename_component(ARG_OUTPUT_DIR "${ARG_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
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
  list(APPEND flags ${ARG_FLAGS})
  set(suffix "")
  if(DEFINED ARG_VARIANT)
    set(suffix ".${ARG_VARIANT}")
  elseif(ARG_DEFINES OR ARG_FLAGS)
    string(SHA1 hash "${ARG_DEFINES}|${ARG_FLAGS}")
    string(SUBSTRING "${hash}" 0 8 hash)
    set(suffix ".${hash}")
  endif()

  file(MAKE_DIRECTORY "${ARG_OUTPUT_DIR}")
  set(outputs)
  set(new_outputs)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(src "${src}" ABSOLUTE)
    get_filename_component(name "${src}" NAME)
    set(stage_flags)
    if(name MATCHES "\\.(vert|frag|comp|geom|tesc|tese|rgen|rchit|rmiss|rahit|rint|rcall|mesh|task)\\.glsl$")
      set(stage_flags -S ${CMAKE_MATCH_1})
    endif()
    set(out "${ARG_OUTPUT_DIR}/${name}${suffix}.spv")
    set(command "${RAYKIT_GLSLANG_VALIDATOR};${flags};${stage_flags};${src}")
    get_property(previous GLOBAL PROPERTY "raykit_spirv:${out}")
    if(previous)
      if(NOT previous STREQUAL command)
        message(FATAL_ERROR "raykit_compile_shaders(${target}): ${out} is already written by another call with "
          "different options (TARGET_ENV, INCLUDE_DIRS?); give this call its own VARIANT or OUTPUT_DIR")
      endif()
    else()
      set_property(GLOBAL PROPERTY "raykit_spirv:${out}" "${command}")
      add_custom_command(
        OUTPUT "${out}"
        COMMAND "${RAYKIT_GLSLANG_VALIDATOR}" ${flags} ${stage_flags} --depfile "${out}.d" -o "${out}" "${src}"
        MAIN_DEPENDENCY "${src}"
        DEPFILE "${out}.d"
        COMMENT "raykit: compiling ${name}${suffix} to SPIR-V (${ARG_TARGET_ENV})"
        VERBATIM)
    endif()
    list(APPEND outputs "${out}")
  endforeach()

  if(TARGET ${target})
    set(spirv_target ${target}_spirv)
    set(n 1)
    while(TARGET ${spirv_target})
      math(EXPR n "${n} + 1")
      set(spirv_target ${target}_spirv_${n})
    endwhile()
    add_custom_target(${spirv_target} DEPENDS ${outputs})
    add_dependencies(${target} ${spirv_target})
  else()
    add_custom_target(${target} ALL DEPENDS ${outputs})
  endif()
  if(ARG_OUT_VAR)
    set(${ARG_OUT_VAR} ${outputs} PARENT_SCOPE)
  endif()
endfunction()
