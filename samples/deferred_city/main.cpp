// deferred_city: the procedural city of samples/city rendered deferred (Fahlén, "Illumination for
// Real-Time Rendering of Large Architectural Environments", chapters 2, 5 and 6) with raykit's
// deferred-shading includes, and the same frame rendered forward for comparison:
//   - the compact G-buffer (raykit::gbuffer_layout_compact(): albedo, octahedral normal in 2 x 16
//     bits, material, specular and emission as two halves; position rebuilt from a reversed-Z D32F
//     depth buffer by rk_gb_linear_depth and rk_gb_view_pos);
//   - the sun with four cascaded shadow maps (cascade_splits, fit_cascade with texel snapping,
//     rk_sh_cascade_index / rk_sh_cascade_blend, normal-offset + slope bias, Vogel PCF turned per
//     pixel: shadow.glsl, shadow_filter.glsl);
//   - normal-mapped facades and ground (tangents from raykit::compute_tangents, normalmap.glsl);
//   - at night, hundreds of street lamps drawn as light volumes (light_volume_sphere, the cull rule
//     of light_volume_cull_sphere with the near-plane margin, rk_lv_point_falloff);
//   - edge anti-aliasing from the G-buffer (edge_aa.glsl), then rk_tonemap.
//
// Views written as PNG (headless EGL): deferred_day.png (street level, low sun, cascaded shadows
// across the boulevard), deferred_cascades.png (from above, cascades tinted), deferred_night.png
// (street lamps as light volumes, lit windows), deferred_compare.png (forward | deferred | 20 x
// their difference, night view). The forward path shades the same surfaces with the same
// functions, every light looped per pixel; the program prints (and --quick asserts) how far the
// two images are apart after display mapping.
//
// Usage: deferred_city [--quick] [--size WxH] [--bench [--reps N] [--bench-out FILE]] [OUT_DIR]
//   --quick  320x180, smaller shadow maps, the checks (for the tests)
//   --bench  forward against deferred frame time as the number of point lights grows (interleaved,
//            median of N repeated frames, default 7); prints a markdown table (and writes it to
//            FILE: scripts/bench_deferred.sh makes docs/benchmarks_deferred.md of it)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "../city/city_gen.hpp"
#include "raykit/gbuffer.hpp"
#include "raykit/light_volume.hpp"
#include "raykit/shadow.hpp"
#include "raykit/tangents.hpp"
#include "rk_gl.hpp"
#include "rk_png.hpp"

