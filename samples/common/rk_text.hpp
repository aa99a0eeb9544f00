// raykit samples — rk_text.hpp: text labels and solid rectangles over a rendered image, drawn in
// one alpha-blended pass on the current framebuffer.
//
// stb_easy_font turns strings into quads on the CPU (a 1-unit-per-pixel bitmap font, about 7 units
// tall); TextOverlay scales them (an integer scale keeps the glyphs crisp), collects them with any
// rectangles as coloured triangles, and draw() renders them all with one trivial program. Origin
// top-left, y down, in framebuffer pixels. Needs a current OpenGL 4.5 context (rk_gl.hpp) and stb
// on the include path (Debian: libstb-dev).
//
//   rkgl::TextOverlay o;
//   o.rect(10, 10, 200, 40, rkgl::rgba(0, 0, 0, 0.6f));
//   o.text(16, 16, "hello", 2.0f, rkgl::rgba(1, 1, 1));
//   o.draw(width, height);
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include "rk_gl.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wcast-qual"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace rkgl {

/// An 8-bit RGBA colour (sRGB-encoded values, as written to an RGBA8 target).
struct Rgba {
    unsigned char r, g, b, a;
};

/// Rgba from floats in [0, 1] (clamped, rounded to nearest).
inline Rgba rgba(float r, float g, float b, float a = 1.0f)
{
    auto u8 = [](float v) { return static_cast<unsigned char>(std::lround(std::min(std::max(v, 0.0f), 1.0f) * 255.0f)); };
    return {u8(r), u8(g), u8(b), u8(a)};
}

/// Text and rectangles collected on the CPU, drawn in one blended pass by draw().
class TextOverlay {
public:
    /// A vertex of the overlay pass: pixel position and colour.
    struct Vertex {
        float x, y;
        Rgba c;
    };

    /// Height of a line of capitals (and digits) in font units: multiply by the scale for pixels.
    static constexpr float kCapHeight = 7.0f;

    /// A solid (or, with alpha < 1, translucent) rectangle from (x0, y0) to (x1, y1).
    void rect(float x0, float y0, float x1, float y1, Rgba c)
    {
        const Vertex a{x0, y0, c}, b{x1, y0, c}, d{x1, y1, c}, e{x0, y1, c};
        verts_.insert(verts_.end(), {a, b, d, a, d, e});
    }

    /// Text with its top-left at (x, y), glyph pixels scaled by `scale` (integer keeps it crisp).
    /// `vertical` writes it bottom to top, (x, y) then being its bottom-left. A "\u00b0" (UTF-8
    /// degree sign, which stb_easy_font lacks) is drawn as a small ring.
    void text(float x, float y, const std::string& s, float scale, Rgba c, bool vertical = false)
    {
        float cursor = 0.0f;  // font units along the text
        size_t start = 0;
        while (start <= s.size()) {
            const size_t deg = s.find(kDegree, start);
            const std::string piece = s.substr(start, deg == std::string::npos ? std::string::npos : deg - start);
            glyphs(x, y, cursor, piece, scale, c, vertical);
            cursor += width(piece, 1.0f);
            if (deg == std::string::npos) break;
            // A 3 x 3 ring at the cap height: four one-unit bars around a one-unit hole.
            const float bars[4][4] = {{0, 0, 3, 1}, {0, 2, 3, 3}, {0, 1, 1, 2}, {2, 1, 3, 2}};
            for (const auto& b : bars) {
                quad(x, y, cursor + b[0], b[1], cursor + b[2], b[3], scale, c, vertical);
            }
            cursor += 4.0f;
            start = deg + std::strlen(kDegree);
        }
    }

    /// Advance width of text() in pixels.
    static float width(const std::string& s, float scale)
    {
        const size_t deg = s.find(kDegree);
        if (deg != std::string::npos) {
            return width(s.substr(0, deg), scale) + 4.0f * scale + width(s.substr(deg + std::strlen(kDegree)), scale);
        }
        std::vector<char> str(s.begin(), s.end());
        str.push_back('\0');
        return static_cast<float>(stb_easy_font_width(str.data())) * scale;
    }

    const std::vector<Vertex>& vertices() const { return verts_; }
    bool empty() const { return verts_.empty(); }
    void clear() { verts_.clear(); }

    /// Draws everything collected, in order, over the bound framebuffer of width x height pixels
    /// with alpha blending (src_alpha, one_minus_src_alpha). Restores the blend enable, the program
    /// and the vertex array binding it found (where they still exist). Throws std::runtime_error if the program fails.
    void draw(int width_px, int height_px) const
    {
        if (verts_.empty()) return;
        GLint prev_program = 0, prev_vao = 0;
        glGetIntegerv(GL_CURRENT_PROGRAM, &prev_program);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
        const GLboolean prev_blend = glIsEnabled(GL_BLEND);

        const GLuint program = build_program({{GL_VERTEX_SHADER, kVert}, {GL_FRAGMENT_SHADER, kFrag}});
        GLuint vao = 0;
        glCreateVertexArrays(1, &vao);
        const GLuint vbo = make_buffer(verts_.size() * sizeof(Vertex), verts_.data());
        glVertexArrayVertexBuffer(vao, 0, vbo, 0, sizeof(Vertex));
        glEnableVertexArrayAttrib(vao, 0);
        glVertexArrayAttribFormat(vao, 0, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, x));
        glVertexArrayAttribBinding(vao, 0, 0);
        glEnableVertexArrayAttrib(vao, 1);
        glVertexArrayAttribFormat(vao, 1, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(Vertex, c));
        glVertexArrayAttribBinding(vao, 1, 0);

        glBindVertexArray(vao);
        glUseProgram(program);
        glUniform2f(glGetUniformLocation(program, "u_size"), static_cast<float>(width_px),
                    static_cast<float>(height_px));
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(verts_.size()));

        if (!prev_blend) glDisable(GL_BLEND);
        // A program deleted while current was freed when draw() replaced it: restore none then.
        glUseProgram(glIsProgram(static_cast<GLuint>(prev_program)) ? static_cast<GLuint>(prev_program) : 0u);
        glBindVertexArray(glIsVertexArray(static_cast<GLuint>(prev_vao)) ? static_cast<GLuint>(prev_vao) : 0u);
        glDeleteBuffers(1, &vbo);
        glDeleteVertexArrays(1, &vao);
        glDeleteProgram(program);
    }

