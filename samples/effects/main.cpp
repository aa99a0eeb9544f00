// effects: raykit's raycasting screen effects together (van Dongen, "Interior Mapping: A new
// technique for rendering realistic buildings", chapters 4 and 6):
//   - smoke puffs three ways side by side, as the thesis's figure 6.22 compares them: plain
//     billboards (a hard line where they cut the ground and the wall), 9 slices laid out as a sphere
//     with the vertex-shader uv correction, and raytraced volumes (soft particles: a sphere cast per
//     pixel against the depth buffer, volume.glsl);
//   - screen-space ambient occlusion (ssao.glsl: normal-oriented hemisphere, depth-aware blur);
//   - light shafts from a low sun through a colonnade (lightshafts.glsl);
//   - a relief-mapped brick wall and paving, cone stepping on conservative cone maps with
//     self-shadowing (relief.glsl).
// Views written as PNG (headless EGL): effects_volumes.png, effects_relief.png (close up, raking
// sun), effects_sunset.png, effects_ssao.png (the AO buffer). --bench times the thesis's volume protocol (figure 6.23): a particle system drawn
// as billboards, 5 to 79 slices (8-bit and float colour buffers) and each raytraced primitive and
// opacity function, as ratios to the billboard frame.
//
// Usage: effects [--quick] [--size WxH] [--bench [--reps N] [--bench-out FILE]] [OUT_DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/gbuffer.hpp"
#include "raykit/lightshafts.hpp"
#include "raykit/relief.hpp"
#include "raykit/ssao.hpp"
#include "raykit/volume.hpp"
#include "rk_gl.hpp"
#include "rk_png.hpp"

