#version 450
#extension GL_GOOGLE_include_directive : require
// A user's shader: window reflectance for a table of cosines.
#include "raykit/fresnel.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Data { float values[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    values[i] = rk_fresnel_window(values[i], 1.52f, 2.0f);
}
