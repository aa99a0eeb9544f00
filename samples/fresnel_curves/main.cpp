// raykit sample — fresnel_curves: a plot of Fresnel reflectance against the angle of incidence for
// glass (n = 1.52), rendered headless on the GPU.
//
// Every curve is computed per pixel by raykit's GLSL (shaders/raykit/fresnel.glsl) in
// fresnel_curves.frag, which draws them as anti-aliased lines over a grid. The text (title, tick
// labels, legend) comes from stb_easy_font through samples/common/rk_text.hpp, which turns strings
// into quads on the CPU and draws them in a second, blended pass with a trivial shader. The few numbers printed in the labels (critical
// and Brewster angles) come from the C++ build of the same fresnel.glsl.
//
// Usage: fresnel_curves [out.png]   (default fresnel_curves.png)
// Exit codes: 0 written; 1 error; 77 no OpenGL 4.5 context (skip; 1 instead when CI=true).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "raykit/fresnel.hpp"
#include "raykit/shader_source.hpp"
#include "rk_gl.hpp"
#include "rk_text.hpp"

#include "rk_png.hpp"

namespace {

constexpr int kWidth = 1200;
constexpr int kHeight = 800;
constexpr float kEta = 1.52f;  // window glass, relative to air

// Layout in pixels (origin top-left, y down). The data domain [0°, 90°] x [0, 1] maps to
// 12 px per degree and 600 px per unit, so every grid line falls on a pixel centre.
constexpr float kDataLeft = 100.5f;
constexpr float kDataTop = 88.5f;
constexpr float kDataRight = kDataLeft + 1080.0f;
constexpr float kDataBottom = kDataTop + 600.0f;
constexpr float kFramePad = 10.0f;

using rkgl::Rgba;

Rgba rgb(float r, float g, float b, float a = 1.0f) { return rkgl::rgba(r, g, b, a); }

struct Curve {
    const char* label;
    const char* code;
    float r, g, b;
    float width;  // full line width, pixels
};

// Same order as eval_curves() in fresnel_curves.frag.
const Curve kCurves[8] = {
    {"exact, unpolarised", "rk_fresnel_dielectric", 0.96f, 0.96f, 0.96f, 4.5f},
    {"Rs, s-polarised", "rk_fresnel_dielectric_sp .x", 0.32f, 0.62f, 1.00f, 2.5f},
    {"Rp, p-polarised", "rk_fresnel_dielectric_sp .y", 0.30f, 0.86f, 0.52f, 2.5f},
    {"Schlick", "rk_fresnel_schlick, rk_f0_from_eta", 1.00f, 0.58f, 0.12f, 2.5f},
    {"fast approximation", "rk_fresnel_dielectric_fast", 0.92f, 0.16f, 0.48f, 1.6f},
    {"one pane, per polarisation", "rk_fresnel_slab_sp", 0.98f, 0.86f, 0.30f, 2.5f},
    {"two panes", "rk_fresnel_glazing_sp, panes = 2", 0.74f, 0.56f, 1.00f, 2.5f},
    {"internal, glass -> air", "rk_fresnel_dielectric, eta = 1/1.52", 1.00f, 0.36f, 0.30f, 2.5f},
};

// The overlay: legend boxes and text, drawn in one blended pass by rk_text.hpp.
using Overlay = rkgl::TextOverlay;

const char* kFullscreenVert = R"(#version 450 core
// A triangle covering the viewport, from gl_VertexID alone (no vertex buffer).
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

std::string fmt(const char* format, double v)
{
    char b[64];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

// Largest |approximation - exact| over 0°..90° (C++ build of fresnel.glsl), and where.
struct MaxError {
    float error = 0.0f;
    float degrees = 0.0f;
};

template <class F>
MaxError max_error_vs_exact(F approx)
{
    MaxError m;
    for (int i = 0; i <= 9000; ++i) {
        const float deg = 0.01f * static_cast<float>(i);
        const float c = std::cos(deg * RK_PI / 180.0f);
        const float e = std::fabs(approx(c) - raykit::rk_fresnel_dielectric(c, kEta));
        if (e > m.error) m = {e, deg};
    }
    return m;
}

void build_overlay(Overlay& o, const std::string& renderer)
{
    const Rgba text = rgb(0.90f, 0.91f, 0.94f);
    const Rgba dim = rgb(0.60f, 0.63f, 0.70f);
    const Rgba code = rgb(0.56f, 0.70f, 0.80f);
    const std::string deg = "\xc2\xb0";

    // Title and subtitle.
    o.text(kDataLeft - 10.0f, 14.0f, "Fresnel reflectance of glass, n = 1.52", 3.0f, text);
    o.text(kDataLeft - 10.0f, 48.0f, "raykit fresnel.glsl evaluated per pixel on " + renderer, 2.0f, dim);

    // Tick labels.
    for (int d = 0; d <= 90; d += 10) {
        const std::string s = std::to_string(d) + deg;
        const float x = kDataLeft + 12.0f * static_cast<float>(d);
        o.text(std::round(x - 0.5f * Overlay::width(s, 2.0f)), kDataBottom + kFramePad + 8.0f, s, 2.0f, text);
    }
    for (int i = 0; i <= 10; ++i) {
        const std::string s = fmt("%.1f", 0.1 * i);
        const float y = kDataBottom - 60.0f * static_cast<float>(i);
        o.text(std::round(kDataLeft - kFramePad - 8.0f - Overlay::width(s, 2.0f)), std::round(y - 7.0f), s, 2.0f,
               text);
    }
    // Axis titles.
    const std::string xt = "angle of incidence";
    o.text(std::round(0.5f * (kDataLeft + kDataRight - Overlay::width(xt, 2.0f))), kDataBottom + kFramePad + 38.0f,
           xt, 2.0f, text);
    const std::string yt = "reflectance";
    o.text(14.0f, std::round(0.5f * (kDataTop + kDataBottom + Overlay::width(yt, 2.0f))), yt, 2.0f, text, true);

    // Markers (the dashed lines are drawn by the shader from the same functions).
    const float crit = raykit::rk_critical_angle(1.0f / kEta) * 180.0f / RK_PI;
    const float brew = raykit::rk_brewster_angle(kEta) * 180.0f / RK_PI;
    const float crit_x = std::round(kDataLeft + 12.0f * crit + 8.0f);
    const float brew_x = std::round(kDataLeft + 12.0f * brew + 8.0f);
    const Rgba plot_area = rgb(0.085f, 0.095f, 0.118f);  // kPlotArea in the shader: hides the grid behind the notes
    o.rect(crit_x - 4.0f, kDataTop + 12.0f, crit_x + Overlay::width("(glass -> air)", 2.0f) + 2.0f, kDataTop + 74.0f,
           plot_area);
    o.rect(brew_x - 4.0f, kDataTop + 12.0f, brew_x + Overlay::width("Brewster angle", 2.0f) + 2.0f, kDataTop + 74.0f,
           plot_area);
    o.text(crit_x, kDataTop + 16.0f, "critical angle", 2.0f, dim);
    o.text(crit_x, kDataTop + 36.0f, fmt("%.2f", crit) + deg, 2.0f, dim);
    o.text(crit_x, kDataTop + 56.0f, "(glass -> air)", 2.0f, dim);
    o.text(brew_x, kDataTop + 16.0f, "Brewster angle", 2.0f, dim);
    o.text(brew_x, kDataTop + 36.0f, fmt("%.2f", brew) + deg, 2.0f, dim);
    o.text(brew_x, kDataTop + 56.0f, "(Rp = 0)", 2.0f, dim);

    // Legend, top left of the plot where every curve is low.
    const float lx = kDataLeft + 6.0f;
    const float ly = kDataTop + 8.0f;
    const float row = 44.0f;
    float lw = 0.0f;
    for (const Curve& c : kCurves) {
        lw = std::max(lw, std::max(Overlay::width(c.label, 2.0f), Overlay::width(c.code, 2.0f)));
    }
    o.rect(lx, ly, lx + lw + 74.0f, ly + 8.0f * row + 14.0f, rgb(0.03f, 0.035f, 0.045f, 0.88f));
    for (int i = 0; i < 8; ++i) {
        const Curve& c = kCurves[i];
        const float y = ly + 12.0f + row * static_cast<float>(i);
        const float sx = lx + 12.0f;
        const float sw = std::max(std::round(c.width), 2.0f);
        if (i == 4) {  // the fast approximation is drawn as a thin line over the exact one
            const Curve& e = kCurves[0];
            const float ew = std::round(e.width);
            o.rect(sx, y + 7.0f - std::floor(0.5f * ew), sx + 44.0f, y + 7.0f - std::floor(0.5f * ew) + ew,
                   rgb(e.r, e.g, e.b));
        }
        o.rect(sx, y + 7.0f - std::floor(0.5f * sw), sx + 44.0f, y + 7.0f - std::floor(0.5f * sw) + sw,
               rgb(c.r, c.g, c.b));
        o.text(sx + 56.0f, y, c.label, 2.0f, text);
        o.text(sx + 56.0f, y + 18.0f, c.code, 2.0f, code);
    }

    // Footer: how far the approximations stray (computed on the CPU from the same GLSL source).
    const MaxError schlick =
        max_error_vs_exact([](float c) { return raykit::rk_fresnel_schlick(c, raykit::rk_f0_from_eta(kEta)); });
    const MaxError fast = max_error_vs_exact([](float c) { return raykit::rk_fresnel_dielectric_fast(c, kEta); });
    o.text(kDataLeft - 10.0f, static_cast<float>(kHeight) - 30.0f,
           "largest error vs exact: Schlick " + fmt("%.4f", schlick.error) + " at " + fmt("%.1f", schlick.degrees) +
               deg + ", fast approximation " + fmt("%.4f", fast.error) + " at " + fmt("%.1f", fast.degrees) + deg,
           2.0f, dim);
}

int run(const char* out_path)
{
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) {
        return rkgl::no_context_exit("fresnel_curves", ctx.error());
    }
    std::printf("renderer: %s\n", ctx.renderer().c_str());
    const GLubyte* gl_renderer = glGetString(GL_RENDERER);
    const std::string renderer = gl_renderer ? reinterpret_cast<const char*>(gl_renderer) : "an unknown GPU";

    const std::string frag_path = std::string(SAMPLES_DIR) + "/fresnel_curves/fresnel_curves.frag";
    const GLuint plot = rkgl::build_program({{GL_VERTEX_SHADER, kFullscreenVert},
                                             {GL_FRAGMENT_SHADER, rkgl::shader_file(frag_path, {RAYKIT_SHADER_DIR})}});

    rkgl::Framebuffer fb(kWidth, kHeight);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    glBindVertexArray(vao);

    // Pass 1: grid and curves.
    float colors[8 * 4];
    float widths[8];
    for (int i = 0; i < 8; ++i) {
        const Curve& c = kCurves[i];
        const float v[4] = {c.r, c.g, c.b, 1.0f};
        std::memcpy(&colors[i * 4], v, sizeof v);
        widths[i] = c.width;
    }
    glUseProgram(plot);
    glUniform2f(glGetUniformLocation(plot, "u_size"), float(kWidth), float(kHeight));
    glUniform4f(glGetUniformLocation(plot, "u_data"), kDataLeft, kDataTop, kDataRight, kDataBottom);
    glUniform4f(glGetUniformLocation(plot, "u_frame"), kDataLeft - kFramePad, kDataTop - kFramePad,
                kDataRight + kFramePad, kDataBottom + kFramePad);
    glUniform1f(glGetUniformLocation(plot, "u_eta"), kEta);
    glUniform4fv(glGetUniformLocation(plot, "u_color"), 8, colors);
    glUniform1fv(glGetUniformLocation(plot, "u_width"), 8, widths);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    // Pass 2: legend and text, alpha blended.
    Overlay o;
    build_overlay(o, renderer);
    o.draw(kWidth, kHeight);

    std::vector<unsigned char> px = fb.read_rgba8();
    const GLenum err = glGetError();

    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(plot);
    if (err != GL_NO_ERROR) {
        std::fprintf(stderr, "fresnel_curves: OpenGL error 0x%04x\n", err);
        return 1;
    }

    bool uniform = true;
    for (size_t i = 4; i < px.size() && uniform; i += 4) uniform = std::memcmp(&px[i], &px[0], 4) == 0;
    if (uniform) {
        std::fprintf(stderr, "fresnel_curves: the rendered image is one flat colour: nothing was drawn\n");
        return 1;
    }
    for (size_t i = 3; i < px.size(); i += 4) px[i] = 255;  // opaque PNG whatever the blend left in alpha

    if (!rkgl::write_png_rgba8(out_path, kWidth, kHeight, px.data())) {
        std::fprintf(stderr, "fresnel_curves: cannot write %s\n", out_path);
        return 1;
    }
    std::printf("wrote %s (%dx%d)\n", out_path, kWidth, kHeight);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    const char* out_path = argc > 1 ? argv[1] : "fresnel_curves.png";
    try {
        return run(out_path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fresnel_curves: %s\n", e.what());
        return 1;
    }
}