namespace {

using glm::mat4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

// ---------------------------------------------------------------------------------------------
// Geometry: buildings and ground with uv and tangents

struct Vertex {
    float pos[3];
    float normal[3];
    float tangent[4];
    float uv[2];
    float mat[2];  // texture layer, building index
};

struct MeshBuilder {
    std::vector<float> pos, nrm, uv, mat;
    void vertex(vec3 p, vec3 n, vec2 t, float layer, float id)
    {
        pos.insert(pos.end(), {p.x, p.y, p.z});
        nrm.insert(nrm.end(), {n.x, n.y, n.z});
        uv.insert(uv.end(), {t.x, t.y});
        mat.insert(mat.end(), {layer, id});
    }
    /// A quad a b c d (counter-clockwise from outside) with uv ta tb tc td.
    void quad(vec3 a, vec3 b, vec3 c, vec3 d, vec3 n, vec2 ta, vec2 tb, vec2 tc, vec2 td, float layer, float id)
    {
        vertex(a, n, ta, layer, id);
        vertex(b, n, tb, layer, id);
        vertex(c, n, tc, layer, id);
        vertex(a, n, ta, layer, id);
        vertex(c, n, tc, layer, id);
        vertex(d, n, td, layer, id);
    }
    size_t count() const { return pos.size() / 3; }
};

constexpr float kGroundTile = 4.0f;  // metres per ground texture repeat
constexpr int kFacadeStyles = 3;     // texture layers 1..3

std::vector<Vertex> build_mesh(const city::City& c, int segments)
{
    MeshBuilder m;
    const float g = c.extent + 400.0f;
    auto guv = [](vec3 p) { return vec2(p.x / kGroundTile, -p.z / kGroundTile); };
    const vec3 g0(-g, 0, g), g1(g, 0, g), g2(g, 0, -g), g3(-g, 0, -g);
    m.quad(g0, g1, g2, g3, vec3(0, 1, 0), guv(g0), guv(g1), guv(g2), guv(g3), 0.0f, -1.0f);
    for (size_t i = 0; i < c.buildings.size(); ++i) {
        const city::Building& b = c.buildings[i];
        const float id = static_cast<float>(i), layer = static_cast<float>(1 + b.facade % kFacadeStyles);
        const float storey = b.grid.room_size.y, h = b.height, vt = h / storey;
        if (b.kind == 0) {
            const float x0 = b.cx - b.hx, x1 = b.cx + b.hx, z0 = b.cz - b.hz, z1 = b.cz + b.hz;
            const float ux = (x1 - x0) / b.bay_x, uz = (z1 - z0) / b.bay_z;
            // Walls: u runs along the wall (left to right seen from outside), v up, in bays and storeys.
            m.quad(vec3(x0, 0, z1), vec3(x1, 0, z1), vec3(x1, h, z1), vec3(x0, h, z1), vec3(0, 0, 1), vec2(0, 0), vec2(ux, 0),
                   vec2(ux, vt), vec2(0, vt), layer, id);
            m.quad(vec3(x1, 0, z0), vec3(x0, 0, z0), vec3(x0, h, z0), vec3(x1, h, z0), vec3(0, 0, -1), vec2(0, 0), vec2(ux, 0),
                   vec2(ux, vt), vec2(0, vt), layer, id);
            m.quad(vec3(x1, 0, z1), vec3(x1, 0, z0), vec3(x1, h, z0), vec3(x1, h, z1), vec3(1, 0, 0), vec2(0, 0), vec2(uz, 0),
                   vec2(uz, vt), vec2(0, vt), layer, id);
            m.quad(vec3(x0, 0, z0), vec3(x0, 0, z1), vec3(x0, h, z1), vec3(x0, h, z0), vec3(-1, 0, 0), vec2(0, 0), vec2(uz, 0),
                   vec2(uz, vt), vec2(0, vt), layer, id);
            const vec3 r0(x0, h, z1), r1(x1, h, z1), r2(x1, h, z0), r3(x0, h, z0);
            m.quad(r0, r1, r2, r3, vec3(0, 1, 0), guv(r0), guv(r1), guv(r2), guv(r3), 0.0f, id);
        } else {
            const float r = b.hx, circ = 6.2831853f * r;
            for (int s = 0; s < segments; ++s) {
                const float a0 = 6.2831853f * static_cast<float>(s) / static_cast<float>(segments);
                const float a1 = 6.2831853f * static_cast<float>(s + 1) / static_cast<float>(segments);
                const vec3 n0(std::cos(a0), 0, std::sin(a0)), n1(std::cos(a1), 0, std::sin(a1));
                const vec3 p0(b.cx + r * n0.x, 0, b.cz + r * n0.z), p1(b.cx + r * n1.x, 0, b.cz + r * n1.z), up(0, h, 0);
                // u decreases with the angle so that it runs left to right seen from outside.
                const float u0 = -circ * static_cast<float>(s) / static_cast<float>(segments) / b.bay_x;
                const float u1 = -circ * static_cast<float>(s + 1) / static_cast<float>(segments) / b.bay_x;
                m.vertex(p0, n0, vec2(u0, 0), layer, id);
                m.vertex(p1 + up, n1, vec2(u1, vt), layer, id);
                m.vertex(p1, n1, vec2(u1, 0), layer, id);
                m.vertex(p0, n0, vec2(u0, 0), layer, id);
                m.vertex(p0 + up, n0, vec2(u0, vt), layer, id);
                m.vertex(p1 + up, n1, vec2(u1, vt), layer, id);
                const vec3 cc(b.cx, h, b.cz);
                for (vec3 p : {cc, p1 + up, p0 + up}) m.vertex(p, vec3(0, 1, 0), guv(p), 0.0f, id);
            }
        }
    }
    std::vector<raykit::vec4> tangents;
    raykit::Status st;
    if (!raykit::compute_tangents(m.pos.data(), m.nrm.data(), m.uv.data(), m.count(), nullptr, m.count() / 3, tangents, st))
        throw std::runtime_error("compute_tangents: " + st.message);
    std::vector<Vertex> out(m.count());
    for (size_t i = 0; i < out.size(); ++i) {
        Vertex& v = out[i];
        for (int k = 0; k < 3; ++k) {
            v.pos[k] = m.pos[3 * i + static_cast<size_t>(k)];
            v.normal[k] = m.nrm[3 * i + static_cast<size_t>(k)];
        }
        for (int k = 0; k < 4; ++k) v.tangent[k] = tangents[i][k];
        for (int k = 0; k < 2; ++k) {
            v.uv[k] = m.uv[2 * i + static_cast<size_t>(k)];
            v.mat[k] = m.mat[2 * i + static_cast<size_t>(k)];
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Material textures: albedo (sRGB, alpha = glass) and a two-channel normal map from a height field

float hash01(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return static_cast<float>(x >> 8) * (1.0f / 16777216.0f);
}

struct Texel {
    vec3 albedo;
    float glass;
    float height;
};

/// Layer 0: paving stones (four per repeat); 1..3: one window bay of one storey on brick, concrete
/// panels and stone.
Texel material_texel(int layer, float u, float v)
{
    Texel t{vec3(0.5f), 0.0f, 1.0f};
    auto groove = [](float x, float w) { return std::min(x, 1.0f - x) < w ? 1.0f : 0.0f; };
    if (layer == 0) {
        const float su = u * 4.0f, sv = v * 4.0f;
        const uint32_t cell = static_cast<uint32_t>(std::floor(su)) * 73u + static_cast<uint32_t>(std::floor(sv)) * 1319u;
        const float fu = su - std::floor(su), fv = sv - std::floor(sv);
        const float var = 0.85f + 0.3f * hash01(cell);
        const bool joint = groove(fu, 0.04f) > 0.0f || groove(fv, 0.04f) > 0.0f;
        t.albedo = joint ? vec3(0.18f, 0.17f, 0.16f) : vec3(0.42f, 0.40f, 0.37f) * var;
        t.height = joint ? 0.0f : 1.0f - 0.15f * hash01(cell + 7u) * (1.0f - 4.0f * (fu - 0.5f) * (fu - 0.5f));
        return t;
    }
    const bool window = u > 0.22f && u < 0.78f && v > 0.24f && v < 0.86f;
    const bool frame = !window && u > 0.19f && u < 0.81f && v > 0.21f && v < 0.89f;
    if (window) {
        const bool mullion = std::abs(u - 0.5f) < 0.015f;
        t.albedo = mullion ? vec3(0.08f) : vec3(0.03f, 0.035f, 0.04f);
        t.glass = mullion ? 0.0f : 1.0f;
        t.height = mullion ? 0.45f : 0.25f;
        return t;
    }
    if (frame) {
        t.albedo = vec3(0.1f, 0.1f, 0.11f);
        t.height = 0.55f;
        return t;
    }
    if (layer == 1) {  // brick: 12 courses a storey, 5 bricks a bay, running bond
        const float cv = v * 12.0f, row = std::floor(cv);
        const float cu = u * 5.0f + (static_cast<int>(row) % 2 ? 0.5f : 0.0f), col = std::floor(cu);
        const bool mortar = groove(cv - row, 0.08f) > 0.0f || groove(cu - col, 0.03f) > 0.0f;
        const float var = 0.8f + 0.4f * hash01(static_cast<uint32_t>(row * 31.0f + col * 7.0f + 1000.0f));
        t.albedo = mortar ? vec3(0.45f, 0.43f, 0.4f) : vec3(0.36f, 0.14f, 0.09f) * var;
        t.height = mortar ? 0.6f : 0.8f;
    } else if (layer == 2) {  // concrete panels, a slab band at each floor
        const bool band = v < 0.1f;
        const bool joint = groove(u, 0.01f) > 0.0f || std::abs(v - 0.1f) < 0.01f;
        t.albedo = band ? vec3(0.55f, 0.54f, 0.5f) : vec3(0.42f, 0.42f, 0.4f);
        t.height = joint ? 0.6f : (band ? 1.0f : 0.8f);
    } else {  // stone blocks, three courses a storey
        const float cv = v * 3.0f, row = std::floor(cv);
        const float cu = u * 2.0f + (static_cast<int>(row) % 2 ? 0.5f : 0.0f), col = std::floor(cu);
        const bool joint = groove(cv - row, 0.025f) > 0.0f || groove(cu - col, 0.015f) > 0.0f;
        const float var = 0.9f + 0.2f * hash01(static_cast<uint32_t>(row * 17.0f + col * 5.0f + 77.0f));
        const float fu = cu - col - 0.5f, fv = cv - row - 0.5f;
        t.albedo = joint ? vec3(0.3f, 0.28f, 0.25f) : vec3(0.58f, 0.52f, 0.43f) * var;
        t.height = joint ? 0.55f : 0.8f - 0.1f * (fu * fu + fv * fv);  // rusticated: bulging blocks
    }
    return t;
}

struct MaterialTextures {
    GLuint albedo = 0, normal = 0;
};

MaterialTextures make_textures(int size)
{
    const int layers = 1 + kFacadeStyles;
    std::vector<uint8_t> albedo(static_cast<size_t>(size) * static_cast<size_t>(size) * static_cast<size_t>(layers) * 4u);
    std::vector<uint8_t> normal(static_cast<size_t>(size) * static_cast<size_t>(size) * static_cast<size_t>(layers) * 2u);
    std::vector<float> h(static_cast<size_t>(size) * static_cast<size_t>(size));
    auto srgb = [](float x) {
        const float c = std::min(std::max(x, 0.0f), 1.0f);
        const float e = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
        return static_cast<uint8_t>(std::lround(e * 255.0f));
    };
    const float relief = 0.035f;  // metres of the height field's unit (facade tile about 4 m)
    for (int l = 0; l < layers; ++l) {
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
                const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
                const Texel t = material_texel(l, u, v);
                const size_t i = (static_cast<size_t>(l) * static_cast<size_t>(size) + static_cast<size_t>(y)) * static_cast<size_t>(size) +
                                 static_cast<size_t>(x);
                h[static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)] = t.height;
                for (int k = 0; k < 3; ++k) albedo[4 * i + static_cast<size_t>(k)] = srgb(t.albedo[k]);
                albedo[4 * i + 3] = static_cast<uint8_t>(t.glass > 0.5f ? 255 : 0);
            }
        // Normal from the height field by central differences (wrapping: the tile repeats); the
        // tile is about 4 m across, so one texel is 4 / size m and the slope is dh / (2 texel).
        const float texel_m = 4.0f / static_cast<float>(size);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                auto at = [&](int xx, int yy) {
                    xx = (xx + size) % size;
                    yy = (yy + size) % size;
                    return h[static_cast<size_t>(yy) * static_cast<size_t>(size) + static_cast<size_t>(xx)];
                };
                const float dx = relief * (at(x + 1, y) - at(x - 1, y)) / (2.0f * texel_m);
                const float dy = relief * (at(x, y + 1) - at(x, y - 1)) / (2.0f * texel_m);
                const vec3 n = glm::normalize(vec3(-dx, -dy, 1.0f));
                const size_t i = (static_cast<size_t>(l) * static_cast<size_t>(size) + static_cast<size_t>(y)) * static_cast<size_t>(size) +
                                 static_cast<size_t>(x);
                normal[2 * i] = static_cast<uint8_t>(std::lround((0.5f * n.x + 0.5f) * 255.0f));
                normal[2 * i + 1] = static_cast<uint8_t>(std::lround((0.5f * n.y + 0.5f) * 255.0f));
            }
    }
    const int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(size))));
    MaterialTextures t;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t.albedo);
    glTextureStorage3D(t.albedo, levels, GL_SRGB8_ALPHA8, size, size, layers);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(t.albedo, 0, 0, 0, 0, size, size, layers, GL_RGBA, GL_UNSIGNED_BYTE, albedo.data());
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t.normal);
    glTextureStorage3D(t.normal, levels, GL_RG8, size, size, layers);
    glTextureSubImage3D(t.normal, 0, 0, 0, 0, size, size, layers, GL_RG, GL_UNSIGNED_BYTE, normal.data());
    for (GLuint tex : {t.albedo, t.normal}) {
        glGenerateTextureMipmap(tex);
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    return t;
}