private:
    static constexpr const char* kDegree = "\xc2\xb0";

    static constexpr const char* kVert = R"(#version 450 core
layout(location = 0) in vec2 a_pos;    // pixels, origin top-left
layout(location = 1) in vec4 a_color;
uniform vec2 u_size;
out vec4 v_color;
void main()
{
    v_color = a_color;
    gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0);
}
)";

    static constexpr const char* kFrag = R"(#version 450 core
in vec4 v_color;
out vec4 frag_color;
void main() { frag_color = v_color; }
)";

    // A quad given in font units (u along the text, w down), placed like text().
    void quad(float x, float y, float u0, float w0, float u1, float w1, float scale, Rgba c, bool vertical)
    {
        Vertex v[4];
        const float us[4] = {u0, u1, u1, u0};
        const float ws[4] = {w0, w0, w1, w1};
        for (int k = 0; k < 4; ++k) {
            const float u = us[k] * scale;
            const float w = ws[k] * scale;
            v[k] = vertical ? Vertex{x + w, y - u, c} : Vertex{x + u, y + w, c};
        }
        verts_.insert(verts_.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
    }

    void glyphs(float x, float y, float cursor, const std::string& s, float scale, Rgba c, bool vertical)
    {
        std::vector<char> str(s.begin(), s.end());
        str.push_back('\0');
        std::vector<char> buf(s.size() * 1024 + 64);  // stb_easy_font truncates silently when short
        unsigned char col[4] = {c.r, c.g, c.b, c.a};
        const int quads = stb_easy_font_print(cursor, 0.0f, str.data(), col, buf.data(), static_cast<int>(buf.size()));
        for (int q = 0; q < quads; ++q) {
            float p[4][2];
            for (int k = 0; k < 4; ++k) {
                std::memcpy(p[k], &buf[static_cast<size_t>(q * 4 + k) * 16u], sizeof p[k]);
            }
            quad(x, y, p[0][0], p[0][1], p[2][0], p[2][1], scale, c, vertical);
        }
    }

    std::vector<Vertex> verts_;
};

}  // namespace rkgl
