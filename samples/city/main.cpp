// raykit sample — city: raykit's main demo. A procedural city of box buildings and round towers
// whose windows show interior-mapped rooms (lit and dark, furnished, with people), reflecting the
// sky and the city itself through a dual-paraboloid map baked at start-up, rendered in HDR,
// exposed from the GPU luminance reduction, bloomed and tone-mapped. Headless by default (EGL):
// named views are written as PNG files; --window opens a free-flying camera (GLFW) when built
// with GLFW and a display exists.
//
// Start-up, all procedural (no asset files): the city (city_gen.hpp: blocks, streets, a
// boulevard, >= 100 buildings with room grids from raykit::room_grid_for_building), the textures
// (city_textures.hpp: facades whose alpha is the window mask, one tile per window bay; room
// surfaces for RK_IM_SHADING 1; two furniture sprite sheets), then per lighting preset the sun's
// shadow map and the reflection map: the city rendered into six cube faces from a point above the
// boulevard with the same shaders (reflections off), read back and resampled on the CPU into a
// dual-paraboloid atlas with mips by raykit::bake_dual_paraboloid (raykit/paraboloid.hpp).
//
// Per view: sky, ground and buildings into RGBA32F (+ a check buffer), exposure from
// rkgl::LuminanceReducer (samples/common/rk_luminance_gl.hpp), the exposed image through
// rkgl::BloomGl (rk_bloom_gl.hpp), tone mapping with tonemap.glsl's default operator, PNG.
//
// Every view is checked (exit 1 on failure): no NaN/Inf in the HDR image; windows show rooms
// (enough distinct rooms, luminance varies inside the windows); the fraction of lit rooms among
// the distinct rooms seen agrees with the buildings' lit probabilities c (binomial bound, 4
// sigma); the GPU's lit decision equals raykit::rk_im_room_lit on the CPU for every room seen;
// the corner view sees at least one room through two facades.
//
// Usage: city [--quick] [--window] [--views a,b,...] [--size WxH] [--no-bloom] [OUT_DIR]
//   OUT_DIR defaults to "." (PNG files city_<view>.png). --quick: 320x180, smaller maps (the
//   ctest). Views: boulevard, corner, tower, overview (day), dusk (default: all, in that order).
// Exit codes: 0 ok; 1 error or failed check; 77 no OpenGL 4.5 context (1 instead when CI=true).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "city_gen.hpp"
#include "city_textures.hpp"
#include "raykit/color.hpp"
#include "raykit/interior_features.hpp"
#include "raykit/interior_mapping.hpp"
#include "raykit/paraboloid.hpp"
#include "raykit/shader_source.hpp"
#include "rk_bloom_gl.hpp"
#include "rk_gl.hpp"
#include "rk_luminance_gl.hpp"

#ifdef CITY_HAVE_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

#include "rk_png.hpp"

