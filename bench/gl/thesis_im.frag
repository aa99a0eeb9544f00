#version 450
// raykit bench — thesis_im.frag: a port to GLSL 4.50 of the interior-mapping pixel program of van
// Dongen's thesis ("Using raycasting in GPU shaders to enhance real-time graphics", 2009, appendix),
// written for this benchmark from a structural description of that program, not copied. It keeps
// the thesis's cost structure, which is what the benchmark measures:
//   - vectorised plane search: floor(P * f) + step(0, dir), divided by f, one vec3 for all axes;
//   - ray fractions of the three plane families in one vec3 division (no guard against dir_i = 0,
//     as in the thesis: an axis-parallel ray gives +inf, which the step selection never picks);
//   - all four interior textures sampled unconditionally (no branches, as ps_2_0 required);
//   - step/mix selection: floor vs ceiling by the sign of dir.y, x-wall vs z-wall by the smaller
//     fraction (ties to the x-wall), walls vs floor/ceiling (ties to walls);
//   - window colour = cube reflection + interior (additive, no Fresnel); output =
//     mix(lit wall, window, diffuse.a).
// One deliberate difference: the hit UVs are multiplied by the wall frequencies, so that a texture
// tile spans one room (the thesis uses object units and notes that they "can be multiplied by some
// constant"): two vec2 multiplies more per pixel.

layout(binding = 0) uniform sampler2D u_facade;     // RGB exterior, A = window mask
layout(binding = 1) uniform sampler2D u_ceiling;
layout(binding = 2) uniform sampler2D u_floor;
layout(binding = 3) uniform sampler2D u_wall_xy;    // walls of constant z
layout(binding = 4) uniform sampler2D u_wall_zy;    // walls of constant x
layout(binding = 5) uniform samplerCube u_env;

uniform vec3 u_wall_freq;    // rooms per object unit along x, y, z (1 / room size)
uniform vec3 u_cam_obj;      // camera position in object space

in vec2 v_uv;
in vec3 v_obj_pos;
in vec3 v_refl_world;
in vec3 v_lighting;
layout(location = 0) out vec4 o_color;

void main()
{
    vec3 dir = v_obj_pos - u_cam_obj;                       // fraction 1 at the surface
    vec3 planes = floor(v_obj_pos * u_wall_freq) + step(vec3(0.0), dir);
    planes /= u_wall_freq;                                  // next plane of each family, object units
    vec3 alpha = (planes - u_cam_obj) / dir;                // ray fractions, three at once

    vec2 uv_xy = (u_cam_obj.xy + alpha.z * dir.xy) * u_wall_freq.xy;   // hit on a z plane
    vec2 uv_xz = (u_cam_obj.xz + alpha.y * dir.xz) * u_wall_freq.xz;   // hit on a y plane
    vec2 uv_zy = (u_cam_obj.zy + alpha.x * dir.zy) * u_wall_freq.zy;   // hit on an x plane

    vec4 ceiling = texture(u_ceiling, uv_xz);
    vec4 floor_c = texture(u_floor, uv_xz);
    vec4 wall_xy = texture(u_wall_xy, uv_xy);
    vec4 wall_zy = texture(u_wall_zy, uv_zy);

    vec4 vertical = mix(floor_c, ceiling, step(0.0, dir.y));
    float sx = step(alpha.x, alpha.z);
    vec4 wall = mix(wall_xy, wall_zy, sx);
    float wall_alpha = mix(alpha.z, alpha.x, sx);
    float sw = step(wall_alpha, alpha.y);
    vec4 interior = mix(vertical, wall, sw);

    vec4 diffuse = texture(u_facade, v_uv);
    vec4 wall_colour = vec4(diffuse.rgb * v_lighting, 1.0);
    vec4 window_colour = texture(u_env, v_refl_world) + interior;
    o_color = vec4(mix(wall_colour, window_colour, diffuse.a).rgb, 1.0);
}