// ---------------------------------------------------------------------------------------------
// Lights: street lamps along every street

struct LightGpu {
    vec4 pos_radius;
    vec4 color;
};

std::vector<LightGpu> street_lamps(const city::City& c, float spacing)
{
    const city::CityLayout& L = c.layout;
    std::vector<LightGpu> out;
    const float intensity = 90.0f, cutoff = 0.16f;
    const float radius = raykit::point_light_radius(intensity, cutoff);
    auto add = [&](vec3 p, uint32_t k) {
        const float t = hash01(k * 2654435761u + 17u);
        const vec3 warm = glm::mix(vec3(1.0f, 0.72f, 0.42f), vec3(1.0f, 0.85f, 0.65f), t);
        out.push_back({vec4(p, radius), vec4(warm * intensity, 0.0f)});
    };
    // Street centre lines between neighbouring blocks (and the boulevard), lamps on both sides.
    auto streets = [&](int count, bool along_z, std::vector<std::pair<float, float>>& lines) {
        for (int i = 0; i + 1 < count; ++i) {
            float lo0, hi0, lo1, hi1;
            city::block_span(L, i, count, along_z, lo0, hi0);
            city::block_span(L, i + 1, count, along_z, lo1, hi1);
            lines.push_back({0.5f * (hi0 + lo1), lo1 - hi0});
        }
    };
    std::vector<std::pair<float, float>> xs, zs;  // x = const streets (between x blocks), z = const
    streets(L.blocks_x, false, xs);
    streets(L.blocks_z, true, zs);
    const float span = c.extent;
    uint32_t k = 0;
    for (const auto& s : zs)  // streets along x at z = s.first
        for (float x = -span; x <= span; x += spacing)
            for (float side : {-1.0f, 1.0f}) add(vec3(x + (side > 0 ? 0.0f : 0.5f * spacing), 6.0f, s.first + side * (0.5f * s.second - 1.5f)), k++);
    for (const auto& s : xs)  // streets along z at x = s.first
        for (float z = -span; z <= span; z += spacing)
            for (float side : {-1.0f, 1.0f}) add(vec3(s.first + side * (0.5f * s.second - 1.5f), 6.0f, z + (side > 0 ? 0.0f : 0.5f * spacing)), k++);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Frame uniforms (std140, dc_common.glsl's DcFrame)

struct FrameUbo {
    mat4 view_proj, inv_view, shadow_mat[4];
    vec4 splits, cascade_texel, view_ray, depth_k, sun_dir, sun_color, ambient, eye, viewport, layout, layout2;
};

struct View {
    std::string name;
    vec3 eye, target;
    float fov_deg = 60.0f;
    bool night = false;
    bool show_cascades = false;
    float exposure = 1.0f;
};

struct Settings {
    int width = 1280, height = 720;
    int shadow_size = 2048;
    int texture_size = 256;
    int pcf_taps = 16;
    bool quick = false;
};

constexpr float kNear = 0.5f, kFar = 4000.0f, kShadowFar = 700.0f;

/// The reversed-Z perspective projection ([0, 1] depth, near at 1).
mat4 reversed_projection(float fov_y, float aspect)
{
    mat4 p = glm::perspectiveRH_ZO(fov_y, aspect, kNear, kFar);
    mat4 flip(1.0f);
    flip[2][2] = -1.0f;
    flip[3][2] = 1.0f;
    return flip * p;
}

GLuint texture2d(GLenum format, int w, int h, GLint filter)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

std::string read_shader(const std::string& file, const std::vector<raykit::ShaderDefine>& defines = {})
{
    return rkgl::shader_file(std::string(SAMPLES_DIR) + "/deferred_city/" + file, {std::string(SAMPLES_DIR) + "/deferred_city", RAYKIT_SHADER_DIR},
                             defines);
}

class Renderer {
public:
    Renderer(const city::City& c, const Settings& s) : city_(c), s_(s)
    {
        const std::vector<raykit::ShaderDefine> sh_defs = {{"RK_SH_MAX_TAPS", "32"}};
        geom_vs_ = read_shader("dc_geom.vert", sh_defs);
        gbuffer_ = rkgl::build_program({{GL_VERTEX_SHADER, geom_vs_}, {GL_FRAGMENT_SHADER, read_shader("dc_gbuffer.frag", sh_defs)}});
        forward_ = rkgl::build_program({{GL_VERTEX_SHADER, geom_vs_}, {GL_FRAGMENT_SHADER, read_shader("dc_forward.frag", sh_defs)}});
        shadow_ = rkgl::build_program({{GL_VERTEX_SHADER, read_shader("dc_geom.vert", {{"RK_SH_MAX_TAPS", "32"}, {"DC_SHADOW", "1"}})}});
        const std::string fs = read_shader("dc_fullscreen.vert");
        sun_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("dc_sun.frag", sh_defs)}});
        sky_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("dc_sky.frag", sh_defs)}});
        post_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("dc_post.frag", sh_defs)}});
        light_ = rkgl::build_program({{GL_VERTEX_SHADER, read_shader("dc_light.vert", sh_defs)},
                                      {GL_FRAGMENT_SHADER, read_shader("dc_light.frag", sh_defs)}});

        // Scene mesh.
        const std::vector<Vertex> verts = build_mesh(city_, 48);
        vertex_count_ = static_cast<GLsizei>(verts.size());
        glCreateBuffers(1, &vbo_);
        glNamedBufferStorage(vbo_, static_cast<GLsizeiptr>(verts.size() * sizeof(Vertex)), verts.data(), 0);
        glCreateVertexArrays(1, &vao_);
        glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(Vertex));
        const GLint sizes[5] = {3, 3, 4, 2, 2};
        const GLuint offsets[5] = {offsetof(Vertex, pos), offsetof(Vertex, normal), offsetof(Vertex, tangent), offsetof(Vertex, uv),
                                   offsetof(Vertex, mat)};
        for (GLuint a = 0; a < 5; ++a) {
            glEnableVertexArrayAttrib(vao_, a);
            glVertexArrayAttribFormat(vao_, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
            glVertexArrayAttribBinding(vao_, a, 0);
        }
        // Light volume: an icosphere subdivided once, containing the unit ball.
        const raykit::LightVolumeMesh sphere = raykit::light_volume_sphere(1);
        sphere_radius_ = 0.0f;
        for (const raykit::vec3& p : sphere.positions) sphere_radius_ = std::max(sphere_radius_, glm::length(p));
        sphere_index_count_ = static_cast<GLsizei>(sphere.indices.size());
        glCreateBuffers(1, &sphere_vbo_);
        glNamedBufferStorage(sphere_vbo_, static_cast<GLsizeiptr>(sphere.positions.size() * sizeof(raykit::vec3)), sphere.positions.data(), 0);
        glCreateBuffers(1, &sphere_ibo_);
        glNamedBufferStorage(sphere_ibo_, static_cast<GLsizeiptr>(sphere.indices.size() * sizeof(uint32_t)), sphere.indices.data(), 0);
        glCreateVertexArrays(1, &sphere_vao_);
        glVertexArrayVertexBuffer(sphere_vao_, 0, sphere_vbo_, 0, sizeof(raykit::vec3));
        glVertexArrayElementBuffer(sphere_vao_, sphere_ibo_);
        glEnableVertexArrayAttrib(sphere_vao_, 0);
        glVertexArrayAttribFormat(sphere_vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(sphere_vao_, 0, 0);

        tex_ = make_textures(s_.texture_size);

        // Cascades: four depth maps with hardware compare (a 2x2 PCF per tap).
        for (int i = 0; i < 4; ++i) {
            cascade_[i] = texture2d(GL_DEPTH_COMPONENT32F, s_.shadow_size, s_.shadow_size, GL_LINEAR);
            glTextureParameteri(cascade_[i], GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            glTextureParameteri(cascade_[i], GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
            glCreateFramebuffers(1, &cascade_fbo_[i]);
            glNamedFramebufferTexture(cascade_fbo_[i], GL_DEPTH_ATTACHMENT, cascade_[i], 0);
            glNamedFramebufferDrawBuffer(cascade_fbo_[i], GL_NONE);
        }

        // G-buffer (compact preset), HDR target sharing its depth, display target.
        const int w = s_.width, h = s_.height;
        gb_albedo_ = texture2d(GL_SRGB8_ALPHA8, w, h, GL_NEAREST);
        gb_normal_ = texture2d(GL_R32UI, w, h, GL_NEAREST);
        gb_material_ = texture2d(GL_RGBA8, w, h, GL_NEAREST);
        gb_extra_ = texture2d(GL_R32UI, w, h, GL_NEAREST);
        gb_depth_ = texture2d(GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
        hdr_ = texture2d(GL_RGBA16F, w, h, GL_LINEAR);
        ldr_ = texture2d(GL_RGBA8, w, h, GL_NEAREST);
        glCreateFramebuffers(1, &gb_fbo_);
        const GLuint gb_tex[4] = {gb_albedo_, gb_normal_, gb_material_, gb_extra_};
        GLenum bufs[4];
        for (int i = 0; i < 4; ++i) {
            glNamedFramebufferTexture(gb_fbo_, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), gb_tex[i], 0);
            bufs[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
        }
        glNamedFramebufferDrawBuffers(gb_fbo_, 4, bufs);
        glNamedFramebufferTexture(gb_fbo_, GL_DEPTH_ATTACHMENT, gb_depth_, 0);
        glCreateFramebuffers(1, &hdr_fbo_);
        glNamedFramebufferTexture(hdr_fbo_, GL_COLOR_ATTACHMENT0, hdr_, 0);
        glNamedFramebufferTexture(hdr_fbo_, GL_DEPTH_ATTACHMENT, gb_depth_, 0);
        glCreateFramebuffers(1, &ldr_fbo_);
        glNamedFramebufferTexture(ldr_fbo_, GL_COLOR_ATTACHMENT0, ldr_, 0);
        for (GLuint f : {gb_fbo_, hdr_fbo_, ldr_fbo_, cascade_fbo_[0]})
            if (glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw std::runtime_error("incomplete framebuffer");

        glCreateBuffers(1, &ubo_);
        glNamedBufferStorage(ubo_, sizeof(FrameUbo), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateVertexArrays(1, &empty_vao_);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    }

    ~Renderer()
    {
        for (GLuint p : {gbuffer_, forward_, shadow_, sun_, sky_, post_, light_}) glDeleteProgram(p);
        GLuint bufs[5] = {vbo_, sphere_vbo_, sphere_ibo_, ubo_, lights_buf_};
        glDeleteBuffers(5, bufs);
        GLuint vaos[3] = {vao_, sphere_vao_, empty_vao_};
        glDeleteVertexArrays(3, vaos);
        GLuint texs[9] = {tex_.albedo, tex_.normal, gb_albedo_, gb_normal_, gb_material_, gb_extra_, gb_depth_, hdr_, ldr_};
        glDeleteTextures(9, texs);
        glDeleteTextures(4, cascade_);
        glDeleteFramebuffers(4, cascade_fbo_);
        GLuint fbos[3] = {gb_fbo_, hdr_fbo_, ldr_fbo_};
        glDeleteFramebuffers(3, fbos);
    }
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Sets the camera, the sun (cascades rendered) and the point lights (sorted by cull mode).
    void setup(const View& v, const std::vector<LightGpu>& lights)
    {
        const float aspect = static_cast<float>(s_.width) / static_cast<float>(s_.height), fov = glm::radians(v.fov_deg);
        const mat4 view = glm::lookAt(v.eye, v.target, vec3(0, 1, 0));
        const mat4 proj = reversed_projection(fov, aspect);
        const mat4 cam_to_world = glm::inverse(view);
        FrameUbo f{};
        f.view_proj = proj * view;
        f.inv_view = cam_to_world;
        f.view_ray = raykit::gbuffer_view_ray(proj);
        f.depth_k = vec4(raykit::gbuffer_depth_params(kNear, kFar, true), 0.0f);
        f.eye = vec4(v.eye, static_cast<float>(lights.size()));
        f.viewport = vec4(static_cast<float>(s_.width), static_cast<float>(s_.height), 1.0f / static_cast<float>(s_.width),
                          1.0f / static_cast<float>(s_.height));
        const city::CityLayout& L = city_.layout;
        f.layout = vec4(L.pitch(), L.block, L.boulevard - L.street, static_cast<float>(L.blocks_x));
        f.layout2 = vec4(static_cast<float>(L.blocks_z), static_cast<float>(s_.shadow_size), v.show_cascades ? 1.0f : 0.0f,
                         static_cast<float>(s_.pcf_taps));
        const vec3 sun = v.night ? glm::normalize(vec3(-0.3f, 0.6f, -0.5f)) : glm::normalize(vec3(-0.51f, 0.77f, 0.38f));
        f.sun_dir = vec4(sun, 1.0f);
        f.sun_color = v.night ? vec4(0.02f, 0.025f, 0.04f, 4.0f) : vec4(3.2f, 2.9f, 2.5f, 4.0f);
        f.ambient = v.night ? vec4(0.004f, 0.005f, 0.009f, 1.2f) : vec4(0.32f, 0.38f, 0.48f, 0.0f);
        // Cascades over the first kShadowFar metres, practical split (lambda 0.8).
        f.splits = raykit::cascade_splits(kNear, kShadowFar, 4, 0.8f);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_DEPTH_CLAMP);  // casters beyond the box's near plane are flattened onto it, not lost
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glUseProgram(shadow_);
        glBindVertexArray(vao_);
        glViewport(0, 0, s_.shadow_size, s_.shadow_size);
        float split_near = kNear;
        for (int i = 0; i < 4; ++i) {
            const raykit::CascadeFit fit =
                raykit::fit_cascade(cam_to_world, fov, aspect, split_near, f.splits[i], -sun, s_.shadow_size, 400.0f, true);
            f.shadow_mat[i] = raykit::shadow_matrix(fit.projection, fit.view, mat4(1.0f), true);
            f.cascade_texel[i] = static_cast<float>(fit.texel);
            const mat4 lvp = fit.projection * fit.view;
            glUniformMatrix4fv(0, 1, GL_FALSE, &lvp[0][0]);
            glBindFramebuffer(GL_FRAMEBUFFER, cascade_fbo_[i]);
            glClearDepth(1.0);
            glClear(GL_DEPTH_BUFFER_BIT);
            glDrawArrays(GL_TRIANGLES, 0, vertex_count_);
            split_near = f.splits[i];
        }
        glDisable(GL_DEPTH_CLAMP);
        frame_ = f;
        glNamedBufferSubData(ubo_, 0, sizeof(FrameUbo), &frame_);

        // Lights: the ones whose volume may reach the near plane first (drawn with back faces).
        const float reach = raykit::near_plane_reach(kNear, proj[0][0], proj[1][1]);
        std::vector<LightGpu> sorted;
        inside_ = 0;
        for (int pass = 0; pass < 2; ++pass)
            for (const LightGpu& l : lights) {
                const bool front = raykit::light_volume_cull_sphere(vec3(l.pos_radius), l.pos_radius.w, sphere_radius_, v.eye, reach) ==
                                   raykit::LightVolumeCull::front;
                if (front == (pass == 0)) sorted.push_back(l);
                if (front && pass == 0) ++inside_;
            }
        light_count_ = static_cast<GLsizei>(sorted.size());
        if (lights_buf_) glDeleteBuffers(1, &lights_buf_);
        sorted.push_back(LightGpu{});  // never an empty buffer
        glCreateBuffers(1, &lights_buf_);
        glNamedBufferStorage(lights_buf_, static_cast<GLsizeiptr>(sorted.size() * sizeof(LightGpu)), sorted.data(), 0);
    }

    void bind_common()
    {
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, lights_buf_);
        for (int i = 0; i < 4; ++i) glBindTextureUnit(static_cast<GLuint>(4 + i), cascade_[i]);
    }

    /// The deferred path into the HDR target: G-buffer, sun pass, light volumes.
    void render_deferred()
    {
        bind_common();
        glViewport(0, 0, s_.width, s_.height);
        glBindFramebuffer(GL_FRAMEBUFFER, gb_fbo_);
        glEnable(GL_FRAMEBUFFER_SRGB);  // the albedo target is SRGB8_ALPHA8
        const GLuint zero_u[4] = {0, 0, 0, 0};
        const float zero_f[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(gb_fbo_, GL_COLOR, 0, zero_f);
        glClearNamedFramebufferuiv(gb_fbo_, GL_COLOR, 1, zero_u);
        glClearNamedFramebufferfv(gb_fbo_, GL_COLOR, 2, zero_f);
        glClearNamedFramebufferuiv(gb_fbo_, GL_COLOR, 3, zero_u);
        glClearDepth(0.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glUseProgram(gbuffer_);
        glBindTextureUnit(0, tex_.albedo);
        glBindTextureUnit(1, tex_.normal);
        glBindVertexArray(vao_);
        glDrawArrays(GL_TRIANGLES, 0, vertex_count_);
        glDisable(GL_FRAMEBUFFER_SRGB);

        // Lighting: read the G-buffer, add into HDR (depth attached read-only for the volume test).
        glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_);
        glBindTextureUnit(0, gb_albedo_);
        glBindTextureUnit(1, gb_normal_);
        glBindTextureUnit(2, gb_material_);
        glBindTextureUnit(3, gb_extra_);
        glBindTextureUnit(8, gb_depth_);
        glDepthMask(GL_FALSE);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glUseProgram(sun_);
        glBindVertexArray(empty_vao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);

        if (light_count_ > 0) {
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            glEnable(GL_DEPTH_TEST);
            glEnable(GL_CULL_FACE);
            glUseProgram(light_);
            glBindVertexArray(sphere_vao_);
            // Camera (or near plane) possibly inside: back faces, where they lie behind the scene.
            if (inside_ > 0) {
                glCullFace(GL_FRONT);
                glDepthFunc(GL_LEQUAL);
                glUniform1i(0, 0);
                glDrawElementsInstanced(GL_TRIANGLES, sphere_index_count_, GL_UNSIGNED_INT, nullptr, inside_);
            }
            // Outside: front faces, where they lie in front of the scene (reversed-Z: greater).
            if (light_count_ > inside_) {
                glCullFace(GL_BACK);
                glDepthFunc(GL_GEQUAL);
                glUniform1i(0, inside_);
                glDrawElementsInstanced(GL_TRIANGLES, sphere_index_count_, GL_UNSIGNED_INT, nullptr, light_count_ - inside_);
            }
            glDisable(GL_BLEND);
        }
        glDepthMask(GL_TRUE);
        glCullFace(GL_BACK);
    }

    /// The forward path into the HDR target: sky, then every surface lit by every light.
    void render_forward()
    {
        bind_common();
        glViewport(0, 0, s_.width, s_.height);
        glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_);
        glClearDepth(0.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glUseProgram(sky_);
        glBindVertexArray(empty_vao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glUseProgram(forward_);
        glBindTextureUnit(0, tex_.albedo);
        glBindTextureUnit(1, tex_.normal);
        glBindVertexArray(vao_);
        glDrawArrays(GL_TRIANGLES, 0, vertex_count_);
    }

    /// Edge AA (mode 0 off, 1 on, 2 edge weights shown), exposure and tone mapping into RGBA8;
    /// returns the pixels top row first.
    std::vector<uint8_t> post(float exposure, int edge_aa)
    {
        glBindFramebuffer(GL_FRAMEBUFFER, ldr_fbo_);
        glViewport(0, 0, s_.width, s_.height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glUseProgram(post_);
        glBindTextureUnit(9, hdr_);
        glBindTextureUnit(1, gb_normal_);
        glBindTextureUnit(8, gb_depth_);
        glUniform1f(0, exposure);
        glUniform1i(1, edge_aa);
        glBindVertexArray(empty_vao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        std::vector<uint8_t> px(static_cast<size_t>(s_.width) * static_cast<size_t>(s_.height) * 4u);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTextureImage(ldr_, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(px.size()), px.data());
        return flip_rows(px, 4);
    }

    /// The HDR target as floats (RGBA), row 0 at the bottom.
    std::vector<float> read_hdr()
    {
        std::vector<float> px(static_cast<size_t>(s_.width) * static_cast<size_t>(s_.height) * 4u);
        glGetTextureImage(hdr_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(px.size() * sizeof(float)), px.data());
        return px;
    }

    std::vector<uint8_t> flip_rows(const std::vector<uint8_t>& px, int channels) const
    {
        std::vector<uint8_t> out(px.size());
        const size_t row = static_cast<size_t>(s_.width) * static_cast<size_t>(channels);
        for (int y = 0; y < s_.height; ++y)
            std::memcpy(&out[static_cast<size_t>(y) * row], &px[static_cast<size_t>(s_.height - 1 - y) * row], row);
        return out;
    }

    GLsizei lights_inside() const { return inside_; }
    GLsizei lights() const { return light_count_; }
    size_t triangles() const { return static_cast<size_t>(vertex_count_) / 3; }

private:
    const city::City& city_;
    Settings s_;
    std::string geom_vs_;
    GLuint gbuffer_ = 0, forward_ = 0, shadow_ = 0, sun_ = 0, sky_ = 0, post_ = 0, light_ = 0;
    GLuint vbo_ = 0, vao_ = 0, sphere_vbo_ = 0, sphere_ibo_ = 0, sphere_vao_ = 0, ubo_ = 0, lights_buf_ = 0, empty_vao_ = 0;
    GLsizei vertex_count_ = 0, sphere_index_count_ = 0, light_count_ = 0, inside_ = 0;
    float sphere_radius_ = 1.0f;
    MaterialTextures tex_;
    GLuint cascade_[4] = {}, cascade_fbo_[4] = {};
    GLuint gb_albedo_ = 0, gb_normal_ = 0, gb_material_ = 0, gb_extra_ = 0, gb_depth_ = 0, hdr_ = 0, ldr_ = 0;
    GLuint gb_fbo_ = 0, hdr_fbo_ = 0, ldr_fbo_ = 0;
    FrameUbo frame_{};
};

// ---------------------------------------------------------------------------------------------
// Views, comparison, benchmark

std::vector<View> make_views()
{
    std::vector<View> v;
    v.push_back({"day", vec3(-235.0f, 7.0f, 9.0f), vec3(-60.0f, 22.0f, -4.0f), 62.0f, false, false, 0.9f});
    v.push_back({"cascades", vec3(-250.0f, 95.0f, 170.0f), vec3(-20.0f, 0.0f, -20.0f), 60.0f, false, true, 0.9f});
    v.push_back({"night", vec3(-262.0f, 24.0f, -3.0f), vec3(-120.0f, 0.0f, 4.0f), 64.0f, true, false, 2.0f});
    return v;
}

/// Display mapping used to compare HDR images: x / (1 + x) per channel, after the exposure.
double display(double x) { return x > 0.0 ? x / (1.0 + x) : 0.0; }

struct Compare {
    double max_diff = 0.0, mean_diff = 0.0, frac_over = 0.0, p999 = 0.0;
    bool finite = true;
};

Compare compare_images(const std::vector<float>& a, const std::vector<float>& b, float exposure, double tol)
{
    Compare c;
    std::vector<double> d;
    size_t over = 0;
    for (size_t i = 0; i + 3 < a.size(); i += 4) {
        double m = 0.0;
        for (int k = 0; k < 3; ++k) {
            const float x = a[i + static_cast<size_t>(k)], y = b[i + static_cast<size_t>(k)];
            if (!std::isfinite(x) || !std::isfinite(y)) c.finite = false;
            m = std::max(m, std::abs(display(static_cast<double>(x) * exposure) - display(static_cast<double>(y) * exposure)));
        }
        d.push_back(m);
        c.mean_diff += m;
        c.max_diff = std::max(c.max_diff, m);
        if (m > tol) ++over;
    }
    c.mean_diff /= static_cast<double>(std::max<size_t>(d.size(), 1));
    c.frac_over = static_cast<double>(over) / static_cast<double>(std::max<size_t>(d.size(), 1));
    std::sort(d.begin(), d.end());
    if (!d.empty()) c.p999 = d[std::min(d.size() - 1, static_cast<size_t>(0.999 * static_cast<double>(d.size())))];
    return c;
}

struct Options {
    bool quick = false, bench = false;
    int reps = 7;
    std::string bench_out;
    int width = 1280, height = 720;
    std::string out_dir = ".";
};

bool parse(int argc, char** argv, Options& o)
{
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") {
            o.quick = true;
            o.width = 320;
            o.height = 180;
        } else if (a == "--bench") {
            o.bench = true;
        } else if (a == "--reps" && i + 1 < argc) {
            o.reps = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--bench-out" && i + 1 < argc) {
            o.bench_out = argv[++i];
        } else if (a == "--size" && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16) return false;
        } else if (!a.empty() && a[0] == '-') {
            return false;
        } else {
            o.out_dir = a;
        }
    }
    return true;
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(const Options& opt)
{
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) return rkgl::no_context_exit("deferred_city", ctx.error());
    std::printf("deferred_city: %s\n", ctx.renderer().c_str());
    Settings s;
    s.width = opt.width;
    s.height = opt.height;
    s.quick = opt.quick;
    if (opt.quick) {
        s.shadow_size = 1024;
        s.texture_size = 128;
    }
    const city::City c = city::make_city(7);
    const std::vector<LightGpu> lamps = street_lamps(c, 24.0f);
    Renderer r(c, s);
    std::printf("city: %zu buildings, %zu triangles, %zu street lamps; G-buffer %d bits/px (compact preset)\n", c.buildings.size(),
                r.triangles(), lamps.size(), raykit::gbuffer_bits_per_pixel(raykit::gbuffer_layout_compact()));
    int failures = 0;

    if (opt.bench) {
        // Forward vs deferred frame time as the light count grows (night view; forward and deferred
        // frames interleaved, the first pair a warm-up, medians of the rest). Shadow maps are
        // rendered once per light count, outside the timing; both paths then draw the same frame.
        const View v = make_views()[2];
        std::string md;
        char line[512];
        std::snprintf(line, sizeof line,
                      "Summary (night view of the deferred city, %dx%d, %d repetitions, median ms per frame; the ratio's spread is "
                      "max/min of the per-repetition ratio):\n\n",
                      s.width, s.height, opt.reps);
        md += line;
        md += "| point lights | forward (ms) | deferred (ms) | forward / deferred | spread |\n| ---: | ---: | ---: | ---: | ---: |\n";
        for (size_t n : {size_t(0), size_t(8), size_t(32), size_t(128), size_t(512)}) {
            std::vector<LightGpu> sub;
            for (size_t i = 0; i < n && !lamps.empty(); ++i) sub.push_back(lamps[(i * 7919u) % lamps.size()]);
            r.setup(v, sub);
            std::vector<double> tf, td, ratio;
            for (int rep = 0; rep <= opt.reps; ++rep) {
                glFinish();
                auto t0 = std::chrono::steady_clock::now();
                r.render_forward();
                glFinish();
                const double f = seconds_since(t0);
                t0 = std::chrono::steady_clock::now();
                r.render_deferred();
                glFinish();
                const double d = seconds_since(t0);
                if (rep == 0) continue;  // warm-up
                tf.push_back(f);
                td.push_back(d);
                ratio.push_back(f / d);
            }
            auto med = [](std::vector<double> x) {
                std::sort(x.begin(), x.end());
                return x[x.size() / 2];
            };
            const double rmin = *std::min_element(ratio.begin(), ratio.end()), rmax = *std::max_element(ratio.begin(), ratio.end());
            std::snprintf(line, sizeof line, "| %zu | %.1f | %.1f | %.2f | %.2f |\n", n, 1e3 * med(tf), 1e3 * med(td), med(ratio), rmax / rmin);
            md += line;
        }
        md += "\nG-buffer presets (raykit::gbuffer_bits_per_pixel, the depth buffer included):\n\n| preset | bits per pixel | bytes per pixel |\n| --- | ---: | ---: |\n";
        for (const auto& pr : {std::make_pair("gbuffer_layout_thesis()", raykit::gbuffer_layout_thesis()),
                               std::make_pair("gbuffer_layout_compact()", raykit::gbuffer_layout_compact())}) {
            const int bits = raykit::gbuffer_bits_per_pixel(pr.second);
            std::snprintf(line, sizeof line, "| `%s` | %d | %d |\n", pr.first, bits, bits / 8);
            md += line;
        }
        std::printf("%s", md.c_str());
        if (!opt.bench_out.empty()) {
            FILE* f = std::fopen(opt.bench_out.c_str(), "w");
            if (!f) {
                std::fprintf(stderr, "cannot write %s\n", opt.bench_out.c_str());
                return 1;
            }
            std::fprintf(f, "**Renderer**: %s\n\n%s", ctx.renderer().c_str(), md.c_str());
            std::fclose(f);
        }
        return 0;
    }

    for (const View& v : make_views()) {
        const auto t0 = std::chrono::steady_clock::now();
        r.setup(v, v.night ? lamps : std::vector<LightGpu>{});
        r.render_deferred();
        const std::vector<uint8_t> px = r.post(v.exposure, 1);
        glFinish();
        const std::string path = opt.out_dir + "/deferred_" + v.name + ".png";
        if (!rkgl::write_png_rgba8(path, s.width, s.height, px.data())) {
            std::fprintf(stderr, "cannot write %s\n", path.c_str());
            return 1;
        }
        std::printf("%-9s %d lights (%d drawn with back faces), %.2f s -> %s\n", v.name.c_str(), static_cast<int>(r.lights()),
                    static_cast<int>(r.lights_inside()), seconds_since(t0), path.c_str());
        // Checks: a finite image that is neither black nor blown out.
        const std::vector<float> hdr = r.read_hdr();
        double mean = 0.0;
        bool finite = true;
        for (size_t i = 0; i + 3 < hdr.size(); i += 4) {
            for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(hdr[i + static_cast<size_t>(k)]);
            mean += display(static_cast<double>(hdr[i + 1]) * v.exposure);
        }
        mean /= static_cast<double>(hdr.size() / 4);
        if (!finite || mean < 0.02 || mean > 0.9) {
            std::fprintf(stderr, "FAIL %s: finite %d, mean displayed green %.3f\n", v.name.c_str(), finite ? 1 : 0, mean);
            ++failures;
        }
    }

    // Forward against deferred, the night view with every lamp (the day view has one light, the sun).
    const double tol = 0.01;
    for (const View& v : make_views()) {
        if (v.show_cascades) continue;
        r.setup(v, v.night ? lamps : std::vector<LightGpu>{});
        r.render_forward();
        const std::vector<float> fwd = r.read_hdr();
        const std::vector<uint8_t> fwd_px = r.post(v.exposure, 0);
        r.render_deferred();
        const std::vector<float> def = r.read_hdr();
        const std::vector<uint8_t> def_px = r.post(v.exposure, 0);
        const Compare cmp = compare_images(fwd, def, v.exposure, tol);
        std::printf("forward vs deferred, %s view (%d lights): max %.4f, 99.9th percentile %.4f, mean %.2e, pixels over %.3f: %.4f %%\n",
                    v.name.c_str(), static_cast<int>(r.lights()), cmp.max_diff, cmp.p999, cmp.mean_diff, tol, 100.0 * cmp.frac_over);
        if (!cmp.finite || cmp.p999 > tol || cmp.frac_over > 0.002) {
            std::fprintf(stderr, "FAIL: forward and deferred differ beyond the stated tolerance\n");
            ++failures;
        }
        if (v.night) {
            // forward | deferred | 20 x |difference|
            const int w = s.width, h = s.height;
            std::vector<uint8_t> panel(static_cast<size_t>(3 * w) * static_cast<size_t>(h) * 4u);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4u;
                    const size_t hi = (static_cast<size_t>(h - 1 - y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4u;
                    for (int k = 0; k < 4; ++k) {
                        const size_t o = (static_cast<size_t>(y) * static_cast<size_t>(3 * w) + static_cast<size_t>(x)) * 4u + static_cast<size_t>(k);
                        panel[o] = fwd_px[i + static_cast<size_t>(k)];
                        panel[o + static_cast<size_t>(w) * 4u] = def_px[i + static_cast<size_t>(k)];
                        double dd = 0.0;
                        if (k < 3)
                            dd = 20.0 * std::abs(display(static_cast<double>(fwd[hi + static_cast<size_t>(k)]) * v.exposure) -
                                                 display(static_cast<double>(def[hi + static_cast<size_t>(k)]) * v.exposure));
                        panel[o + static_cast<size_t>(2 * w) * 4u] = k < 3 ? static_cast<uint8_t>(std::lround(255.0 * std::min(dd, 1.0))) : 255;
                    }
                }
            const std::string path = opt.out_dir + "/deferred_compare.png";
            if (!rkgl::write_png_rgba8(path, 3 * w, h, panel.data())) {
                std::fprintf(stderr, "cannot write %s\n", path.c_str());
                return 1;
            }
        }
    }
    if (failures) std::fprintf(stderr, "deferred_city: %d check(s) failed\n", failures);
    return failures ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv)
{
    Options opt;
    if (!parse(argc, argv, opt)) {
        std::fprintf(stderr, "usage: deferred_city [--quick] [--size WxH] [--bench [--reps N] [--bench-out FILE]] [OUT_DIR]\n");
        return 2;
    }
    try {
        return run(opt);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "deferred_city: %s\n", e.what());
        return 1;
    }
}
