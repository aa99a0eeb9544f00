#!/usr/bin/env bash
# SPIR-V instruction counts of the interior-mapping traces, the figures quoted in
# shaders/raykit/interior_mapping.glsl: for each of rk_im_trace_grad, rk_im_trace and
# rk_im_trace_varying_grad, a fragment shader that calls it and writes uv, uv_dx, uv_dy, family,
# side, room and valid, compiled by glslangValidator -G, optimised by spirv-opt -O and counted by
# count_spirv (scripts/spirv_count.sh: body and ALU instructions).
# Usage: bash scripts/im_trace_spirv.sh [shader root, default shaders]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/spirv_count.sh
root="$(realpath "${1:-shaders}")"
for tool in glslangValidator spirv-opt spirv-dis; do
  command -v "$tool" >/dev/null || { echo "im_trace_spirv: $tool not found (scripts/setup.sh installs it)" >&2; exit 1; }
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "| trace | body | alu |"
echo "| --- | ---: | ---: |"
for fn in rk_im_trace_grad rk_im_trace rk_im_trace_varying_grad; do
  case $fn in
    rk_im_trace_grad) call="rk_im_trace_grad(p, cam, n, dpx, dpy, g)"; def="" ;;
    rk_im_trace) call="rk_im_trace(p, cam, n, g)"; def="" ;;
    rk_im_trace_varying_grad) call="rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, jit, seed)"; def="#define RK_IM_VARYING_WALLS 1" ;;
  esac
  cat > "$tmp/$fn.frag" <<EOT
#version 450
#extension GL_GOOGLE_include_directive : require
$def
#include "raykit/interior_mapping.glsl"
layout(location = 0) in vec3 p;
layout(location = 1) in vec3 cam;
layout(location = 2) in vec3 n;
layout(location = 3) in vec3 dpx;
layout(location = 4) in vec3 dpy;
layout(location = 5) flat in vec3 rs;
layout(location = 6) flat in vec3 org;
layout(location = 7) flat in vec3 jit;
layout(location = 8) flat in uint seed;
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
layout(location = 2) out ivec4 o2;
layout(location = 3) out ivec4 o3;
void main()
{
    rk_im_grid g;
    g.room_size = rs;
    g.origin = org;
    rk_im_hit h = $call;
    o0 = vec4(h.uv, h.uv_dx);
    o1 = vec4(h.uv_dy, 0.0, 0.0);
    o2 = ivec4(h.family, h.side, h.valid ? 1 : 0, 0);
    o3 = ivec4(h.room, 0);
}
EOT
  glslangValidator -G -I"$root" -S frag "$tmp/$fn.frag" -o "$tmp/$fn.spv" >/dev/null
  spirv-opt -O "$tmp/$fn.spv" -o "$tmp/$fn.opt.spv"
  spirv-dis "$tmp/$fn.opt.spv" -o "$tmp/$fn.spvasm"
  read -r body alu _ _ _ < <(count_spirv "$tmp/$fn.spvasm")
  echo "| $fn | $body | $alu |"
done
