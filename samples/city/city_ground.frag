#version 450 core
// raykit sample city — city_ground.frag: streets, sidewalks and courtyards (procedural), lit by
// the shadowed sun, the sky and, at dusk, pools of street light.
#extension GL_GOOGLE_include_directive : require
#include "city_common.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) flat in int v_id;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_aux;
void main()
{
    float kind;
    vec3 albedo = city_ground_albedo(v_world.xz, kind);
    vec3 n = vec3(0.0, 1.0, 0.0);
    vec3 light = city_outdoor_light(v_world, n, 0.85) + city_street_light(v_world);
    vec3 c = albedo * light;
    // A little specular sheen of the sky on the asphalt at grazing angles.
    vec3 to_eye = normalize(u_cam.xyz - v_world);
    float f = 0.04 + 0.96 * pow(clamp(1.0 - to_eye.y, 0.0, 1.0), 5.0);
    c += kind * f * 0.06 * city_sky(reflect(-to_eye, n));
    // Aerial perspective: distant ground fades into the horizon colour.
    float dist = length(u_cam.xyz - v_world);
    c = mix(c, u_sky_horizon.rgb, 1.0 - exp(-dist / 1500.0));
    o_color = vec4(c, 1.0);
    o_aux = vec4(0.0);
}
