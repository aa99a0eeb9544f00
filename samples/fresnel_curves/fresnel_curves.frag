#version 450 core
// raykit sample — fresnel_curves.frag: plots Fresnel reflectance against the angle of incidence.
//
// Every curve is evaluated per pixel by raykit's own GLSL (fresnel.glsl, inlined at load time by
// raykit::load_shader_file; glslangValidator resolves the include itself through the extension
// below). A curve is drawn anti-aliased from the pixel's distance to it: the curve is sampled at a
// few x positions around the pixel (one pixel apart) and the distance to that short polyline gives
// a constant on-screen line width, also where the curve is near vertical (grazing incidence, the
// critical angle) and at its kinks (the onset of total internal reflection).
#extension GL_GOOGLE_include_directive : require
#include "raykit/fresnel.glsl"

#define CURVES 8
#define HALF_WINDOW 4  // samples either side of the pixel: covers line half-widths up to ~3 px

// All positions in pixels, origin top-left, y down (as the CPU-side text overlay).
// u_data: pixel rectangle of the data domain [0, 90] degrees x [0, 1]: x0, y0 (R = 1), x1, y1 (R = 0).
// u_frame: pixel rectangle of the plot frame (a little larger than u_data).
layout(location = 0) uniform vec2 u_size;             // framebuffer size
layout(location = 1) uniform vec4 u_data;
layout(location = 2) uniform vec4 u_frame;
layout(location = 3) uniform float u_eta;             // relative index of the glass, n_glass / n_air
layout(location = 4) uniform vec4 u_color[CURVES];    // locations 4..11
layout(location = 12) uniform float u_width[CURVES];  // full line width in pixels

layout(location = 0) out vec4 frag_color;

const vec3 kBackground = vec3(0.055f, 0.063f, 0.078f);
const vec3 kPlotArea = vec3(0.085f, 0.095f, 0.118f);
const vec3 kGrid = vec3(0.20f, 0.22f, 0.26f);
const vec3 kFrame = vec3(0.42f, 0.45f, 0.52f);
const vec3 kMarker = vec3(0.55f, 0.58f, 0.65f);

// The reflectance of every curve at one angle (degrees). Order = legend order in main.cpp.
void eval_curves(float deg, out float r[CURVES])
{
    float c = cos(radians(clamp(deg, 0.0f, 90.0f)));
    vec2 sp = rk_fresnel_dielectric_sp(c, u_eta);
    r[0] = rk_fresnel_dielectric(c, u_eta);                         // exact, unpolarised
    r[1] = sp.x;                                                    // Rs
    r[2] = sp.y;                                                    // Rp
    r[3] = rk_fresnel_schlick(c, rk_f0_from_eta(u_eta));            // Schlick
    r[4] = rk_fresnel_dielectric_fast(c, rk_fresnel_fast_params(u_eta));  // fast approximation
    r[5] = rk_fresnel_slab_sp(sp);                                  // one pane
    r[6] = rk_fresnel_glazing_sp(sp, 2.0f);                         // two panes
    r[7] = rk_fresnel_dielectric(c, 1.0f / u_eta);                  // internal: glass -> air
}

float seg_dist(vec2 p, vec2 a, vec2 b)
{
    vec2 ab = b - a;
    float t = clamp(dot(p - a, ab) / max(dot(ab, ab), 1e-12f), 0.0f, 1.0f);
    return length(p - (a + t * ab));
}

// Coverage of a line of full width w at distance d (1-pixel linear ramp = box-filtered edge).
float coverage(float d, float w) { return clamp(0.5f * w + 0.5f - d, 0.0f, 1.0f); }

void main()
{
    vec2 p = vec2(gl_FragCoord.x, u_size.y - gl_FragCoord.y);  // pixel centre, y down
    vec3 col = kBackground;

    bool in_frame = p.x >= u_frame.x && p.x <= u_frame.z && p.y >= u_frame.y && p.y <= u_frame.w;
    if (!in_frame) {
        frag_color = vec4(col, 1.0f);
        return;
    }
    col = kPlotArea;

    vec2 scale = vec2(90.0f / (u_data.z - u_data.x), 1.0f / (u_data.w - u_data.y));  // data units per pixel
    float deg = (p.x - u_data.x) * scale.x;
    float refl = (u_data.w - p.y) * scale.y;

    // Grid: every 10 degrees and every 0.1, one pixel wide.
    float gx = abs(deg / 10.0f - round(deg / 10.0f)) * 10.0f / scale.x;
    float gy = abs(refl / 0.1f - round(refl / 0.1f)) * 0.1f / scale.y;
    bool in_data_x = deg > -0.5f * scale.x && deg < 90.0f + 0.5f * scale.x;
    bool in_data_y = refl > -0.5f * scale.y && refl < 1.0f + 0.5f * scale.y;
    float grid = max(in_data_y ? coverage(gx, 1.0f) : 0.0f, in_data_x ? coverage(gy, 1.0f) : 0.0f);
    col = mix(col, kGrid, grid);

    // Dashed markers at the critical angle of glass -> air and at Brewster's angle (Rp = 0).
    float crit_x = u_data.x + degrees(rk_critical_angle(1.0f / u_eta)) / scale.x;
    float brew_x = u_data.x + degrees(rk_brewster_angle(u_eta)) / scale.x;
    float dash = step(0.5f, fract(p.y / 10.0f)) * (in_data_y ? 1.0f : 0.0f);
    col = mix(col, kMarker, dash * max(coverage(abs(p.x - crit_x), 1.0f), coverage(abs(p.x - brew_x), 1.0f)));

    // Curves: distance to the polyline through samples one pixel apart around p.x.
    float dmin[CURVES];
    float prev[CURVES];
    float cur[CURVES];
    for (int i = 0; i < CURVES; ++i) dmin[i] = 1e9f;
    float x0 = floor(p.x) + 0.5f - float(HALF_WINDOW);
    eval_curves((x0 - u_data.x) * scale.x, prev);
    for (int k = 1; k <= 2 * HALF_WINDOW; ++k) {
        float xa = x0 + float(k - 1);
        float xb = xa + 1.0f;
        eval_curves((xb - u_data.x) * scale.x, cur);
        bool inside = xa >= u_data.x - 0.5f && xb <= u_data.z + 0.5f;
        for (int i = 0; i < CURVES; ++i) {
            vec2 a = vec2(xa, u_data.w - prev[i] / scale.y);
            vec2 b = vec2(xb, u_data.w - cur[i] / scale.y);
            if (inside) dmin[i] = min(dmin[i], seg_dist(p, a, b));
            prev[i] = cur[i];
        }
    }
    // Back to front: the wide exact curve goes under the thin fast approximation (index 4), which
    // overlaps it within 1.7e-3.
    const int order[CURVES] = int[CURVES](6, 5, 1, 2, 7, 3, 0, 4);
    for (int j = 0; j < CURVES; ++j) {
        int i = order[j];
        col = mix(col, u_color[i].rgb, u_color[i].a * coverage(dmin[i], u_width[i]));
    }

    // Frame: one pixel on the frame's border.
    float fd = min(min(p.x - u_frame.x, u_frame.z - p.x), min(p.y - u_frame.y, u_frame.w - p.y));
    col = mix(col, kFrame, coverage(fd, 1.0f));

    frag_color = vec4(col, 1.0f);
}