namespace {

using glm::mat4;
using glm::vec3;
using glm::vec4;

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---------------------------------------------------------------------------------------------
// Lighting presets and views

struct Lighting {
    const char* name;
    vec3 sun_dir;        // towards the sun
    float sun_scale;
    vec3 sun_color;
    float interior;      // room light intensity
    vec3 zenith;
    float dusk;
    vec3 horizon;
    float street_light;
    float lit_scale;     // multiplies every building's lit probability c
    float unlit;         // daylight multiplier of unlit rooms
};

Lighting day_lighting()
{
    Lighting l{};
    l.name = "day";
    l.sun_dir = glm::normalize(vec3(-0.55f, 0.52f, -0.45f));
    l.sun_scale = 3.2f;
    l.sun_color = vec3(1.0f, 0.93f, 0.82f);
    l.interior = 0.9f;
    l.zenith = vec3(0.16f, 0.32f, 0.75f);
    l.dusk = 0.0f;
    l.horizon = vec3(0.62f, 0.72f, 0.86f);
    l.street_light = 0.0f;
    l.lit_scale = 1.0f;
    l.unlit = 0.12f;
    return l;
}

Lighting dusk_lighting()
{
    Lighting l{};
    l.name = "dusk";
    l.sun_dir = glm::normalize(vec3(0.85f, 0.02f, -0.3f));
    l.sun_scale = 0.35f;
    l.sun_color = vec3(1.0f, 0.42f, 0.15f);
    l.interior = 1.7f;
    l.zenith = vec3(0.010f, 0.018f, 0.06f);
    l.dusk = 1.0f;
    l.horizon = vec3(0.22f, 0.11f, 0.07f);
    l.street_light = 0.35f;
    l.lit_scale = 1.7f;
    l.unlit = 0.03f;
    return l;
}

struct View {
    std::string name;
    const char* what;
    int lighting;  // 0 day, 1 dusk
    vec3 eye, target;
    float fov_deg;
    float ev;      // exposure compensation (stops)
};

/// The named views, placed from the generated city (the corner and tower views pick buildings).
std::vector<View> make_views(const city::City& c)
{
    const city::CityLayout& L = c.layout;
    std::vector<View> v;
    const float west = -0.5f * static_cast<float>(L.blocks_x) * L.pitch();
    v.push_back(View{"boulevard", "street level looking up the boulevard, afternoon sun", 0,
                     vec3(west + 30.0f, 3.5f, -9.0f), vec3(20.0f, 62.0f, 2.0f), 66.0f, 0.6f});
    // Corner: the tallest box on the boulevard's north side near the centre, seen diagonally from
    // across the corner so that its corner room shows through both facades.
    const city::Building* corner = nullptr;
    for (const city::Building& b : c.buildings) {
        if (b.kind != 0 || b.cz - b.hz < 0.0f || b.cz - b.hz > 30.0f || std::abs(b.cx) > 120.0f) continue;
        if (!corner || b.height > corner->height) corner = &b;
    }
    if (!corner) corner = &c.buildings.front();
    {
        const vec3 k(corner->cx - corner->hx, 0.0f, corner->cz - corner->hz);  // south-west corner
        const float y = std::min(corner->height * 0.5f, 3.5f * corner->grid.room_size.y);
        v.push_back(View{"corner", "a corner building up close: the corner rooms seen through two facades", 0,
                         k + vec3(-9.0f, y - 2.0f, -11.0f), k + vec3(0.5f, y + 1.0f, 0.5f), 58.0f, 0.5f});
    }
    // Tower: the round tower nearest the centre.
    const city::Building* tower = nullptr;
    for (const city::Building& b : c.buildings) {
        if (b.kind != 1) continue;
        if (!tower || b.cx * b.cx + b.cz * b.cz < tower->cx * tower->cx + tower->cz * tower->cz) tower = &b;
    }
    if (tower) {
        const vec3 cen(tower->cx, 0.0f, tower->cz);
        const vec3 out = glm::normalize(vec3(-0.3f, 0.0f, tower->cz > 0.0f ? -1.0f : 1.0f));
        const float r = tower->hx;
        v.push_back(View{"tower", "a round tower: interior mapping on a curved facade, reflections at grazing angles", 0,
                         cen + out * (r + 16.0f) + vec3(0.0f, 14.0f, 0.0f), cen + vec3(0.0f, 26.0f, 0.0f), 64.0f, 0.6f});
    }
    v.push_back(View{"overview", "the whole city from above, afternoon", 0, vec3(-230.0f, 140.0f, -270.0f),
                     vec3(20.0f, 0.0f, 20.0f), 52.0f, 0.5f});
    v.push_back(View{"dusk", "dusk over the boulevard: many lit rooms", 1, vec3(west + 10.0f, 24.0f, 8.0f),
                     vec3(40.0f, 20.0f, -6.0f), 60.0f, -1.6f});
    return v;
}

// ---------------------------------------------------------------------------------------------
// GL helpers

struct FrameUbo {
    mat4 view_proj, inv_view_proj, shadow_mat;
    vec4 cam, sun_dir, sun_color, sky_zenith, sky_horizon, env_center, env_params, layout0, layout1;
};

std::string read_city_shader(const std::string& file, const std::vector<raykit::ShaderDefine>& defines)
{
    return rkgl::shader_file(std::string(SAMPLES_DIR) + "/city/" + file, {std::string(SAMPLES_DIR) + "/city", RAYKIT_SHADER_DIR},
                                    defines);
}

GLuint texture_array(const std::vector<std::uint8_t>& rgba, int size, int layers, bool srgb, GLint wrap)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
    const int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(size))));
    glTextureStorage3D(t, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, size, size, layers);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(t, 0, 0, 0, 0, size, size, layers, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glGenerateTextureMipmap(t);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, wrap);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, wrap);
    return t;
}

/// A render target: RGBA32F colour, RGBA32F check buffer, 24-bit depth.
struct SceneTarget {
    int w = 0, h = 0;
    GLuint fbo = 0, color = 0, aux = 0, depth = 0;
    SceneTarget(int width, int height) : w(width), h(height)
    {
        glCreateTextures(GL_TEXTURE_2D, 1, &color);
        glTextureStorage2D(color, 1, GL_RGBA32F, w, h);
        glCreateTextures(GL_TEXTURE_2D, 1, &aux);
        glTextureStorage2D(aux, 1, GL_RGBA32F, w, h);
        glCreateTextures(GL_TEXTURE_2D, 1, &depth);
        glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT24, w, h);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, aux, 0);
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
        const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(fbo, 2, bufs);
        if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("incomplete scene framebuffer");
        }
    }
    ~SceneTarget()
    {
        glDeleteFramebuffers(1, &fbo);
        GLuint t[3] = {color, aux, depth};
        glDeleteTextures(3, t);
    }
    SceneTarget(const SceneTarget&) = delete;
    SceneTarget& operator=(const SceneTarget&) = delete;

    std::vector<float> read(GLuint tex) const
    {
        std::vector<float> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4u);
        glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(px.size() * sizeof(float)), px.data());
        return px;
    }
};

/// A colour-only target (post passes).
struct ColorTarget {
    int w = 0, h = 0;
    GLuint fbo = 0, tex = 0;
    ColorTarget(int width, int height, GLenum format) : w(width), h(height)
    {
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, format, w, h);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("incomplete post framebuffer");
        }
    }
    ~ColorTarget()
    {
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
    }
    ColorTarget(const ColorTarget&) = delete;
    ColorTarget& operator=(const ColorTarget&) = delete;
};

// ---------------------------------------------------------------------------------------------
// The renderer

struct Settings {
    int width = 1280, height = 720;
    int shadow_size = 2048;
    int cube_size = 256;
    int env_half = 256;      // dual-paraboloid half size
    float env_max_lod = 3.0f;
    int tex_size = 128;      // texture tiles
    bool bloom = true;
};

