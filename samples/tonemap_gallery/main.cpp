// raykit sample — tonemap_gallery: one HDR scene through every tone operator of tonemap.glsl, side
// by side, rendered headless on the GPU.
//
// The scene (scene.glsl: sky and sun, ground, diffuse, glossy and emissive spheres) and a chart of
// luminance ramps from 1e-3 to 1e4 are evaluated per pixel in gallery.frag. Each panel is drawn by
// its own program, compiled with raykit::tonemap_defines(op, look): the operator is chosen by the
// preprocessor, so a shader pays only for the operator it uses. One exposure serves every panel:
// key 0.18 over the log-average luminance of the scene, computed once on the CPU from a float
// rendering of it (GALLERY_MODE 2). A twelfth panel maps scene luminance to false colour, one band
// per stop. Captions and tick labels come from rk_text.hpp (stb_easy_font).
//
// Usage: tonemap_gallery [out.png]   (default tonemap_gallery.png)
// Exit codes: 0 written; 1 error (shader, GL, a flat image); 77 no OpenGL 4.5 context (skip;
// 1 instead when CI=true).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "raykit/color.hpp"
#include "raykit/shader_source.hpp"
#include "raykit/tonemap.hpp"
#include "rk_gl.hpp"
#include "rk_text.hpp"

#include "rk_png.hpp"

namespace {

using raykit::ToneOperator;
using rkgl::Rgba;
using rkgl::rgba;

// Layout in pixels (origin top-left, y down).
constexpr int kCols = 3;
constexpr int kRows = 4;
constexpr int kMargin = 18;      // left/right image border
constexpr int kGutter = 12;      // between panel columns
constexpr int kHeader = 118;     // title block
constexpr int kCaption = 32;     // caption strip above each panel
constexpr int kRowGap = 12;      // between a panel and the next caption
constexpr int kFooter = 34;
constexpr int kPanelW = 480;
constexpr int kViewH = 262;      // the 3-D view
constexpr int kStripTop = kViewH + 6;  // first hue strip
constexpr int kStripH = 12;
constexpr int kStripPitch = 14;
constexpr int kGreyTop = kStripTop + 4 * kStripPitch + 2;
constexpr int kGreyH = 18;
constexpr int kTickH = 5;
constexpr int kPanelH = kGreyTop + kGreyH + kTickH + 20;  // ticks and their labels end the panel
constexpr int kRampX0 = 18;              // local x of 1e-3
constexpr int kRampX1 = kPanelW - 18;    // local x of 1e4
constexpr int kWidth = 2 * kMargin + kCols * kPanelW + (kCols - 1) * kGutter;
constexpr int kHeight = kHeader + kRows * (kCaption + kPanelH) + (kRows - 1) * kRowGap + kFooter;

constexpr float kKey = 0.18f;  // exposed log-average (Reinhard's key)

// Display (sRGB-encoded) colours of the page.
const float kBackground = 0.075f;  // grey, encoded

enum class Mode { tonemap = 0, false_colour = 1, hdr = 2 };

struct Panel {
    Mode mode;
    ToneOperator op;
    int look;
    const char* suffix;  // appended to tonemap_operator_name (e.g. the AgX look)
};

const Panel kPanels[kCols * kRows] = {
    {Mode::false_colour, ToneOperator::clamp, 0, ""},
    {Mode::tonemap, ToneOperator::clamp, 0, ""},
    {Mode::tonemap, ToneOperator::reinhard, 0, " extended"},
    {Mode::tonemap, ToneOperator::aces_narkowicz, 0, ""},
    {Mode::tonemap, ToneOperator::aces_hill, 0, ""},
    {Mode::tonemap, ToneOperator::agx, 0, ""},
    {Mode::tonemap, ToneOperator::agx, 1, " golden"},
    {Mode::tonemap, ToneOperator::agx, 2, " punchy"},
    {Mode::tonemap, ToneOperator::pbr_neutral, 0, ""},
    {Mode::tonemap, ToneOperator::hable, 0, ""},
    {Mode::tonemap, ToneOperator::lottes, 0, ""},
    {Mode::tonemap, ToneOperator::uchimura, 0, ""},
};

int panel_x(int index) { return kMargin + (index % kCols) * (kPanelW + kGutter); }
int panel_y(int index) { return kHeader + (index / kCols) * (kCaption + kPanelH + kRowGap) + kCaption; }

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

// "OPERATOR=4 LOOK=1" for RK_TONEMAP_OPERATOR=4 RK_AGX_LOOK=1 (the prefixes left out to fit).
std::string defines_text(const std::vector<raykit::ShaderDefine>& defines)
{
    std::string s;
    for (const raykit::ShaderDefine& d : defines) {
        s += (s.empty() ? "" : " ") + d.name.substr(d.name.find_last_of('_') + 1) + "=" + d.value;
    }
    return s;
}

// Sets the panel uniforms of gallery.frag for a panel at (x, y) (top-left, pixels) of a
// framebuffer `fb_height` tall, and draws it.
void draw_panel(GLuint program, int x, int y, int w, int h, int fb_height, float exposure, float white)
{
    glUseProgram(program);
    auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
    glUniform4f(loc("u_panel"), float(x), float(y), float(w), float(h));
    glUniform1f(loc("u_fb_height"), float(fb_height));
    glUniform1f(loc("u_view_height"), float(kViewH));
    glUniform2f(loc("u_ramp_x"), float(kRampX0), float(kRampX1));
    glUniform4f(loc("u_strips"), float(kStripTop), float(kStripH), float(kStripPitch), float(kGreyTop));
    glUniform1f(loc("u_grey_height"), float(kGreyH));
    glUniform1f(loc("u_exposure"), exposure);
    glUniform1f(loc("u_white"), white);
    const float bg = raykit::rk_srgb_decode(kBackground);
    glUniform3f(loc("u_background"), bg, bg, bg);
    glViewport(x, fb_height - y - h, w, h);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

struct SceneStats {
    double log_average = 0.0;  // exp(mean(ln(1e-4 + L)))
    double min = 0.0, max = 0.0;
};

// Renders the 3-D view unexposed into a float target and measures its luminance on the CPU.
SceneStats measure_scene(GLuint hdr_program)
{
    GLuint tex = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, kPanelW, kViewH);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw std::runtime_error("incomplete float framebuffer");
    }
    GLint prev_fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    draw_panel(hdr_program, 0, 0, kPanelW, kViewH, kViewH, 1.0f, 1.0f);
    std::vector<float> px(static_cast<size_t>(kPanelW) * kViewH * 4u);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, kPanelW, kViewH, GL_RGBA, GL_FLOAT, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(prev_fbo));
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);

    SceneStats s;
    s.min = 1e30;
    double sum_log = 0.0;
    for (size_t i = 0; i < px.size(); i += 4) {
        const double l = raykit::rk_luminance(raykit::vec3(px[i], px[i + 1], px[i + 2]));
        sum_log += std::log(1e-4 + std::max(l, 0.0));
        s.min = std::min(s.min, l);
        s.max = std::max(s.max, l);
    }
    s.log_average = std::exp(sum_log / static_cast<double>(px.size() / 4u));
    return s;
}

