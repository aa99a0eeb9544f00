# raykit_compile_shaders() refuses what would go wrong silently: each case configures a tiny
# project and expects the configure step to fail with the message given.
#
# cmake -DCMAKE_DIR=<raykit>/cmake -DSHADER_DIR=<raykit>/shaders -DWORK_DIR=... -P compile_shaders_errors.cmake
foreach(v CMAKE_DIR SHADER_DIR WORK_DIR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "compile_shaders_errors: -D${v}= is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
set(cases
  "raykit_compile_shaders(t SOURCE s.comp)|unknown arguments 'SOURCE"
  "raykit_compile_shaders(t SOURCES s.comp DEFINES 1X=2)|malformed DEFINES entry '1X=2'"
  "raykit_compile_shaders(t SOURCES s.comp TARGET_ENV vulkan2)|TARGET_ENV must be"
  "raykit_compile_shaders(t SOURCES s.comp OUT_VAR)|no value after OUT_VAR"
  "raykit_compile_shaders(t SOURCES s.comp VARIANT a/b)|VARIANT 'a/b' must be"
  "raykit_compile_shaders(a SOURCES s.comp TARGET_ENV opengl)\nraykit_compile_shaders(b SOURCES s.comp TARGET_ENV vulkan1.2)|already written by another call")
set(failures 0)
set(i 0)
foreach(c IN LISTS cases)
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 call)
  list(GET parts 1 want)
  set(dir "${WORK_DIR}/case${i}")
  file(WRITE "${dir}/s.comp" "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n")
  file(WRITE "${dir}/CMakeLists.txt" "cmake_minimum_required(VERSION 3.21)\nproject(t NONE)\n"
    "set(RAYKIT_SHADER_DIR \"${SHADER_DIR}\")\ninclude(\"${CMAKE_DIR}/RaykitShaders.cmake\")\n${call}\n")
  execute_process(COMMAND "${CMAKE_COMMAND}" -S "${dir}" -B "${dir}/build" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX REPLACE "[ \n]+" " " flat "${out}${err}")
  if(rc EQUAL 0)
    message("FAIL: configured without error: ${call}")
    math(EXPR failures "${failures} + 1")
  else()
    string(FIND "${flat}" "${want}" at)
    if(at LESS 0)
      message("FAIL: ${call}: no '${want}' in\n${out}${err}")
      math(EXPR failures "${failures} + 1")
    endif()
  endif()
  math(EXPR i "${i} + 1")
endforeach()
message("compile_shaders_errors: ${i} cases")
if(failures GREATER 0)
  message(FATAL_ERROR "compile_shaders_errors: ${failures} failed")
endif()
