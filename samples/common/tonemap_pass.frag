#version 450
#extension GL_GOOGLE_include_directive : require
// raykit — tonemap_pass.frag: a full-screen tone-mapping pass (HDR texture in, display-encoded
// sRGB out) written for every target: the uniform block and the bindings make it valid for
// OpenGL 4.5, for Vulkan (SPIR-V) and, through SPIRV-Cross, for HLSL and MSL
// (tests/cross_compile.cmake; docs/integration.md). Choose the operator with RK_TONEMAP_OPERATOR
// (and RK_AGX_LOOK), e.g. from raykit::tonemap_defines() or raykit_tonemap_defines().
//
// Inputs: binding 0, the HDR colour (sampler2D, linear Rec.709); binding 1, the std140 block
// RkTonemapPass; location 0, the texture coordinate of the full-screen triangle.
#include "raykit/tonemap.glsl"

layout(binding = 0) uniform sampler2D u_hdr;
layout(std140, binding = 1) uniform RkTonemapPass {
    float exposure;        // multiplies the HDR colour first (exp2 of the EV from exposure.glsl)
    float reinhard_white;  // RK_TONEMAP_OPERATOR 1 only: the exposed luminance that maps to white
} u_pass;

layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main()
{
    const vec3 hdr = texture(u_hdr, v_uv).rgb * u_pass.exposure;
    o_color = vec4(rk_srgb_encode(rk_tonemap(hdr, u_pass.reinhard_white)), 1.0);
}