namespace {

using glm::mat4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

constexpr float kNear = 0.1f, kFar = 1000.0f;

struct Vertex {
    float pos[3], normal[3], albedo[3], material;
};

/// A box; material 0 plain, 1 relief-mapped bricks, 2 relief-mapped paving (fx_geom.frag).
void add_box(std::vector<Vertex>& v, vec3 lo, vec3 hi, vec3 albedo, float material = 0.0f)
{
    const vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int faces[6][4] = {{4, 5, 6, 7}, {1, 0, 3, 2}, {5, 1, 2, 6}, {0, 4, 7, 3}, {7, 6, 2, 3}, {0, 1, 5, 4}};
    const vec3 normals[6] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
    for (int f = 0; f < 6; ++f)
        for (int k : {0, 1, 2, 0, 2, 3}) {
            const vec3 p = c[faces[f][k]], n = normals[f];
            v.push_back(Vertex{{p.x, p.y, p.z}, {n.x, n.y, n.z}, {albedo.x, albedo.y, albedo.z}, material});
        }
}

std::vector<Vertex> build_scene()
{
    std::vector<Vertex> v;
    add_box(v, vec3(-150.0f, -1.0f, -150.0f), vec3(150.0f, 0.0f, 150.0f), vec3(0.45f, 0.43f, 0.40f), 2.0f);  // ground
    add_box(v, vec3(-14.0f, 0.0f, -8.0f), vec3(14.0f, 5.0f, -7.4f), vec3(0.62f, 0.56f, 0.50f), 1.0f);  // wall
    add_box(v, vec3(-5.6f, 0.0f, -3.6f), vec3(-4.4f, 1.2f, -2.4f), vec3(0.55f, 0.42f, 0.30f));         // crates
    add_box(v, vec3(-4.3f, 0.0f, -3.8f), vec3(-3.1f, 1.2f, -2.6f), vec3(0.55f, 0.42f, 0.30f));
    add_box(v, vec3(3.4f, 0.0f, -2.6f), vec3(4.6f, 1.2f, -1.4f), vec3(0.5f, 0.45f, 0.35f));
    add_box(v, vec3(3.6f, 1.2f, -2.5f), vec3(4.4f, 2.0f, -1.7f), vec3(0.5f, 0.45f, 0.35f));
    for (int i = -4; i <= 4; ++i) {  // the colonnade and its lintel
        const float x = 6.0f * static_cast<float>(i);
        add_box(v, vec3(x - 0.75f, 0.0f, -40.0f), vec3(x + 0.75f, 16.0f, -38.5f), vec3(0.5f, 0.47f, 0.42f));
    }
    add_box(v, vec3(-26.0f, 16.0f, -40.5f), vec3(26.0f, 17.5f, -38.0f), vec3(0.5f, 0.47f, 0.42f));
    return v;
}

/// The smoke texture: a soft blob of value noise whose alpha stays inside the unit disk (the
/// thesis's first sphere pitfall: alpha beyond the silhouette shows as a hard circle).
GLuint smoke_texture(int size)
{
    std::vector<uint8_t> px(static_cast<size_t>(size) * static_cast<size_t>(size) * 4u);
    auto hash = [](int x, int y) {
        uint32_t h = static_cast<uint32_t>(x) * 374761393u + static_cast<uint32_t>(y) * 668265263u;
        h = (h ^ (h >> 13)) * 1274126177u;
        return static_cast<float>((h ^ (h >> 16)) & 0xFFFFu) / 65535.0f;
    };
    auto noise = [&](float x, float y) {
        const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
        const float fx = x - static_cast<float>(xi), fy = y - static_cast<float>(yi);
        const float sx = fx * fx * (3.0f - 2.0f * fx), sy = fy * fy * (3.0f - 2.0f * fy);
        const float a = hash(xi, yi) + sx * (hash(xi + 1, yi) - hash(xi, yi));
        const float b = hash(xi, yi + 1) + sx * (hash(xi + 1, yi + 1) - hash(xi, yi + 1));
        return a + sy * (b - a);
    };
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size) * 2.0f - 1.0f;
            const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size) * 2.0f - 1.0f;
            const float r = std::sqrt(u * u + v * v);
            float n = 0.0f, amp = 0.5f, f = 3.0f;
            for (int o = 0; o < 4; ++o, amp *= 0.5f, f *= 2.0f) n += amp * noise(u * f + 7.0f, v * f + 3.0f);
            const float blob = 1.0f - std::min(std::max((r - 0.35f) / (0.95f - 0.35f), 0.0f), 1.0f);
            const float a = std::min(std::max(blob * blob * (3.0f - 2.0f * blob) * (0.45f + 0.75f * n), 0.0f), 1.0f);
            const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)) * 4u;
            const uint8_t g = static_cast<uint8_t>(std::lround(255.0f * (0.75f + 0.25f * n)));
            px[i] = px[i + 1] = px[i + 2] = g;
            px[i + 3] = static_cast<uint8_t>(std::lround(255.0f * a));
        }
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    const int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(size))));
    glTextureStorage2D(t, levels, GL_RGBA8, size, size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t, 0, 0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glGenerateTextureMipmap(t);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

/// A relief material's depth map with its conservative cone map (relief.hpp), as an RG32F texture
/// (REPEAT, LINEAR: the sampler rk_relief_read's C++ twin assumes): bricks (4 across and 8 courses a
/// metre, mortar 1 deep) or paving (2 x 2 stones a repeat, domed faces).
GLuint relief_texture(bool bricks, int size)
{
    raykit::ReliefMapCpu m;
    m.width = m.height = size;
    m.wrap = true;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size), v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
            const float cx = bricks ? 4.0f : 2.0f, cy = bricks ? 8.0f : 2.0f;
            const float row = std::floor(v * cy);
            const float su = u * cx + (bricks && static_cast<int>(row) % 2 ? 0.5f : 0.0f), sv = v * cy;
            const float fu = su - std::floor(su), fv = sv - std::floor(sv);
            const float gu = std::min(fu, 1.0f - fu) * (bricks ? 0.25f : 0.5f), gv = std::min(fv, 1.0f - fv) * (bricks ? 0.125f : 0.5f);
            const float edge = std::min(gu, gv);  // metres (of a 1 m tile) to the joint
            const float joint = bricks ? 0.008f : 0.012f, bevel = 0.012f;
            float d = edge < joint ? 1.0f : 0.15f + 0.85f * std::max(0.0f, 1.0f - (edge - joint) / bevel);
            if (!bricks && edge >= joint) d -= 0.1f * (1.0f - 4.0f * ((fu - 0.5f) * (fu - 0.5f) + (fv - 0.5f) * (fv - 0.5f)));
            m.texels.push_back(raykit::vec2(std::min(std::max(d, 0.0f), 1.0f), 0.0f));
        }
    raykit::relief_build_cones(m);
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, GL_RG32F, size, size);
    glTextureSubImage2D(t, 0, 0, 0, size, size, GL_RG, GL_FLOAT, m.texels.data());
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
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

GLuint framebuffer(std::vector<GLuint> colours, GLuint depth)
{
    GLuint f = 0;
    glCreateFramebuffers(1, &f);
    std::vector<GLenum> bufs;
    for (size_t i = 0; i < colours.size(); ++i) {
        glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), colours[i], 0);
        bufs.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    }
    glNamedFramebufferDrawBuffers(f, static_cast<GLsizei>(bufs.size()), bufs.data());
    if (depth) glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, depth, 0);
    if (glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw std::runtime_error("incomplete framebuffer");
    return f;
}

