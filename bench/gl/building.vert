#version 450
// raykit bench — building.vert: the vertex stage of the plain material and of the thesis port
// (bench_interior_gl). One mesh holds every building of the grid, so object space is the mesh's
// space (as in the thesis's z-cull test); u_model places it in the world.
//
// Outputs, as the thesis's appendix vertex program computes them (written from the description in
// notes §2.6, GLSL 4.50): the exterior UV times a multiplier, the object-space position unchanged
// (interior mapping's input), the reflection vector in world space (so reflections do not turn
// with the object) and a hard-coded directional light on the object-space normal (saturated dot
// times (1, 1, 0.9) plus ambient (0.3, 0.3, 0.4)). `invariant gl_Position` so that the depth-only
// pre-pass and the colour pass produce identical depths (GL_EQUAL depth test).

layout(location = 0) in vec3 a_position;   // object space
layout(location = 1) in vec3 a_normal;     // object space, unit
layout(location = 2) in vec2 a_uv;         // facade UV, one unit per window tile

uniform mat4 u_view_proj;
uniform mat4 u_model;
uniform vec3 u_cam_world;
uniform float u_uv_multiplier;

invariant gl_Position;
out vec2 v_uv;
out vec3 v_obj_pos;
out vec3 v_refl_world;
out vec3 v_lighting;

void main()
{
    vec4 world = u_model * vec4(a_position, 1.0);
    gl_Position = u_view_proj * world;
    v_uv = a_uv * u_uv_multiplier;
    v_obj_pos = a_position;
    // As in the appendix: the normal goes through the model's upper 3x3 (no inverse transpose), the
    // incident vector is not normalised (a cube lookup does not care).
    vec3 n_world = mat3(u_model) * a_normal;
    v_refl_world = reflect(world.xyz - u_cam_world, n_world);
    const vec3 light_dir = vec3(0.5, 0.33166, 0.8);
    v_lighting = clamp(dot(a_normal, light_dir), 0.0, 1.0) * vec3(1.0, 1.0, 0.9) + vec3(0.3, 0.3, 0.4);
}