// A tick label "10" with a raised, smaller exponent, centred on cx, its top at y.
void power_of_ten(rkgl::TextOverlay& o, float cx, float y, int exponent, Rgba c)
{
    const std::string e = std::to_string(exponent);
    const float w = rkgl::TextOverlay::width("10", 2.0f) + rkgl::TextOverlay::width(e, 1.0f) + 1.0f;
    const float x = std::round(cx - 0.5f * w);
    o.text(x, y + 3.0f, "10", 2.0f, c);
    o.text(x + rkgl::TextOverlay::width("10", 2.0f) + 1.0f, y, e, 1.0f, c);
}

void build_overlay(rkgl::TextOverlay& o, const SceneStats& stats, float exposure, const std::string& renderer)
{
    const Rgba text = rgba(0.92f, 0.93f, 0.95f);
    const Rgba dim = rgba(0.58f, 0.61f, 0.67f);
    const Rgba code = rgba(0.50f, 0.66f, 0.78f);
    const Rgba tick = rgba(0.55f, 0.57f, 0.62f);

    o.text(float(kMargin), 14.0f, "raykit tonemap.glsl: one HDR scene through every tone operator", 3.0f, text);
    const std::string lines[3] = {
        "scene luminance " + fmt("%.2g", stats.min) + " .. " + fmt("%.0f", stats.max) + " (" +
            fmt("%.0f", std::log2(stats.max / std::max(stats.min, 1e-30))) + " stops); one exposure for every panel: key " +
            fmt("%.2f", kKey) + " / log-average " + fmt("%.3f", stats.log_average) + " = x" + fmt("%.3f", exposure),
        "each panel is its own program, built with raykit::tonemap_defines(op, look): its defines are at top right",
        "under each view: log ramps 10^-3 .. 10^4 of four saturated hues and grey, of equal luminance; Reinhard's "
        "white = scene max",
    };
    for (int i = 0; i < 3; ++i) o.text(float(kMargin), 48.0f + 20.0f * float(i), lines[i], 2.0f, dim);

    for (int i = 0; i < kCols * kRows; ++i) {
        const Panel& p = kPanels[i];
        const float x = float(panel_x(i));
        const float y = float(panel_y(i));
        std::string name;
        std::string note;
        if (p.mode == Mode::false_colour) {
            name = "scene luminance";
            note = "1 band = 1 stop";
        } else {
            name = std::string(raykit::tonemap_operator_name(p.op)) + p.suffix;
            note = defines_text(raykit::tonemap_defines(p.op, p.look));
        }
        o.text(x, y - 27.0f, name, 3.0f, text);
        o.text(x + float(kPanelW) - rkgl::TextOverlay::width(note, 2.0f), y - 20.0f, note, 2.0f,
               p.mode == Mode::false_colour ? dim : code);

        // Decade ticks and labels under the grey ramp.
        for (int k = -3; k <= 4; ++k) {
            const float tx = x + std::round(float(kRampX0) + float(kRampX1 - kRampX0) * float(k + 3) / 7.0f);
            const float ty = y + float(kGreyTop + kGreyH);
            o.rect(tx - (k == 4 ? 1.0f : 0.0f), ty, tx + (k == 4 ? 0.0f : 1.0f), ty + float(kTickH), tick);
            power_of_ten(o, tx, ty + float(kTickH) + 2.0f, k, dim);
        }
    }
    o.text(float(kMargin), float(kHeight - kFooter + 10), "rendered on " + renderer + "   |   samples/tonemap_gallery",
           2.0f, dim);
}