std::string read_shader(const std::string& file, const std::vector<raykit::ShaderDefine>& defines = {})
{
    return rkgl::shader_file(std::string(SAMPLES_DIR) + "/effects/" + file, {std::string(SAMPLES_DIR) + "/effects", RAYKIT_SHADER_DIR}, defines);
}

struct FrameUbo {
    mat4 view_proj, view, inv_view;
    vec4 view_ray, depth_k, proj, viewport, sun_view, sun_color, sky, light_uv, eye;
};

struct Puff {
    vec4 centre_radius;
    vec4 colour_opacity;
};

/// How a group of puffs is drawn (FX_PUFF_MODE, FX_PUFF_PRIM, FX_PUFF_OPACITY, FX_SLICES).
struct PuffStyle {
    int mode = 0, prim = 3, opacity = 1, slices = 1;
    bool operator<(const PuffStyle& o) const
    {
        return std::tie(mode, prim, opacity, slices) < std::tie(o.mode, o.prim, o.opacity, o.slices);
    }
};

struct Scene {
    vec3 eye, target;
    vec3 sun;  // towards the sun (world)
    vec3 sun_color, sky;
    bool ssao = true, shafts = false, relief = true;
    float exposure = 1.0f;
};

class Renderer {
public:
    Renderer(int w, int h) : w_(w), h_(h)
    {
        geom_ = rkgl::build_program({{GL_VERTEX_SHADER, read_shader("fx_geom.vert")}, {GL_FRAGMENT_SHADER, read_shader("fx_geom.frag")}});
        const std::string fs = read_shader("fx_fullscreen.vert");
        for (int p = 0; p < 3; ++p)
            ssao_[p] = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("fx_ssao.frag", {{"FX_SSAO_PASS", std::to_string(p)}})}});
        light_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("fx_light.frag")}});
        occ_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("fx_occlusion.frag")}});
        shafts_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("fx_shafts.frag")}});
        post_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_shader("fx_post.frag")}});

        const std::vector<Vertex> verts = build_scene();
        count_ = static_cast<GLsizei>(verts.size());
        glCreateBuffers(1, &vbo_);
        glNamedBufferStorage(vbo_, static_cast<GLsizeiptr>(verts.size() * sizeof(Vertex)), verts.data(), 0);
        glCreateVertexArrays(1, &vao_);
        glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(Vertex));
        for (GLuint a = 0; a < 4; ++a) {
            glEnableVertexArrayAttrib(vao_, a);
            glVertexArrayAttribFormat(vao_, a, a < 3 ? 3 : 1, GL_FLOAT, GL_FALSE, a * 3u * static_cast<GLuint>(sizeof(float)));
            glVertexArrayAttribBinding(vao_, a, 0);
        }
        glCreateVertexArrays(1, &empty_);
        smoke_ = smoke_texture(128);
        bricks_ = relief_texture(true, 128);
        paving_ = relief_texture(false, 128);

        depth_ = texture2d(GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
        albedo_ = texture2d(GL_RGBA8, w, h, GL_NEAREST);
        normal_ = texture2d(GL_RGBA16F, w, h, GL_NEAREST);
        geo_normal_ = texture2d(GL_RGBA16F, w, h, GL_NEAREST);
        ao_raw_ = texture2d(GL_R16F, w, h, GL_NEAREST);
        ao_tmp_ = texture2d(GL_R16F, w, h, GL_NEAREST);
        ao_ = texture2d(GL_R16F, w, h, GL_NEAREST);
        occ_tex_ = texture2d(GL_RGBA16F, w / 2, h / 2, GL_LINEAR);
        shafts_tex_ = texture2d(GL_RGBA16F, w / 2, h / 2, GL_LINEAR);
        hdr_ = texture2d(GL_RGBA16F, w, h, GL_NEAREST);
        ldr8_ = texture2d(GL_RGBA8, w, h, GL_NEAREST);
        out_ = texture2d(GL_RGBA8, w, h, GL_NEAREST);
        gfbo_ = framebuffer({albedo_, normal_, geo_normal_}, depth_);
        ao_raw_fbo_ = framebuffer({ao_raw_}, 0);
        ao_tmp_fbo_ = framebuffer({ao_tmp_}, 0);
        ao_fbo_ = framebuffer({ao_}, 0);
        occ_fbo_ = framebuffer({occ_tex_}, 0);
        shafts_fbo_ = framebuffer({shafts_tex_}, 0);
        hdr_fbo_ = framebuffer({hdr_}, depth_);
        ldr8_fbo_ = framebuffer({ldr8_}, depth_);
        out_fbo_ = framebuffer({out_}, 0);

        glCreateBuffers(1, &ubo_);
        glNamedBufferStorage(ubo_, sizeof(FrameUbo), nullptr, GL_DYNAMIC_STORAGE_BIT);
        // SSAO kernel (16 samples of ao_kernel_hemisphere) and 4 x 4 rotation tile, std140 vec4s.
        std::vector<vec4> kern(static_cast<size_t>(RK_AO_MAX_SAMPLES) + 16u, vec4(0.0f));
        const std::vector<raykit::vec3> k = raykit::ao_kernel_hemisphere(16, 7u);
        for (size_t i = 0; i < k.size(); ++i) kern[i] = vec4(k[i], 0.0f);
        const std::vector<raykit::vec2> noise = raykit::ao_rotation_noise(4, 3u);
        for (size_t i = 0; i < 16; ++i) kern[static_cast<size_t>(RK_AO_MAX_SAMPLES) + i] = vec4(noise[i], 0.0f, 0.0f);
        glCreateBuffers(1, &kernel_ubo_);
        glNamedBufferStorage(kernel_ubo_, static_cast<GLsizeiptr>(kern.size() * sizeof(vec4)), kern.data(), 0);
        glCreateBuffers(1, &puffs_);
        glNamedBufferStorage(puffs_, 256 * sizeof(Puff), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    }
    ~Renderer()
    {
        for (GLuint p : {geom_, ssao_[0], ssao_[1], ssao_[2], light_, occ_, shafts_, post_}) glDeleteProgram(p);
        for (auto& kv : puff_progs_) glDeleteProgram(kv.second);
        GLuint bufs[4] = {vbo_, ubo_, kernel_ubo_, puffs_};
        glDeleteBuffers(4, bufs);
        GLuint vaos[2] = {vao_, empty_};
        glDeleteVertexArrays(2, vaos);
        GLuint texs[15] = {smoke_, depth_, albedo_, normal_, geo_normal_, ao_raw_, ao_tmp_, ao_, occ_tex_, shafts_tex_, hdr_, ldr8_, out_, bricks_, paving_};
        glDeleteTextures(15, texs);
        GLuint fbos[9] = {gfbo_, ao_raw_fbo_, ao_tmp_fbo_, ao_fbo_, occ_fbo_, shafts_fbo_, hdr_fbo_, ldr8_fbo_, out_fbo_};
        glDeleteFramebuffers(9, fbos);
    }
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void set_view(const Scene& s)
    {
        const float aspect = static_cast<float>(w_) / static_cast<float>(h_);
        const mat4 view = glm::lookAt(s.eye, s.target, vec3(0, 1, 0));
        mat4 p = glm::perspectiveRH_ZO(glm::radians(60.0f), aspect, kNear, kFar), flip(1.0f);
        flip[2][2] = -1.0f;
        flip[3][2] = 1.0f;
        p = flip * p;  // reversed-Z
        FrameUbo f{};
        f.view_proj = p * view;
        f.view = view;
        f.inv_view = glm::inverse(view);
        f.view_ray = raykit::gbuffer_view_ray(p);
        f.depth_k = vec4(raykit::gbuffer_depth_params(kNear, kFar, true), kNear);
        f.proj = vec4(p[0][0], p[1][1], p[2][0], p[2][1]);
        f.viewport = vec4(static_cast<float>(w_), static_cast<float>(h_), 1.0f / static_cast<float>(w_), 1.0f / static_cast<float>(h_));
        const vec3 sun = glm::normalize(s.sun);
        f.sun_view = vec4(glm::normalize(vec3(view * vec4(sun, 0.0f))), sun.y > 0.0f ? 1.0f : 0.0f);
        f.sun_color = vec4(s.sun_color, 0.0f);
        f.sky = vec4(s.sky, s.ssao ? 1.0f : 0.0f);
        const vec4 clip = f.view_proj * vec4(sun, 0.0f);
        const raykit::vec2 luv = raykit::rk_ls_light_uv(clip);
        f.light_uv = vec4(luv.x, luv.y, raykit::rk_ls_fade(clip, 0.3f), s.shafts ? 1.0f : 0.0f);
        f.eye = vec4(s.eye, 1.0f);
        frame_ = f;
        glNamedBufferSubData(ubo_, 0, sizeof(FrameUbo), &frame_);
    }

    /// The scene without the puffs into the HDR target (target8: the 8-bit one, for the bench).
    void render_scene(const Scene& s, bool target8 = false)
    {
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_);
        glBindBufferBase(GL_UNIFORM_BUFFER, 1, kernel_ubo_);
        glViewport(0, 0, w_, h_);
        glBindFramebuffer(GL_FRAMEBUFFER, gfbo_);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(gfbo_, GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(gfbo_, GL_COLOR, 1, zero);
        glClearNamedFramebufferfv(gfbo_, GL_COLOR, 2, zero);
        glClearDepth(0.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glUseProgram(geom_);
        glUniform1i(0, s.relief ? 1 : 0);
        glBindTextureUnit(6, bricks_);
        glBindTextureUnit(7, paving_);
        glBindVertexArray(vao_);
        glDrawArrays(GL_TRIANGLES, 0, count_);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glBindVertexArray(empty_);
        glBindTextureUnit(0, depth_);
        glBindTextureUnit(1, geo_normal_);
        if (s.ssao) {
            glBindFramebuffer(GL_FRAMEBUFFER, ao_raw_fbo_);
            glUseProgram(ssao_[0]);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindFramebuffer(GL_FRAMEBUFFER, ao_tmp_fbo_);
            glBindTextureUnit(2, ao_raw_);
            glUseProgram(ssao_[1]);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindFramebuffer(GL_FRAMEBUFFER, ao_fbo_);
            glBindTextureUnit(2, ao_tmp_);
            glUseProgram(ssao_[2]);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        if (s.shafts) {
            glViewport(0, 0, w_ / 2, h_ / 2);
            glBindFramebuffer(GL_FRAMEBUFFER, occ_fbo_);
            glUseProgram(occ_);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindFramebuffer(GL_FRAMEBUFFER, shafts_fbo_);
            glBindTextureUnit(0, occ_tex_);
            glUseProgram(shafts_);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glViewport(0, 0, w_, h_);
        } else {
            const float none[4] = {0, 0, 0, 0};
            glClearTexImage(shafts_tex_, 0, GL_RGBA, GL_FLOAT, none);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, target8 ? ldr8_fbo_ : hdr_fbo_);
        glBindTextureUnit(0, depth_);
        glBindTextureUnit(1, normal_);
        glBindTextureUnit(2, ao_);
        glBindTextureUnit(3, albedo_);
        glBindTextureUnit(4, shafts_tex_);
        glUseProgram(light_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    /// Draws puffs [first, first + count) of the uploaded list in one style, blended over the
    /// current target (premultiplied alpha).
    void draw_puffs(const PuffStyle& st, int first, int count, bool target8 = false)
    {
        GLuint& prog = puff_progs_[st];
        if (!prog) {
            const std::vector<raykit::ShaderDefine> d = {{"FX_PUFF_MODE", std::to_string(st.mode)},
                                                         {"FX_PUFF_PRIM", std::to_string(st.prim)},
                                                         {"FX_PUFF_OPACITY", std::to_string(st.opacity)},
                                                         {"FX_SLICES", std::to_string(st.mode == 1 ? st.slices : 1)}};
            prog = rkgl::build_program({{GL_VERTEX_SHADER, read_shader("fx_puff.vert", d)}, {GL_FRAGMENT_SHADER, read_shader("fx_puff.frag", d)}});
        }
        glBindFramebuffer(GL_FRAMEBUFFER, target8 ? ldr8_fbo_ : hdr_fbo_);
        glViewport(0, 0, w_, h_);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, puffs_, static_cast<GLintptr>(first) * static_cast<GLintptr>(sizeof(Puff)),
                          static_cast<GLsizeiptr>(std::max(count, 1)) * static_cast<GLsizeiptr>(sizeof(Puff)));
        glBindTextureUnit(5, smoke_);
        glBindTextureUnit(0, depth_);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);
        if (st.mode == 2) {
            glDisable(GL_DEPTH_TEST);  // the thesis's z-buffer off: the shader compares with the depth
        } else {
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_GREATER);
        }
        glUseProgram(prog);
        glBindVertexArray(empty_);
        glDrawArraysInstanced(GL_TRIANGLES, 0, 6, count * (st.mode == 1 ? st.slices : 1));
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
    }

    /// Uploads puffs sorted back to front for the current eye.
    void upload_puffs(std::vector<Puff> p)
    {
        const vec3 eye(frame_.eye);
        std::stable_sort(p.begin(), p.end(), [&](const Puff& a, const Puff& b) {
            return glm::length(vec3(a.centre_radius) - eye) > glm::length(vec3(b.centre_radius) - eye);
        });
        glNamedBufferSubData(puffs_, 0, static_cast<GLsizeiptr>(std::min<size_t>(p.size(), 256) * sizeof(Puff)), p.data());
    }

    std::vector<uint8_t> finish(float exposure, bool show_ao)
    {
        glBindFramebuffer(GL_FRAMEBUFFER, out_fbo_);
        glViewport(0, 0, w_, h_);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(post_);
        glBindTextureUnit(0, hdr_);
        glBindTextureUnit(1, ao_);
        glUniform1f(0, exposure);
        glUniform1i(1, show_ao ? 1 : 0);
        glBindVertexArray(empty_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        std::vector<uint8_t> px(static_cast<size_t>(w_) * static_cast<size_t>(h_) * 4u), flipped(px.size());
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTextureImage(out_, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(px.size()), px.data());
        const size_t row = static_cast<size_t>(w_) * 4u;
        for (int y = 0; y < h_; ++y) std::memcpy(&flipped[static_cast<size_t>(y) * row], &px[static_cast<size_t>(h_ - 1 - y) * row], row);
        return flipped;
    }

    std::vector<float> read_r(GLuint tex) const
    {
        std::vector<float> v(static_cast<size_t>(w_) * static_cast<size_t>(h_));
        glGetTextureImage(tex, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(v.size() * sizeof(float)), v.data());
        return v;
    }
    std::vector<float> read_hdr() const
    {
        std::vector<float> v(static_cast<size_t>(w_) * static_cast<size_t>(h_) * 4u);
        glGetTextureImage(hdr_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(v.size() * sizeof(float)), v.data());
        return v;
    }
    GLuint ao_texture() const { return ao_; }
    GLuint shafts_texture() const { return shafts_tex_; }

private:
    int w_, h_;
    GLuint geom_ = 0, ssao_[3] = {}, light_ = 0, occ_ = 0, shafts_ = 0, post_ = 0;
    std::map<PuffStyle, GLuint> puff_progs_;
    GLuint vbo_ = 0, vao_ = 0, empty_ = 0, smoke_ = 0, bricks_ = 0, paving_ = 0, ubo_ = 0, kernel_ubo_ = 0, puffs_ = 0;
    GLsizei count_ = 0;
    GLuint depth_ = 0, albedo_ = 0, normal_ = 0, geo_normal_ = 0, ao_raw_ = 0, ao_tmp_ = 0, ao_ = 0, occ_tex_ = 0, shafts_tex_ = 0, hdr_ = 0, ldr8_ = 0,
           out_ = 0;
    GLuint gfbo_ = 0, ao_raw_fbo_ = 0, ao_tmp_fbo_ = 0, ao_fbo_ = 0, occ_fbo_ = 0, shafts_fbo_ = 0, hdr_fbo_ = 0, ldr8_fbo_ = 0, out_fbo_ = 0;
    FrameUbo frame_{};
};

Scene day_scene()
{
    Scene s;
    s.eye = vec3(0.0f, 1.9f, 8.5f);
    s.target = vec3(0.0f, 1.1f, -6.0f);
    s.sun = vec3(0.8f, 0.55f, 0.35f);
    s.sun_color = vec3(3.0f, 2.85f, 2.6f);
    s.sky = vec3(0.30f, 0.36f, 0.46f);
    s.exposure = 0.9f;
    return s;
}

Scene sunset_scene()
{
    Scene s;
    s.eye = vec3(1.5f, 4.5f, 14.0f);
    s.target = vec3(0.0f, 7.0f, -40.0f);
    s.sun = vec3(0.03f, 0.2f, -1.0f);
    s.sun_color = vec3(3.2f, 1.7f, 0.75f);
    s.sky = vec3(0.22f, 0.16f, 0.15f);
    s.shafts = true;
    s.exposure = 1.1f;
    return s;
}

/// Three columns of puffs crossing the ground (and one the wall): x = -5 billboards, 0 slices,
/// 5 raytraced.
std::vector<Puff> column_puffs(float x)
{
    const vec4 colour(0.9f, 0.9f, 0.92f, 0.85f);
    return {{vec4(x, 0.3f, -1.0f, 1.5f), colour}, {vec4(x + 0.4f, 1.8f, -2.2f, 1.3f), colour}, {vec4(x - 0.3f, 1.4f, -7.0f, 1.6f), colour}};
}

struct Options {
    bool quick = false, bench = false;
    int width = 1280, height = 720, reps = 5;
    std::string out_dir = ".", bench_out;
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

double seconds_since(std::chrono::steady_clock::time_point t0) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }

int bench(Renderer& r, const Options& opt)
{
    // The thesis's protocol (§6.4.2, figure 6.23): one particle system, each technique, frames per
    // time; here the median frame time of interleaved repetitions, as a ratio to the billboard frame.
    Scene s = day_scene();
    s.ssao = false;
    s.relief = false;
    r.set_view(s);
    std::vector<Puff> p;
    for (int i = 0; i < 24; ++i) {
        const float a = 0.7f * static_cast<float>(i);
        p.push_back({vec4(3.0f * std::cos(a), 0.6f + 0.12f * static_cast<float>(i), -2.0f + 2.5f * std::sin(a), 2.2f), vec4(0.9f, 0.9f, 0.92f, 0.7f)});
    }
    r.upload_puffs(p);
    struct Row {
        const char* name;
        PuffStyle st;
        bool target8;
        double thesis;  // frames in 5 s (figure 6.23)
    };
    const Row rows[] = {
        {"billboard", {0, 0, 0, 1}, true, 3573},
        {"5 slices", {1, 0, 0, 5}, true, 2324},
        {"9 slices", {1, 0, 0, 9}, true, 1691},
        {"19 slices", {1, 0, 0, 19}, true, 1066},
        {"39 slices", {1, 0, 0, 39}, true, 620},
        {"79 slices", {1, 0, 0, 79}, true, 338},
        {"5 slices, float colour buffer", {1, 0, 0, 5}, false, 754},
        {"9 slices, float colour buffer", {1, 0, 0, 9}, false, 575},
        {"19 slices, float colour buffer", {1, 0, 0, 19}, false, 381},
        {"39 slices, float colour buffer", {1, 0, 0, 39}, false, 229},
        {"79 slices, float colour buffer", {1, 0, 0, 79}, false, 129},
        {"raytraced, constant thickness, log", {2, 0, 1, 1}, true, 1141},
        {"raytraced, linearly decreasing, log", {2, 1, 1, 1}, true, 1088},
        {"raytraced sphere, log", {2, 3, 1, 1}, true, 988},
        {"raytraced sphere, linear", {2, 3, 0, 1}, true, 1012},
        {"raytraced sphere, square root", {2, 3, 2, 1}, true, 906},
        {"raytraced, thickness from alpha, log", {2, 2, 1, 1}, true, 1138},
    };
    auto frame = [&](const Row& row) {
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        r.render_scene(s, row.target8);
        r.draw_puffs(row.st, 0, static_cast<int>(p.size()), row.target8);
        glFinish();
        return seconds_since(t0);
    };
    std::string md;
    char line[512];
    std::snprintf(line, sizeof line,
                  "Summary (24 overlapping puffs of radius 2.2 over the ground at %dx%d, %d interleaved repetitions; cost = median frame "
                  "time / the billboard's, spread = max/min of the per-repetition ratio; the thesis's cost = 3573 / its frames):\n\n",
                  opt.width, opt.height, opt.reps);
    md += line;
    md += "| technique | frame (ms) | cost vs billboard | spread | thesis (frames in 5 s) | thesis cost |\n| --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const Row& row : rows) {
        frame(row);  // warm-up (and shader compilation)
        frame(rows[0]);
        std::vector<double> t, ratio;
        for (int k = 0; k < opt.reps; ++k) {
            const double b = frame(rows[0]), v = frame(row);
            t.push_back(v);
            ratio.push_back(v / b);
        }
        std::sort(t.begin(), t.end());
        std::vector<double> rs = ratio;
        std::sort(rs.begin(), rs.end());
        std::snprintf(line, sizeof line, "| %s | %.1f | %.2f | %.2f | %.0f | %.2f |\n", row.name, 1e3 * t[t.size() / 2], rs[rs.size() / 2],
                      rs.back() / rs.front(), row.thesis, 3573.0 / row.thesis);
        md += line;
    }
    std::printf("%s", md.c_str());
    if (!opt.bench_out.empty()) {
        FILE* f = std::fopen(opt.bench_out.c_str(), "w");
        if (!f) return 1;
        std::fprintf(f, "%s", md.c_str());
        std::fclose(f);
    }
    return 0;
}

int run(const Options& opt)
{
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) return rkgl::no_context_exit("effects", ctx.error());
    std::printf("effects: %s\n", ctx.renderer().c_str());
    Renderer r(opt.width, opt.height);
    if (opt.bench) {
        std::printf("**Renderer**: %s\n\n", ctx.renderer().c_str());
        return bench(r, opt);
    }
    int failures = 0;
    auto write = [&](const std::string& name, const std::vector<uint8_t>& px) {
        const std::string path = opt.out_dir + "/" + name;
        if (!rkgl::write_png_rgba8(path, opt.width, opt.height, px.data())) {
            std::fprintf(stderr, "cannot write %s\n", path.c_str());
            ++failures;
        } else {
            std::printf("wrote %s\n", path.c_str());
        }
    };
    auto finite_mean = [&](const std::vector<float>& v, int stride, double& mean) {
        mean = 0.0;
        for (size_t i = 0; i < v.size(); i += static_cast<size_t>(stride)) {
            if (!std::isfinite(v[i])) return false;
            mean += v[i];
        }
        mean /= static_cast<double>(v.size() / static_cast<size_t>(stride));
        return true;
    };

    // Smoke: billboards | slices | raytraced, crossing the ground and the wall.
    const Scene day = day_scene();
    r.set_view(day);
    std::vector<Puff> all;
    for (float x : {-5.0f, 0.0f, 5.0f})
        for (const Puff& p : column_puffs(x)) all.push_back(p);
    r.render_scene(day);
    const int per = 3;
    const PuffStyle styles[3] = {{0, 0, 0, 1}, {1, 0, 0, 9}, {2, 3, 1, 1}};
    for (int c = 0; c < 3; ++c) {
        r.upload_puffs(std::vector<Puff>(all.begin() + c * per, all.begin() + (c + 1) * per));
        r.draw_puffs(styles[c], 0, per);
    }
    double mean = 0.0;
    if (!finite_mean(r.read_hdr(), 1, mean) || mean < 0.05) {
        std::fprintf(stderr, "FAIL volumes: non-finite or black image (mean %.3f)\n", mean);
        ++failures;
    }
    write("effects_volumes.png", r.finish(day.exposure, false));

    // SSAO: the AO buffer of the day view (open floor reads 0; contact under the crates and along
    // the wall's foot reads more).
    const std::vector<float> ao = r.read_r(r.ao_texture());
    double ao_mean = 0.0;
    if (!finite_mean(ao, 1, ao_mean) || ao_mean <= 0.0 || ao_mean > 0.02) {
        std::fprintf(stderr, "FAIL ssao: mean AO %.4f outside (0, 0.02] (mostly open floor and wall)\n", ao_mean);
        ++failures;
    }
    write("effects_ssao.png", r.finish(day.exposure, true));
    std::printf("ssao: mean AO %.4f\n", ao_mean);

    // Relief: the brick wall and the paving close up, at a grazing angle under a raking sun.
    Scene close = day_scene();
    close.eye = vec3(-7.5f, 1.3f, -4.6f);
    close.target = vec3(-2.0f, 1.0f, -7.4f);
    close.sun = vec3(0.9f, 0.35f, 0.25f);
    r.set_view(close);
    r.render_scene(close);
    write("effects_relief.png", r.finish(close.exposure, false));

    // Sunset: light shafts through the colonnade (and the same without them, to check they add).
    Scene sunset = sunset_scene();
    r.set_view(sunset);
    r.render_scene(sunset);
    double with = 0.0, without = 0.0;
    finite_mean(r.read_hdr(), 4, with);
    write("effects_sunset.png", r.finish(sunset.exposure, false));
    sunset.shafts = false;
    r.set_view(sunset);
    r.render_scene(sunset);
    finite_mean(r.read_hdr(), 4, without);
    std::printf("sunset: mean red with shafts %.4f, without %.4f\n", with, without);
    if (!(with > without * 1.02)) {
        std::fprintf(stderr, "FAIL shafts: they add nothing\n");
        ++failures;
    }
    if (failures) std::fprintf(stderr, "effects: %d check(s) failed\n", failures);
    return failures ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv)
{
    Options opt;
    if (!parse(argc, argv, opt)) {
        std::fprintf(stderr, "usage: effects [--quick] [--size WxH] [--bench [--reps N] [--bench-out FILE]] [OUT_DIR]\n");
        return 2;
    }
    try {
        return run(opt);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "effects: %s\n", e.what());
        return 1;
    }
}