class CityRenderer {
public:
    CityRenderer(const city::City& c, const Settings& s) : city_(c), s_(s)
    {
        raykit::InteriorSceneDesc desc;
        desc.textures = raykit::InteriorTextures::texture_array;
        desc.room_lights = true;
        desc.furniture_layers = city::kFurnitureLayers;
        desc.fade_distance = 250.0f;
        std::vector<raykit::ShaderDefine> defs = raykit::interior_defines(desc);
        defs.push_back({"CITY_ROOM_VARIANTS", std::to_string(city::kInteriorVariants)});
        defs.push_back({"CITY_SHEET_CELLS", std::to_string(city::kSheetCells)});
        std::vector<raykit::ShaderDefine> aux_defs = defs;
        defs.push_back({"CITY_AUX", "0"});
        aux_defs.push_back({"CITY_AUX", "1"});
        const std::string vs = read_city_shader("city_building.vert", {});
        building_ = rkgl::build_program({{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, read_city_shader("city_building.frag", defs)}});
        building_aux_ =
            rkgl::build_program({{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, read_city_shader("city_building.frag", aux_defs)}});
        ground_ = rkgl::build_program({{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, read_city_shader("city_ground.frag", {})}});
        shadow_ = rkgl::build_program({{GL_VERTEX_SHADER, read_city_shader("city_building.vert", {{"CITY_SHADOW_PASS", "1"}})},
                                       {GL_FRAGMENT_SHADER, read_city_shader("city_shadow.frag", {})}});
        const std::string fs = read_city_shader("city_fullscreen.vert", {});
        sky_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_city_shader("city_sky.frag", {})}});
        expose_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_city_shader("city_post.frag", {{"CITY_POST_MODE", "0"}})}});
        tonemap_ = rkgl::build_program({{GL_VERTEX_SHADER, fs}, {GL_FRAGMENT_SHADER, read_city_shader("city_post.frag", {{"CITY_POST_MODE", "1"}})}});

        // Geometry: buildings, then the ground quad (id -1).
        std::vector<city::Vertex> verts = c.vertices;
        building_count_ = static_cast<GLsizei>(verts.size());
        const float g = 20000.0f;
        const float quad[6][2] = {{-g, -g}, {g, g}, {g, -g}, {-g, -g}, {-g, g}, {g, g}};
        for (const auto& q : quad) verts.push_back(city::Vertex{{q[0], 0.0f, q[1]}, {0.0f, 1.0f, 0.0f}, -1.0f});
        glCreateBuffers(1, &vbo_);
        glNamedBufferStorage(vbo_, static_cast<GLsizeiptr>(verts.size() * sizeof(city::Vertex)), verts.data(), 0);
        glCreateVertexArrays(1, &vao_);
        glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(city::Vertex));
        for (GLuint a = 0; a < 3; ++a) glEnableVertexArrayAttrib(vao_, a);
        glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, offsetof(city::Vertex, pos));
        glVertexArrayAttribFormat(vao_, 1, 3, GL_FLOAT, GL_FALSE, offsetof(city::Vertex, normal));
        glVertexArrayAttribFormat(vao_, 2, 1, GL_FLOAT, GL_FALSE, offsetof(city::Vertex, id));
        for (GLuint a = 0; a < 3; ++a) glVertexArrayAttribBinding(vao_, a, 0);
        glCreateVertexArrays(1, &empty_vao_);

        glCreateBuffers(1, &ubo_);
        glNamedBufferStorage(ubo_, sizeof(FrameUbo), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateBuffers(1, &ssbo_);
        glNamedBufferStorage(ssbo_, static_cast<GLsizeiptr>(c.buildings.size() * sizeof(city::BuildingGpu)), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);

        const auto t0 = std::chrono::steady_clock::now();
        const int ts = s.tex_size;
        facades_ = texture_array(city::make_facades(ts), ts, city::kFacadeLayers, true, GL_REPEAT);
        rooms_ = texture_array(city::make_interiors(ts), ts, city::kInteriorLayers, true, GL_REPEAT);
        sprites_ = texture_array(city::make_furniture(ts), 4 * ts, city::kFurnitureLayers, true, GL_CLAMP_TO_EDGE);
        texture_seconds_ = seconds_since(t0);

        glCreateTextures(GL_TEXTURE_2D, 1, &shadow_tex_);
        glTextureStorage2D(shadow_tex_, 1, GL_DEPTH_COMPONENT24, s.shadow_size, s.shadow_size);
        glTextureParameteri(shadow_tex_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(shadow_tex_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(shadow_tex_, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(shadow_tex_, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        glTextureParameteri(shadow_tex_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(shadow_tex_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glCreateFramebuffers(1, &shadow_fbo_);
        glNamedFramebufferTexture(shadow_fbo_, GL_DEPTH_ATTACHMENT, shadow_tex_, 0);
        glNamedFramebufferDrawBuffer(shadow_fbo_, GL_NONE);

        // A 1x1 black placeholder for the environment until one is baked.
        glCreateTextures(GL_TEXTURE_2D, 1, &env_);
        glTextureStorage2D(env_, 1, GL_RGBA16F, 2, 1);
        env_center_ = vec3(0.0f, 22.0f, 0.0f);
    }

    ~CityRenderer()
    {
        for (GLuint p : {building_, building_aux_, ground_, shadow_, sky_, expose_, tonemap_}) glDeleteProgram(p);
        GLuint bufs[3] = {vbo_, ubo_, ssbo_};
        glDeleteBuffers(3, bufs);
        GLuint texs[5] = {facades_, rooms_, sprites_, shadow_tex_, env_};
        glDeleteTextures(5, texs);
        glDeleteFramebuffers(1, &shadow_fbo_);
        GLuint vaos[2] = {vao_, empty_vao_};
        glDeleteVertexArrays(2, vaos);
    }
    CityRenderer(const CityRenderer&) = delete;
    CityRenderer& operator=(const CityRenderer&) = delete;

    double texture_seconds() const { return texture_seconds_; }
    const std::vector<city::BuildingGpu>& table() const { return table_; }

    /// Sets the lighting preset: building table (lit probabilities), shadow map, reflection map.
    /// Returns the seconds spent on (cube render, CPU bake).
    std::pair<double, double> set_lighting(const Lighting& l, bool reflections)
    {
        light_ = l;
        table_ = city::building_table(city_, l.lit_scale);
        glNamedBufferSubData(ssbo_, 0, static_cast<GLsizeiptr>(table_.size() * sizeof(city::BuildingGpu)), table_.data());
        // Shadow map: orthographic from the sun over the whole city.
        const float ext = city_.extent + 20.0f;
        const mat4 sv = glm::lookAt(l.sun_dir * 600.0f, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
        const mat4 sp = glm::ortho(-ext * 1.05f, ext * 1.05f, -ext * 1.05f, ext * 1.05f, 1.0f, 1400.0f);
        const mat4 bias = glm::translate(mat4(1.0f), vec3(0.5f)) * glm::scale(mat4(1.0f), vec3(0.5f));
        shadow_mat_ = bias * sp * sv;
        upload_frame(mat4(1.0f), vec3(0.0f), 0.0f, false);
        glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
        glViewport(0, 0, s_.shadow_size, s_.shadow_size);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glUseProgram(shadow_);
        glBindVertexArray(vao_);
        glDrawArrays(GL_TRIANGLES, 0, building_count_);
        glBindVertexArray(0);
        if (!reflections) return {0.0, 0.0};
        return bake_environment();
    }

    /// Renders the scene from a camera into `t` (HDR + check buffer).
    void render(SceneTarget& t, const mat4& view_proj, vec3 eye, float time, bool reflections, bool aux)
    {
        upload_frame(view_proj, eye, time, reflections);
        glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
        glViewport(0, 0, t.w, t.h);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, zero);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        glBindTextureUnit(0, facades_);
        glBindTextureUnit(3, env_);
        glBindTextureUnit(5, rooms_);
        glBindTextureUnit(6, shadow_tex_);
        glBindTextureUnit(7, sprites_);
        glBindVertexArray(vao_);
        glUseProgram(aux ? building_aux_ : building_);
        glDrawArrays(GL_TRIANGLES, 0, building_count_);
        glUseProgram(ground_);
        glDrawArrays(GL_TRIANGLES, building_count_, 6);
        glBindVertexArray(empty_vao_);
        glUseProgram(sky_);
        glUniform2f(0, static_cast<float>(t.w), static_cast<float>(t.h));
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glUseProgram(0);
    }

    /// Post: HDR x exposure -> bloom -> tone map into `out` (RGBA8).
    void post(const SceneTarget& t, float exposure, rkgl::BloomGl* bloom, ColorTarget& exposed, ColorTarget& out)
    {
        glDisable(GL_DEPTH_TEST);
        glBindVertexArray(empty_vao_);
        glBindFramebuffer(GL_FRAMEBUFFER, exposed.fbo);
        glViewport(0, 0, exposed.w, exposed.h);
        glUseProgram(expose_);
        glUniform1f(0, exposure);
        glBindTextureUnit(0, t.color);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        GLuint src = exposed.tex;
        if (bloom) src = bloom->apply(exposed.tex, exposed.w, exposed.h).texture;
        glBindVertexArray(empty_vao_);
        glBindFramebuffer(GL_FRAMEBUFFER, out.fbo);
        glViewport(0, 0, out.w, out.h);
        glUseProgram(tonemap_);
        glBindTextureUnit(0, src);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glUseProgram(0);
        glBindVertexArray(0);
    }

private:
    void upload_frame(const mat4& view_proj, vec3 eye, float time, bool reflections)
    {
        const Lighting& l = light_;
        const city::CityLayout& L = city_.layout;
        FrameUbo f;
        f.view_proj = view_proj;
        f.inv_view_proj = glm::inverse(view_proj);
        f.shadow_mat = shadow_mat_;
        f.cam = vec4(eye, time);
        f.sun_dir = vec4(l.sun_dir, l.sun_scale);
        f.sun_color = vec4(l.sun_color, l.interior);
        f.sky_zenith = vec4(l.zenith, l.dusk);
        f.sky_horizon = vec4(l.horizon, l.street_light);
        f.env_center = vec4(env_center_, reflections ? 1.0f : 0.0f);
        f.env_params = vec4(env_guard_, s_.env_max_lod, 16.0f, l.unlit);
        f.layout0 = vec4(static_cast<float>(L.blocks_x), static_cast<float>(L.blocks_z), L.block, L.street);
        f.layout1 = vec4(L.boulevard, L.sidewalk, city_.extent, 0.0f);
        glNamedBufferSubData(ubo_, 0, sizeof f, &f);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, ssbo_);
    }

    // The city seen from env_center_ into the six faces of a cube (GL conventions: face texel
    // (i, j) looks along raykit::cube_face_direction), reflections off, read back, resampled on
    // the CPU into a dual-paraboloid atlas with mips, uploaded.
    std::pair<double, double> bake_environment()
    {
        const auto t0 = std::chrono::steady_clock::now();
        const int n = s_.cube_size;
        raykit::EnvCubeMap cube;
        cube.size = n;
        SceneTarget face_target(n, n);
        const mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, 0.5f, 3000.0f);
        for (int face = 0; face < 6; ++face) {
            const vec3 f = raykit::cube_face_direction(face, 0.0f, 0.0f);
            const vec3 sx = raykit::cube_face_direction(face, 1.0f, 0.0f) - f;
            const vec3 ty = raykit::cube_face_direction(face, 0.0f, 1.0f) - f;
            // View space: x along the face's s axis, y along t, looking down -z = f.
            mat4 view(1.0f);
            for (int k = 0; k < 3; ++k) {
                view[k][0] = sx[k];
                view[k][1] = ty[k];
                view[k][2] = -f[k];
            }
            view[3][0] = -glm::dot(sx, env_center_);
            view[3][1] = -glm::dot(ty, env_center_);
            view[3][2] = glm::dot(f, env_center_);
            render(face_target, proj * view, env_center_, 0.0f, false, false);
            const std::vector<float> px = face_target.read(face_target.color);
            raykit::EnvImage img(n, n);
            for (int j = 0; j < n; ++j) {
                for (int i = 0; i < n; ++i) {
                    const std::size_t k = (static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i)) * 4u;
                    img.set(i, j, vec3(px[k], px[k + 1], px[k + 2]));
                }
            }
            cube.faces[static_cast<std::size_t>(face)] = img;
        }
        const double cube_seconds = seconds_since(t0);
        const auto t1 = std::chrono::steady_clock::now();
        raykit::DualParaboloidBakeOptions o;
        o.half_size = s_.env_half;
        o.max_lod = s_.env_max_lod;
        o.supersample = 0;  // automatic: about two samples per cube texel
        const raykit::DualParaboloidMap map = raykit::bake_dual_paraboloid(cube, o);
        const double bake_seconds = seconds_since(t1);
        env_guard_ = map.guard_scale;
        glDeleteTextures(1, &env_);
        glCreateTextures(GL_TEXTURE_2D, 1, &env_);
        const GLsizei levels = static_cast<GLsizei>(map.levels.size());
        glTextureStorage2D(env_, levels, GL_RGBA16F, map.levels[0].width, map.levels[0].height);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        for (GLsizei l = 0; l < levels; ++l) {
            const raykit::EnvImage& img = map.levels[static_cast<std::size_t>(l)];
            glTextureSubImage2D(env_, l, 0, 0, img.width, img.height, GL_RGB, GL_FLOAT, img.rgb.data());
        }
        glTextureParameteri(env_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(env_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(env_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(env_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(env_, GL_TEXTURE_MAX_LEVEL, levels - 1);
        return {cube_seconds, bake_seconds};
    }

    const city::City& city_;
    Settings s_;
    Lighting light_{};
    std::vector<city::BuildingGpu> table_;
    GLuint building_ = 0, building_aux_ = 0, ground_ = 0, shadow_ = 0, sky_ = 0, expose_ = 0, tonemap_ = 0;
    GLuint vbo_ = 0, vao_ = 0, empty_vao_ = 0, ubo_ = 0, ssbo_ = 0;
    GLuint facades_ = 0, rooms_ = 0, sprites_ = 0, shadow_tex_ = 0, shadow_fbo_ = 0, env_ = 0;
    GLsizei building_count_ = 0;
    mat4 shadow_mat_{1.0f};
    vec3 env_center_{0.0f};
    float env_guard_ = 1.0f;
    double texture_seconds_ = 0.0;
};

mat4 view_projection(vec3 eye, vec3 target, float fov_deg, float aspect)
{
    return glm::perspective(glm::radians(fov_deg), aspect, 0.3f, 3000.0f) * glm::lookAt(eye, target, vec3(0.0f, 1.0f, 0.0f));
}

// ---------------------------------------------------------------------------------------------
// Checks

struct ViewCheck {
    std::size_t pixels = 0, nonfinite = 0, window_pixels = 0;
    std::size_t rooms = 0, lit = 0, two_facade_rooms = 0, cpu_mismatch = 0;
    double expected_lit = 0.0, sigma = 0.0;
    double window_mean = 0.0, window_cv = 0.0;  // luminance over window pixels: mean, std / mean
};

ViewCheck check_view(const std::vector<float>& hdr, const std::vector<float>& aux, const std::vector<city::BuildingGpu>& table)
{
    ViewCheck c;
    c.pixels = hdr.size() / 4u;
    // Distinct rooms: (building, cell) -> (lit flag, facade axes seen).
    std::map<std::tuple<int, int, int, int>, std::pair<int, int>> rooms;
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t i = 0; i < c.pixels; ++i) {
        const float* h = &hdr[4 * i];
        if (!std::isfinite(h[0]) || !std::isfinite(h[1]) || !std::isfinite(h[2]) || !std::isfinite(h[3])) {
            if (c.nonfinite++ == 0 && std::getenv("CITY_DEBUG")) {
                std::fprintf(stderr, "nonfinite at pixel %zu (%g %g %g %g) aux (%g %g %g %g)\n", i, h[0], h[1], h[2], h[3],
                             aux[4 * i], aux[4 * i + 1], aux[4 * i + 2], aux[4 * i + 3]);
            }
        }
        const float* a = &aux[4 * i];
        if (a[0] < 3.5f) continue;
        const int code = static_cast<int>(std::lround(a[0]));
        const int building = code / 4 - 1;
        const int lit = code & 1;
        const int axis = (code >> 1) & 1;
        const auto key = std::make_tuple(building, static_cast<int>(std::lround(a[1])), static_cast<int>(std::lround(a[2])),
                                         static_cast<int>(std::lround(a[3])));
        auto it = rooms.find(key);
        if (it == rooms.end()) {
            rooms[key] = {lit, 1 << axis};
        } else {
            it->second.second |= 1 << axis;
        }
        ++c.window_pixels;
        const double y = raykit::rk_luminance(raykit::vec3(h[0], h[1], h[2]));
        sum += y;
        sum2 += y * y;
    }
    if (c.window_pixels > 0) {
        c.window_mean = sum / static_cast<double>(c.window_pixels);
        const double var = std::max(0.0, sum2 / static_cast<double>(c.window_pixels) - c.window_mean * c.window_mean);
        c.window_cv = std::sqrt(var) / std::max(c.window_mean, 1e-12);
    }
    double var = 0.0;
    for (const auto& r : rooms) {
        const int b = std::get<0>(r.first);
        if (b < 0 || static_cast<std::size_t>(b) >= table.size()) {
            ++c.cpu_mismatch;
            continue;
        }
        const float p = std::clamp(table[static_cast<std::size_t>(b)].lit, 0.0f, 1.0f);
        const std::uint32_t seed = static_cast<std::uint32_t>(table[static_cast<std::size_t>(b)].seed);
        const raykit::ivec3 cell(std::get<1>(r.first), std::get<2>(r.first), std::get<3>(r.first));
        const bool cpu_lit = raykit::rk_im_room_lit(cell, p, seed);
        if (cpu_lit != (r.second.first == 1)) ++c.cpu_mismatch;
        c.lit += static_cast<std::size_t>(r.second.first);
        c.expected_lit += p;
        var += static_cast<double>(p) * (1.0 - static_cast<double>(p));
        if (r.second.second == 3) ++c.two_facade_rooms;
    }
    c.rooms = rooms.size();
    c.sigma = std::sqrt(var);
    return c;
}

// ---------------------------------------------------------------------------------------------

struct Options {
    std::string out_dir = ".";
    bool quick = false, window = false, bloom = true;
    int width = 0, height = 0;
    std::vector<std::string> views;
};

bool parse(int argc, char** argv, Options& o)
{
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") {
            o.quick = true;
        } else if (a == "--window") {
            o.window = true;
        } else if (a == "--no-bloom") {
            o.bloom = false;
        } else if (a == "--views" && i + 1 < argc) {
            std::string list = argv[++i];
            std::size_t start = 0;
            while (start <= list.size()) {
                const std::size_t comma = list.find(',', start);
                const std::string v = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
                if (!v.empty()) o.views.push_back(v);
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
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

Settings settings_for(const Options& o)
{
    Settings s;
    if (o.quick) {
        s.width = 320;
        s.height = 180;
        s.shadow_size = 1024;
        s.cube_size = 64;
        s.env_half = 64;
        s.env_max_lod = 2.0f;
        s.tex_size = 64;
    }
    if (o.width > 0) {
        s.width = o.width;
        s.height = o.height;
    }
    s.bloom = o.bloom;
    return s;
}

int run_headless(const Options& opt)
{
    const auto t_start = std::chrono::steady_clock::now();
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) {
        return rkgl::no_context_exit("city", ctx.error());
    }
    std::printf("renderer: %s\n", ctx.renderer().c_str());
    const Settings s = settings_for(opt);

    const auto t_gen = std::chrono::steady_clock::now();
    const city::City c = city::make_city(20091u);
    std::size_t rooms_total = 0;
    for (const city::Building& b : c.buildings) {
        const raykit::vec3 r = b.grid.room_size;
        rooms_total += static_cast<std::size_t>(std::lround(2.0 * b.hx / r.x) * std::lround(b.height / r.y) *
                                                std::lround(2.0 * b.hz / r.z));
    }
    std::printf("city: %zu buildings (%d round towers), %zu triangles, ~%zu rooms, generated in %.3f s\n",
                c.buildings.size(), c.cylinders, c.vertices.size() / 3u, rooms_total, seconds_since(t_gen));
    if (c.buildings.size() < 100) {
        std::fprintf(stderr, "city: only %zu buildings\n", c.buildings.size());
        return 1;
    }

    const auto t_init = std::chrono::steady_clock::now();
    CityRenderer r(c, s);
    rkgl::LuminanceReducer reducer(RAYKIT_SHADER_DIR);
    std::unique_ptr<rkgl::BloomGl> bloom;
    if (s.bloom) {
        bloom = std::make_unique<rkgl::BloomGl>(RAYKIT_SHADER_DIR, GL_RGBA16F);
        raykit::BloomParams bp = raykit::BloomParams::recommended();
        bp.threshold = 1.2f;
        bp.strength = 0.25f;
        bloom->set_params(bp);
    }
    std::printf("programs + textures: %.2f s (textures %.3f s)\n", seconds_since(t_init), r.texture_seconds());

    std::vector<View> views = make_views(c);
    if (!opt.views.empty()) {
        std::vector<View> chosen;
        for (const std::string& name : opt.views) {
            auto it = std::find_if(views.begin(), views.end(), [&](const View& v) { return v.name == name; });
            if (it == views.end()) {
                std::fprintf(stderr, "city: unknown view '%s'\n", name.c_str());
                return 1;
            }
            chosen.push_back(*it);
        }
        views = chosen;
    }

    SceneTarget target(s.width, s.height);
    ColorTarget exposed(s.width, s.height, GL_RGBA16F);
    ColorTarget out(s.width, s.height, GL_RGBA8);
    const Lighting presets[2] = {day_lighting(), dusk_lighting()};
    int current = -1;
    bool ok = true;
    const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
    for (const View& v : views) {
        if (v.lighting != current) {
            current = v.lighting;
            const auto tl = std::chrono::steady_clock::now();
            const std::pair<double, double> env = r.set_lighting(presets[current], true);
            glFinish();
            std::printf("lighting '%s': shadow map + reflection map %.2f s (cube %dx6 rendered and read back in %.2f s, "
                        "CPU dual-paraboloid bake %dx%d + mips in %.2f s)\n",
                        presets[current].name, seconds_since(tl), s.cube_size, env.first, 2 * s.env_half, s.env_half, env.second);
        }
        const auto t0 = std::chrono::steady_clock::now();
        r.render(target, view_projection(v.eye, v.target, v.fov_deg, aspect), v.eye, 1.5f, true, true);
        glFinish();
        const double t_scene = seconds_since(t0);
        rkgl::LuminanceReduceOptions lo;
        lo.reset_adaptation = true;
        lo.ev_compensation = v.ev;
        const rkgl::LuminanceReduceResult lum = reducer.reduce_texture(target.color, s.width, s.height, 4, lo);
        const float exposure = std::isfinite(lum.exposure) && lum.exposure > 0.0f ? lum.exposure : 1.0f;
        r.post(target, exposure, bloom.get(), exposed, out);
        glFinish();
        const double t_frame = seconds_since(t0);

        const ViewCheck ck = check_view(target.read(target.color), target.read(target.aux), r.table());
        std::vector<unsigned char> px(static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height) * 4u);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, out.fbo);
        glReadPixels(0, 0, s.width, s.height, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        std::vector<unsigned char> flipped(px.size());
        const std::size_t row = static_cast<std::size_t>(s.width) * 4u;
        for (int y = 0; y < s.height; ++y) {
            std::memcpy(&flipped[static_cast<std::size_t>(y) * row], &px[static_cast<std::size_t>(s.height - 1 - y) * row], row);
        }
        for (std::size_t i = 3; i < flipped.size(); i += 4) flipped[i] = 255;
        const GLenum err = glGetError();
        const std::string path = opt.out_dir + "/city_" + v.name + ".png";
        if (!rkgl::write_png_rgba8(path, s.width, s.height, flipped.data())) {
            std::fprintf(stderr, "city: cannot write %s\n", path.c_str());
            return 1;
        }

        // Checks.
        const double dev = std::abs(static_cast<double>(ck.lit) - ck.expected_lit);
        const double bound = 4.0 * ck.sigma + 2.0;
        std::vector<std::string> fails;
        if (err != GL_NO_ERROR) fails.push_back("OpenGL error " + std::to_string(err));
        if (ck.nonfinite) fails.push_back(std::to_string(ck.nonfinite) + " NaN/Inf HDR pixels");
        if (ck.rooms < 20) fails.push_back("only " + std::to_string(ck.rooms) + " distinct rooms visible");
        if (dev > bound) fails.push_back("lit rooms off the expectation by more than 4 sigma + 2");
        if (ck.cpu_mismatch) fails.push_back(std::to_string(ck.cpu_mismatch) + " rooms where the GPU lit flag differs from rk_im_room_lit");
        if (!(ck.window_cv > 0.3)) fails.push_back("window luminance nearly flat (cv <= 0.3)");
        if (v.name == "corner" && ck.two_facade_rooms < 1) fails.push_back("no room seen through two facades");
        std::printf("view %-9s %s: %.2f s (scene %.2f s), exposure %.4g (EV100 %.2f)\n"
                    "    checks: %zu px, %zu NaN/Inf, %zu window px (mean luminance %.3g, cv %.2f), %zu rooms, lit %zu vs "
                    "expected %.1f +- %.1f (|dev| %.1f <= %.1f), GPU/CPU lit mismatches %zu, rooms through two facades %zu -> %s\n",
                    v.name.c_str(), path.c_str(), t_frame, t_scene, exposure, lum.ev100, ck.pixels, ck.nonfinite, ck.window_pixels,
                    ck.window_mean, ck.window_cv, ck.rooms, ck.lit, ck.expected_lit, ck.sigma, dev, bound, ck.cpu_mismatch,
                    ck.two_facade_rooms, fails.empty() ? "ok" : "FAILED");
        for (const std::string& f : fails) std::fprintf(stderr, "city: view %s: %s\n", v.name.c_str(), f.c_str());
        ok = ok && fails.empty();
    }
    std::printf("total %.2f s\n", seconds_since(t_start));
    return ok ? 0 : 1;
}

#ifdef CITY_HAVE_GLFW
// Free camera: WASD (+ Q/E down/up, shift faster), mouse look with the left button held,
// 1/2 switch day/dusk, Esc quits.
int run_window(const Options& opt)
{
    if (!glfwInit()) {
        std::fprintf(stderr, "city: GLFW could not initialise (no display?)\n");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    Settings s = settings_for(opt);
    GLFWwindow* win = glfwCreateWindow(s.width, s.height, "raykit city", nullptr, nullptr);
    if (!win) {
        std::fprintf(stderr, "city: no OpenGL 4.5 window\n");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    int rc = 0;
    try {
        const city::City c = city::make_city(20091u);
        CityRenderer r(c, s);
        rkgl::LuminanceReducer reducer(RAYKIT_SHADER_DIR);
        rkgl::BloomGl bloom(RAYKIT_SHADER_DIR, GL_RGBA16F);
        raykit::BloomParams bp = raykit::BloomParams::recommended();
        bp.threshold = 1.2f;
        bp.strength = 0.25f;
        bloom.set_params(bp);
        const Lighting presets[2] = {day_lighting(), dusk_lighting()};
        int preset = 0;
        r.set_lighting(presets[preset], true);
        vec3 eye(-200.0f, 2.0f, -5.0f);
        float yaw = 0.0f, pitch = 0.1f;
        double last_x = 0.0, last_y = 0.0;
        glfwGetCursorPos(win, &last_x, &last_y);
        auto t_prev = std::chrono::steady_clock::now();
        const auto t0 = t_prev;
        int fb_w = 0, fb_h = 0;
        std::unique_ptr<SceneTarget> target;
        std::unique_ptr<ColorTarget> exposed, out;
        while (!glfwWindowShouldClose(win)) {
            glfwPollEvents();
            const float dt = static_cast<float>(seconds_since(t_prev));
            t_prev = std::chrono::steady_clock::now();
            if (glfwGetKey(win, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(win, 1);
            for (int k = 0; k < 2; ++k) {
                if (glfwGetKey(win, GLFW_KEY_1 + k) == GLFW_PRESS && preset != k) {
                    preset = k;
                    r.set_lighting(presets[preset], true);
                }
            }
            double mx = 0.0, my = 0.0;
            glfwGetCursorPos(win, &mx, &my);
            if (glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
                yaw += 0.004f * static_cast<float>(mx - last_x);
                pitch = std::clamp(pitch - 0.004f * static_cast<float>(my - last_y), -1.5f, 1.5f);
            }
            last_x = mx;
            last_y = my;
            const vec3 fwd(std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw));
            const vec3 right = glm::normalize(glm::cross(fwd, vec3(0.0f, 1.0f, 0.0f)));
            const float speed = (glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 60.0f : 12.0f) * dt;
            if (glfwGetKey(win, GLFW_KEY_W) == GLFW_PRESS) eye += fwd * speed;
            if (glfwGetKey(win, GLFW_KEY_S) == GLFW_PRESS) eye -= fwd * speed;
            if (glfwGetKey(win, GLFW_KEY_D) == GLFW_PRESS) eye += right * speed;
            if (glfwGetKey(win, GLFW_KEY_A) == GLFW_PRESS) eye -= right * speed;
            if (glfwGetKey(win, GLFW_KEY_E) == GLFW_PRESS) eye.y += speed;
            if (glfwGetKey(win, GLFW_KEY_Q) == GLFW_PRESS) eye.y = std::max(0.5f, eye.y - speed);
            int w = 0, h = 0;
            glfwGetFramebufferSize(win, &w, &h);
            if (w < 1 || h < 1) continue;
            if (w != fb_w || h != fb_h) {
                fb_w = w;
                fb_h = h;
                target = std::make_unique<SceneTarget>(w, h);
                exposed = std::make_unique<ColorTarget>(w, h, GL_RGBA16F);
                out = std::make_unique<ColorTarget>(w, h, GL_RGBA8);
            }
            const float aspect = static_cast<float>(w) / static_cast<float>(h);
            r.render(*target, view_projection(eye, eye + fwd, 60.0f, aspect), eye, static_cast<float>(seconds_since(t0)), true,
                     false);
            rkgl::LuminanceReduceOptions lo;
            lo.dt = dt;
            lo.ev_compensation = 0.5f;
            const rkgl::LuminanceReduceResult lum = reducer.reduce_texture(target->color, w, h, 4, lo);
            r.post(*target, lum.exposure > 0.0f ? lum.exposure : 1.0f, &bloom, *exposed, *out);
            glBlitNamedFramebuffer(out->fbo, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glfwSwapBuffers(win);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "city: %s\n", e.what());
        rc = 1;
    }
    glfwDestroyWindow(win);
    glfwTerminate();
    return rc;
}
#endif

}  // namespace

int main(int argc, char** argv)
{
    Options opt;
    if (!parse(argc, argv, opt)) {
        std::fprintf(stderr, "usage: city [--quick] [--window] [--views a,b,...] [--size WxH] [--no-bloom] [OUT_DIR]\n");
        return 1;
    }
    try {
        if (opt.window) {
#ifdef CITY_HAVE_GLFW
            return run_window(opt);
#else
            std::fprintf(stderr, "city: built without GLFW; --window is not available\n");
            return 1;
#endif
        }
        return run_headless(opt);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "city: %s\n", e.what());
        return 1;
    }
}