int run(const char* out_path)
{
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) {
        return rkgl::no_context_exit("tonemap_gallery", ctx.error());
    }
    std::printf("renderer: %s\n", ctx.renderer().c_str());
    const GLubyte* gl_renderer = glGetString(GL_RENDERER);
    const std::string renderer = gl_renderer ? reinterpret_cast<const char*>(gl_renderer) : "an unknown GPU";

    const std::string frag_path = std::string(SAMPLES_DIR) + "/tonemap_gallery/gallery.frag";
    auto build = [&](std::vector<raykit::ShaderDefine> defines, Mode mode) {
        defines.push_back({"GALLERY_MODE", std::to_string(static_cast<int>(mode))});
        return rkgl::build_program({{GL_VERTEX_SHADER, kFullscreenVert},
                                    {GL_FRAGMENT_SHADER, rkgl::shader_file(frag_path, {RAYKIT_SHADER_DIR}, defines)}});
    };

    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    glBindVertexArray(vao);

    // The exposure, once, from the unexposed scene.
    const GLuint hdr_program = build({}, Mode::hdr);
    const SceneStats stats = measure_scene(hdr_program);
    glDeleteProgram(hdr_program);
    const float exposure = static_cast<float>(kKey / stats.log_average);
    const float white = static_cast<float>(stats.max) * exposure;  // Reinhard: white = scene max
    std::printf("scene luminance %.3g .. %.3g, log-average %.4f -> exposure %.4f, Reinhard white %.4g\n", stats.min,
                stats.max, stats.log_average, exposure, white);

    rkgl::Framebuffer fb(kWidth, kHeight);
    glClearColor(kBackground, kBackground, kBackground, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    for (int i = 0; i < kCols * kRows; ++i) {
        const Panel& p = kPanels[i];
        const GLuint program =
            p.mode == Mode::tonemap ? build(raykit::tonemap_defines(p.op, p.look), p.mode) : build({}, p.mode);
        draw_panel(program, panel_x(i), panel_y(i), kPanelW, kPanelH, kHeight, exposure, white);
        glUseProgram(0);
        glDeleteProgram(program);
    }
    glViewport(0, 0, kWidth, kHeight);

    rkgl::TextOverlay o;
    build_overlay(o, stats, exposure, renderer);
    o.draw(kWidth, kHeight);

    std::vector<unsigned char> px = fb.read_rgba8();
    const GLenum err = glGetError();
    glDeleteVertexArrays(1, &vao);
    if (err != GL_NO_ERROR) {
        std::fprintf(stderr, "tonemap_gallery: OpenGL error 0x%04x\n", err);
        return 1;
    }

    // Every panel's view must show something (a flat one means a shader rendered nothing).
    for (int i = 0; i < kCols * kRows; ++i) {
        const size_t first = (static_cast<size_t>(panel_y(i)) * kWidth + static_cast<size_t>(panel_x(i))) * 4u;
        bool uniform = true;
        for (int y = 0; y < kViewH && uniform; ++y) {
            for (int x = 0; x < kPanelW && uniform; ++x) {
                const size_t at = (static_cast<size_t>(panel_y(i) + y) * kWidth + static_cast<size_t>(panel_x(i) + x)) * 4u;
                uniform = std::memcmp(&px[at], &px[first], 3) == 0;
            }
        }
        if (uniform) {
            std::fprintf(stderr, "tonemap_gallery: panel %d is one flat colour: nothing was drawn\n", i);
            return 1;
        }
    }
    for (size_t i = 3; i < px.size(); i += 4) px[i] = 255;  // opaque PNG

    if (!rkgl::write_png_rgba8(out_path, kWidth, kHeight, px.data())) {
        std::fprintf(stderr, "tonemap_gallery: cannot write %s\n", out_path);
        return 1;
    }
    std::printf("wrote %s (%dx%d)\n", out_path, kWidth, kHeight);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    const char* out_path = argc > 1 ? argv[1] : "tonemap_gallery.png";
    try {
        return run(out_path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tonemap_gallery: %s\n", e.what());
        return 1;
    }
}
