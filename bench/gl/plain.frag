#version 450
// raykit bench — plain.frag: the baseline of bench_interior_gl, the thesis's "plain material":
// a lit diffuse facade texture whose alpha marks the windows (1 = window, the appendix's
// convention), and in the windows a cube-map reflection only (no interior). One 2D and one cube
// fetch per pixel.

layout(binding = 0) uniform sampler2D u_facade;   // RGB exterior, A = window mask
layout(binding = 5) uniform samplerCube u_env;    // environment (world-space directions)

in vec2 v_uv;
in vec3 v_obj_pos;
in vec3 v_refl_world;
in vec3 v_lighting;
layout(location = 0) out vec4 o_color;

void main()
{
    vec4 diffuse = texture(u_facade, v_uv);
    vec3 wall = diffuse.rgb * v_lighting;
    vec3 window = texture(u_env, v_refl_world).rgb;
    o_color = vec4(mix(wall, window, diffuse.a), 1.0);
}
