#version 450 core
// raykit sample — tonemap_gallery/gallery.frag: one panel of the tone-mapping gallery.
//
// A panel is the 3-D view of scene.glsl over a chart of five luminance ramps from 1e-3 to 1e4 on a
// log scale (four saturated hues of equal luminance, then grey). The C++ side compiles this file
// once per panel with raykit::tonemap_defines(op, look): RK_TONEMAP_OPERATOR (and RK_AGX_LOOK for
// AgX) select the operator inside rk_tonemap() at compile time, so each program carries only the
// code of its own operator.
//
// GALLERY_MODE: 0 tone-map with rk_tonemap (default); 1 false colour of scene luminance, one band
// per stop; 2 raw scene radiance, unexposed (the float pass the CPU reads back for the exposure).
// Every pixel averages 3 x 3 samples after tone mapping (display-linear), then rk_srgb_encode.
#extension GL_GOOGLE_include_directive : require
#include "raykit/tonemap.glsl"
#include "scene.glsl"

#ifndef GALLERY_MODE
#define GALLERY_MODE 0
#endif

// All positions in pixels, y down. Panel-local coordinates have (0, 0) at the panel's top-left.
uniform vec4 u_panel;         // panel in the framebuffer: x0, y0 (top-left), width, height
uniform float u_fb_height;    // framebuffer height (gl_FragCoord is y up)
uniform float u_view_height;  // rows of the 3-D view at the top of the panel
uniform vec2 u_ramp_x;        // local x of luminance 1e-3 and 1e4 on the ramps
uniform vec4 u_strips;        // y0 of the first hue strip, strip height, pitch, y0 of the grey strip
uniform float u_grey_height;  // height of the grey strip
uniform float u_exposure;     // multiplies scene radiance before rk_tonemap
uniform float u_white;        // Reinhard's white (exposed), read by operator 1 only
uniform vec3 u_background;    // display-linear colour between the strips

layout(location = 0) out vec4 frag_color;

// Scene radiance at panel-local q; false on the background between and around the ramps.
bool panel_radiance(vec2 q, out vec3 hdr)
{
    hdr = vec3(0.0);
    if (q.y < u_view_height) {
        hdr = scene_radiance(q / vec2(u_panel.z, u_view_height), u_panel.z / u_view_height);
        return true;
    }
    if (q.x < u_ramp_x.x || q.x >= u_ramp_x.y) return false;
    float lum = pow(10.0, mix(-3.0, 4.0, (q.x - u_ramp_x.x) / (u_ramp_x.y - u_ramp_x.x)));
#if GALLERY_MODE == 1
    // The false-colour panel's chart is its legend: one bar over the height of all five ramps.
    if (q.y >= u_strips.x && q.y < u_strips.w + u_grey_height) {
        hdr = vec3(lum);
        return true;
    }
#endif
    for (int i = 0; i < 4; ++i) {
        float y0 = u_strips.x + float(i) * u_strips.z;
        if (q.y >= y0 && q.y < y0 + u_strips.y) {
            hdr = scene_hue(i) * lum;
            return true;
        }
    }
    if (q.y >= u_strips.w && q.y < u_strips.w + u_grey_height) {
        hdr = vec3(lum);
        return true;
    }
    return false;
}

// Google's Turbo colour map (Mikhailov 2019, polynomial fit, Apache-2.0); sRGB-encoded output.
vec3 turbo(float x)
{
    const vec4 kRed4 = vec4(0.13572138, 4.61539260, -42.66032258, 132.13108234);
    const vec4 kGreen4 = vec4(0.09140261, 2.19418839, 4.84296658, -14.18503333);
    const vec4 kBlue4 = vec4(0.10667330, 12.64194608, -60.58204836, 110.36276771);
    const vec2 kRed2 = vec2(-152.94239396, 59.28637943);
    const vec2 kGreen2 = vec2(4.27729857, 2.82956604);
    const vec2 kBlue2 = vec2(-89.90310912, 27.34824973);
    x = clamp(x, 0.0, 1.0);
    vec4 v4 = vec4(1.0, x, x * x, x * x * x);
    vec2 v2 = v4.zw * v4.z;
    return vec3(dot(v4, kRed4) + dot(v2, kRed2), dot(v4, kGreen4) + dot(v2, kGreen2),
                dot(v4, kBlue4) + dot(v2, kBlue2));
}

// Scene luminance in false colour: Turbo over log2 L from 1e-3 (blue) to 1e4 (dark red), one flat
// band per stop, alternate bands slightly darker so that neighbours stay apart.
vec3 false_colour(vec3 hdr)
{
    float stop = floor(log2(max(rk_luminance(hdr), 1e-12)));
    float lo = log2(1e-3);
    float hi = log2(1e4);
    vec3 c = rk_srgb_decode(turbo((stop + 0.5 - lo) / (hi - lo)));
    return mod(stop, 2.0) == 0.0 ? c : c * 0.8;
}

void main()
{
    vec2 q = vec2(gl_FragCoord.x - u_panel.x, (u_fb_height - gl_FragCoord.y) - u_panel.y);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            vec2 s = q + (vec2(float(i), float(j)) - 1.0) / 3.0;  // q is the pixel centre
            vec3 hdr;
            bool on = panel_radiance(s, hdr);
#if GALLERY_MODE == 2
            sum += hdr;
#elif GALLERY_MODE == 1
            sum += on ? false_colour(hdr) : u_background;
#else
            sum += on ? rk_tonemap(hdr * u_exposure, u_white) : u_background;
#endif
        }
    }
    sum /= 9.0;
#if GALLERY_MODE == 2
    frag_color = vec4(sum, 1.0);
#else
    frag_color = vec4(rk_srgb_encode(sum), 1.0);
#endif
}
