# raykit's GLSL to HLSL and MSL through SPIRV-Cross: samples/common/tonemap_pass.frag, for every
# tone-mapping operator, is compiled to Vulkan SPIR-V (glslang, spirv-val), translated by
# spirv-cross to HLSL (shader model 5.0) and MSL (2.0); the HLSL is compiled back by glslang's HLSL
# front end and validated, the MSL is checked for its entry point (no Metal compiler on Linux).
#
# cmake -DSAMPLES_DIR= -DSHADER_DIR= -DWORK_DIR= -DGLSLANG= -DSPIRV_VAL= -DSPIRV_CROSS= -P cross_compile.cmake
foreach(v SAMPLES_DIR SHADER_DIR WORK_DIR GLSLANG SPIRV_VAL SPIRV_CROSS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "cross_compile: -D${v}= is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(failures 0)
function(step label)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR "${out}${err}" MATCHES "WARNING|[Ww]arning:")
    message("FAIL ${label}\n  ${ARGN}\n${out}${err}")
    math(EXPR f "${failures} + 1")
    set(failures ${f} PARENT_SCOPE)
  endif()
endfunction()
set(src "${SAMPLES_DIR}/common/tonemap_pass.frag")
foreach(op RANGE 0 8)
  set(b "${WORK_DIR}/tonemap_op${op}")
  step("op ${op}: GLSL -> SPIR-V (Vulkan 1.2)" "${GLSLANG}" -V --target-env vulkan1.2 "-I${SHADER_DIR}"
    -DRK_TONEMAP_OPERATOR=${op} -o "${b}.spv" "${src}")
  step("op ${op}: spirv-val" "${SPIRV_VAL}" --target-env vulkan1.2 "${b}.spv")
  step("op ${op}: SPIR-V -> HLSL" "${SPIRV_CROSS}" "${b}.spv" --hlsl --shader-model 50 --output "${b}.hlsl")
  step("op ${op}: HLSL -> SPIR-V (glslang HLSL front end)" "${GLSLANG}" -D -V -S frag -e main -o "${b}.hlsl.spv" "${b}.hlsl")
  step("op ${op}: spirv-val of the HLSL build" "${SPIRV_VAL}" "${b}.hlsl.spv")
  step("op ${op}: SPIR-V -> MSL" "${SPIRV_CROSS}" "${b}.spv" --msl --msl-version 20000 --output "${b}.metal")
  if(EXISTS "${b}.metal")
    file(READ "${b}.metal" msl)
    if(NOT msl MATCHES "fragment main0_out main0\\(")
      message("FAIL op ${op}: no fragment entry point in ${b}.metal")
      math(EXPR failures "${failures} + 1")
    endif()
  endif()
  # GL SPIR-V too (ARB_gl_spirv).
  step("op ${op}: GLSL -> SPIR-V (OpenGL)" "${GLSLANG}" -G --target-env opengl "-I${SHADER_DIR}"
    -DRK_TONEMAP_OPERATOR=${op} -o "${b}.gl.spv" "${src}")
endforeach()

# The sample interior material in its uniform-block form (RK_IM_BUILDING_BLOCK=1), both stages,
# under feature sets that together use every texture mode and every optional feature.
set(variants
  "RK_IM_SHADING=1"
  "RK_IM_SHADING=2;RK_IM_ROOM_LIGHTS=1;RK_IM_FURNITURE_LAYERS=2;RK_IM_FADE=1;RK_IM_REFLECTION=1;RK_IM_BUILDING_OUTPUT=1"
  "RK_IM_SHADING=0;RK_IM_BUILDING_FACADE=1;RK_IM_COMPOSE_MODE=1"
  "RK_IM_SHADING=3;RK_IM_VARYING_WALLS=1;RK_IM_FURNITURE_LAYERS=4;RK_IM_FURNITURE_FLIPBOOK=0")
set(vi 0)
foreach(v IN LISTS variants)
  string(REPLACE "|" ";" defs "${v}")
  set(dflags -DRK_IM_BUILDING_BLOCK=1)
  foreach(d IN LISTS defs)
    list(APPEND dflags "-D${d}")
  endforeach()
  foreach(stage frag vert)
    set(b "${WORK_DIR}/interior_v${vi}_${stage}")
    set(src "${SAMPLES_DIR}/common/interior_building.${stage}")
    step("material [${v}] ${stage}: GLSL -> SPIR-V (Vulkan 1.2)" "${GLSLANG}" -V --target-env vulkan1.2 "-I${SHADER_DIR}"
      ${dflags} -o "${b}.spv" "${src}")
    step("material [${v}] ${stage}: spirv-val" "${SPIRV_VAL}" --target-env vulkan1.2 "${b}.spv")
    step("material [${v}] ${stage}: GLSL -> SPIR-V (OpenGL)" "${GLSLANG}" -G --target-env opengl "-I${SHADER_DIR}"
      ${dflags} -o "${b}.gl.spv" "${src}")
    step("material [${v}] ${stage}: spirv-val (OpenGL)" "${SPIRV_VAL}" --target-env opengl4.5 "${b}.gl.spv")
    step("material [${v}] ${stage}: SPIR-V -> HLSL" "${SPIRV_CROSS}" "${b}.spv" --hlsl --shader-model 50 --output "${b}.hlsl")
    step("material [${v}] ${stage}: HLSL -> SPIR-V" "${GLSLANG}" -D -V -S ${stage} -e main -o "${b}.hlsl.spv" "${b}.hlsl")
    step("material [${v}] ${stage}: SPIR-V -> MSL" "${SPIRV_CROSS}" "${b}.spv" --msl --msl-version 20000 --output "${b}.metal")
  endforeach()
  math(EXPR vi "${vi} + 1")
endforeach()
message("cross_compile: tonemap_pass.frag (9 operators) and the interior material's block form (4 feature sets, 2 stages): Vulkan/GL SPIR-V, HLSL (recompiled), MSL")
if(failures GREATER 0)
  message(FATAL_ERROR "cross_compile: ${failures} steps failed")
endif()
