#version 450
// raykit bench — raykit_building.vert: the vertex stage of the benchmark's own raykit material
// (raykit_building.frag). As building.vert, plus the object-space normal and the world position.

layout(location = 0) in vec3 a_position;   // object space
layout(location = 1) in vec3 a_normal;     // object space, unit
layout(location = 2) in vec2 a_uv;         // facade UV, one unit per window tile

uniform mat4 u_view_proj;
uniform mat4 u_model;
uniform float u_uv_multiplier;

invariant gl_Position;
out vec2 v_uv;
out vec3 v_obj_pos;
out vec3 v_obj_normal;
out vec3 v_world_pos;
out vec3 v_lighting;

void main()
{
    vec4 world = u_model * vec4(a_position, 1.0);
    gl_Position = u_view_proj * world;
    v_uv = a_uv * u_uv_multiplier;
    v_obj_pos = a_position;
    v_obj_normal = a_normal;
    v_world_pos = world.xyz;
    const vec3 light_dir = vec3(0.5, 0.33166, 0.8);
    v_lighting = clamp(dot(a_normal, light_dir), 0.0, 1.0) * vec3(1.0, 1.0, 0.9) + vec3(0.3, 0.3, 0.4);
}
