# Every option macro of every shaders/raykit/*.glsl is checked: the default block
#   #ifndef RK_X / #define RK_X <default> / #endif
# must be followed by `#if <invalid> / #error "... must be ..."` (the message lists the valid
# values) and RK_OPTION_CHECK. For each such macro this script compiles, and expects to FAIL:
#   - with glslang (OpenGL 4.50): RK_X=-1 and RK_X=<largest valid + 1> (parsed from `RK_X > N`),
#     whose output must carry the "must be" message, and RK_X=aces (an identifier);
#   - with the C++ compiler, where include/raykit/<file>.hpp exists: RK_X=-1 ("must be") and
#     RK_X=aces.
# Files are globbed at test time: a new option macro is covered without editing CMake.
#
# cmake -DSHADER_DIR= -DINCLUDE_DIR= -DWORK_DIR= -DGLSLANG= -DCXX= -DLANG=glsl|cpp -P option_macros.cmake
cmake_policy(SET CMP0057 NEW)
foreach(v SHADER_DIR INCLUDE_DIR WORK_DIR GLSLANG CXX LANG)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "option_macros: -D${v}= is required")
  endif()
endforeach()
# Not integer options: a float (no #if can test it) and a function-like hook.
set(unchecked RK_IM_NUDGE RK_IM_NUDGE_TAG RK_SVO_LOAD)

file(GLOB files RELATIVE "${SHADER_DIR}/raykit" "${SHADER_DIR}/raykit/*.glsl")
list(SORT files)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(failures 0)
set(checked 0)

function(expect_failure label want_message)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(text "${out}${err}")
  if(rc EQUAL 0)
    message("FAIL ${label}: compiled, expected an error")
    math(EXPR f "${failures} + 1")
    set(failures ${f} PARENT_SCOPE)
  elseif(want_message AND NOT text MATCHES "must be")
    message("FAIL ${label}: no message listing the valid values\n${text}")
    math(EXPR f "${failures} + 1")
    set(failures ${f} PARENT_SCOPE)
  endif()
endfunction()

foreach(rel IN LISTS files)
  file(READ "${SHADER_DIR}/raykit/${rel}" src)
  get_filename_component(name "${rel}" NAME_WE)
  string(REGEX MATCHALL "#ifndef RK_[A-Z0-9_]+\n#define RK_[A-Z0-9_]+[^\n]*\n#endif\n[^\n]*" blocks "${src}")
  set(stage comp)
  if(src MATCHES "@rk-stages frag")
    set(stage frag)
  endif()
  foreach(b IN LISTS blocks)
    string(REGEX MATCH "#ifndef (RK_[A-Z0-9_]+)" _ "${b}")
    set(m "${CMAKE_MATCH_1}")
    if(m MATCHES "_GLSL$" OR m IN_LIST unchecked)
      continue()
    endif()
    string(REGEX MATCH "#ifndef ${m}\n#define ${m}[^\n]*\n#endif\n#if ([^\n]*)\n#error \"([^\"]*)\"\n#endif\nRK_OPTION_CHECK\\([a-z0-9_]+, ${m}\\);" ok "${src}")
    if(NOT ok)
      message("FAIL ${rel}: ${m} has no `#if ... #error \"...\"` range check and RK_OPTION_CHECK after its default")
      math(EXPR failures "${failures} + 1")
      continue()
    endif()
    set(cond "${CMAKE_MATCH_1}")
    set(values "-1;aces")
    if(cond MATCHES "${m} > ([0-9]+)")
      math(EXPR above "${CMAKE_MATCH_1} + 1")
      list(APPEND values "${above}")
    endif()
    math(EXPR checked "${checked} + 1")
    foreach(v IN LISTS values)
      set(want ON)
      if(v STREQUAL "aces")
        set(want OFF)  # an undeclared identifier: the compiler's own message
      endif()
      string(MAKE_C_IDENTIFIER "${m}_${v}" id)
      if(LANG STREQUAL "glsl")
        if(stage STREQUAL "comp")
          set(body "layout(local_size_x = 1) in;\nvoid main() {}\n")
        else()
          set(body "layout(location = 0) out vec4 rk_color;\nvoid main() { rk_color = vec4(0.0); }\n")
        endif()
        file(WRITE "${WORK_DIR}/${id}.${stage}"
          "#version 450 core\n#define ${m} ${v}\n#extension GL_GOOGLE_include_directive : require\n#include \"raykit/${rel}\"\n${body}")
        expect_failure("${rel}: GLSL ${m}=${v}" ${want} "${GLSLANG}" -G --target-env opengl "-I${SHADER_DIR}"
          -o "${WORK_DIR}/${id}.spv" "${WORK_DIR}/${id}.${stage}")
      elseif(EXISTS "${INCLUDE_DIR}/raykit/${name}.hpp" AND NOT v MATCHES "^[0-9]")
        file(WRITE "${WORK_DIR}/${id}.cpp" "#define ${m} ${v}\n#include \"raykit/${name}.hpp\"\nint main() { return 0; }\n")
        expect_failure("${rel}: C++ ${m}=${v}" ${want} "${CXX}" -std=c++17 -fsyntax-only "-I${INCLUDE_DIR}" "-I${SHADER_DIR}"
          "${WORK_DIR}/${id}.cpp")
      endif()
    endforeach()
  endforeach()
endforeach()
message("option_macros (${LANG}): ${checked} option macros checked")
if(checked LESS 20)
  message(FATAL_ERROR "option_macros: only ${checked} option macros found; the pattern no longer matches the files?")
endif()
if(failures GREATER 0)
  message(FATAL_ERROR "option_macros: ${failures} failed")
endif()
