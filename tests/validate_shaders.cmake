# Validates every shaders/**/*.glsl by compiling generated stub shaders with glslangValidator:
#   - OpenGL 4.50 -> SPIR-V (-G), then spirv-val --target-env opengl4.5
#   - Vulkan 1.2  -> SPIR-V (-V), then spirv-val --target-env vulkan1.2
#   - GLSL ES 3.10 (front end only) when the file declares `// @rk-es 310`
#   - GLSL ES 3.00 / WebGL 2 (front end only, fragment stage, precision highp float and int) when
#     it declares `// @rk-es300 [NAME=VALUE...]`, with those macros (e.g. RK_SVO_BUFFER_TEXTURE=1)
# once per stage (comp, frag) and per feature-macro variant declared in the file as
#   // @rk-variants A=0 | A=1 B=2 | ...
# (each `|`-separated group is one variant; the default, no macro, is always compiled too),
# in the stages named by `// @rk-stages comp frag` (default: both).
# Any warning fails the test as well as any error. Files are globbed at test time, so a new
# include is validated without editing CMake.
#
# cmake -DSHADER_DIR=... -DWORK_DIR=... -DGLSLANG=... -DSPIRV_VAL=... -P validate_shaders.cmake
foreach(v SHADER_DIR WORK_DIR GLSLANG SPIRV_VAL)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "validate_shaders: -D${v}= is required")
  endif()
endforeach()

file(GLOB_RECURSE files RELATIVE "${SHADER_DIR}" "${SHADER_DIR}/*.glsl")
list(SORT files)
if(NOT files)
  message(FATAL_ERROR "validate_shaders: no .glsl files under ${SHADER_DIR}")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(failures 0)
set(runs 0)
function(run_checked label)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(text "${out}${err}")
  math(EXPR n "${runs} + 1")
  set(runs ${n} PARENT_SCOPE)
  if(NOT rc EQUAL 0 OR text MATCHES "WARNING|[Ww]arning:")
    message("FAIL ${label}\n  command: ${ARGN}\n${text}")
    math(EXPR f "${failures} + 1")
    set(failures ${f} PARENT_SCOPE)
  endif()
endfunction()

foreach(rel IN LISTS files)
  file(READ "${SHADER_DIR}/${rel}" src)
  string(MAKE_C_IDENTIFIER "${rel}" id)
  set(variants "<default>")
  if(src MATCHES "@rk-variants ([^\n]*)")
    string(REPLACE "|" ";" groups "${CMAKE_MATCH_1}")
    foreach(g IN LISTS groups)
      string(STRIP "${g}" g)
      list(APPEND variants "${g}")
    endforeach()
  endif()
  # `// @rk-stages comp` restricts a file to some stages (e.g. one that declares compute
  # buffers or uses shared memory); the default is both comp and frag.
  set(stages comp frag)
  if(src MATCHES "@rk-stages ([a-z ]+)")
    string(STRIP "${CMAKE_MATCH_1}" st)
    string(REPLACE " " ";" stages "${st}")
  endif()
  set(es OFF)
  if(src MATCHES "@rk-es 310")
    set(es ON)
  endif()
  if(src MATCHES "@rk-es300([^\n]*)")
    string(STRIP "${CMAKE_MATCH_1}" es300_words)
    set(es300_defs "")
    if(es300_words)
      string(REPLACE " " ";" es300_words "${es300_words}")
      foreach(w IN LISTS es300_words)
        string(REPLACE "=" " " w "${w}")
        string(APPEND es300_defs "#define ${w}\n")
      endforeach()
    endif()
    set(base "${WORK_DIR}/${id}_es300")
    file(WRITE "${base}.frag" "#version 300 es\n#extension GL_GOOGLE_include_directive : require\n"
      "precision highp float;\nprecision highp int;\n${es300_defs}#include \"${rel}\"\n#include \"${rel}\"\n"
      "out vec4 rk_color;\nvoid main() { rk_color = vec4(0.0); }\n")
    run_checked("${rel} GLSL ES 3.00 frag" "${GLSLANG}" -l "-I${SHADER_DIR}" "${base}.frag")
  endif()
  if(NOT src MATCHES "#ifndef RK_[A-Z0-9_]+_GLSL")
    message("FAIL ${rel}: no `#ifndef RK_<NAME>_GLSL` include guard")
    math(EXPR failures "${failures} + 1")
  endif()

  set(vi 0)
  foreach(variant IN LISTS variants)
    # Macros go into the stub itself (glslangValidator's -D needs -l in front-end-only mode).
    set(defs "")
    if(NOT variant STREQUAL "<default>")
      string(REPLACE " " ";" words "${variant}")
      foreach(w IN LISTS words)
        if(w)
          string(REPLACE "=" " " w "${w}")
          string(APPEND defs "#define ${w}\n")
        endif()
      endforeach()
    endif()
    foreach(stage IN LISTS stages)
      if(stage STREQUAL "comp")
        set(body "layout(local_size_x = 1) in;\nvoid main() {}\n")
      else()
        set(body "layout(location = 0) out vec4 rk_color;\nvoid main() { rk_color = vec4(0.0); }\n")
      endif()
      # Include twice: the guard must make the second include a no-op.
      set(inc "${defs}#extension GL_GOOGLE_include_directive : require\n#include \"${rel}\"\n#include \"${rel}\"\n")
      set(base "${WORK_DIR}/${id}_v${vi}")
      file(WRITE "${base}.gl.${stage}" "#version 450 core\n${inc}${body}")
      file(WRITE "${base}.vk.${stage}" "#version 450\n${inc}${body}")
      run_checked("${rel} [${variant}] OpenGL 4.50 ${stage}"
        "${GLSLANG}" -G --target-env opengl "-I${SHADER_DIR}" -o "${base}.gl.${stage}.spv" "${base}.gl.${stage}")
      run_checked("${rel} [${variant}] OpenGL 4.50 ${stage} spirv-val"
        "${SPIRV_VAL}" --target-env opengl4.5 "${base}.gl.${stage}.spv")
      run_checked("${rel} [${variant}] Vulkan 1.2 ${stage}"
        "${GLSLANG}" -V --target-env vulkan1.2 "-I${SHADER_DIR}" -o "${base}.vk.${stage}.spv" "${base}.vk.${stage}")
      run_checked("${rel} [${variant}] Vulkan 1.2 ${stage} spirv-val"
        "${SPIRV_VAL}" --target-env vulkan1.2 "${base}.vk.${stage}.spv")
      if(es)
        file(WRITE "${base}.es.${stage}" "#version 310 es\nprecision highp float;\nprecision highp int;\n${inc}${body}")
        run_checked("${rel} [${variant}] GLSL ES 3.10 ${stage}"
          "${GLSLANG}" -l "-I${SHADER_DIR}" "${base}.es.${stage}")
      endif()
    endforeach()
    math(EXPR vi "${vi} + 1")
  endforeach()
  list(LENGTH variants nv)
  message("ok-checked ${rel}: ${nv} variant(s), ES 3.10 ${es}")
endforeach()

list(LENGTH files nfiles)
math(EXPR passed "${runs} - ${failures}")
message("validate_shaders: ${nfiles} files, ${runs} compilations/validations")
if(failures GREATER 0)
  message(FATAL_ERROR "validate_shaders: ${failures} failed")
endif()
