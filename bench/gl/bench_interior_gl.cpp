// raykit bench — bench_interior_gl: GPU frame time of interior mapping against a plain material,
// on one scene, in one run (issue 4 item 10).
//
// The scene is the thesis's z-cull test scene (van Dongen, "Using raycasting in GPU shaders to
// enhance real-time graphics", Master's thesis, Utrecht University, 2009, §5.3):
// one mesh holding a grid of box buildings (8 x 8 buildings of 24 x 93 x 24 units, the thesis's
// test building of 6 x 6 windows and 31 floors, with 16-unit streets), drawn in one call, seen by
// a camera that moves down a street and turns. Every material draws the same mesh from the same
// camera poses:
//   plain        lit facade texture, cube-map reflection in the windows (the thesis's baseline)
//   thesis       bench/gl/thesis_im.frag: the thesis's appendix shader ported to GLSL 4.50
//   rk_min       samples/common/interior_building.frag, every RK_IM_* feature off (four textures)
//   rk_full      the same file with every feature on (texture array, room lights, furniture,
//                Fresnel-weighted dual-paraboloid reflection, distance fade)
//   rk_full-X    rk_full with feature X off, and rk_min+X with only X on (cost attribution)
//   rkb_*        bench/gl/raykit_building.frag, a leaner composition of the same raykit includes,
//                for the switches the sample material has not (opaque-texel skip, implicit LOD,
//                reflection LOD); it provides the rk_* variants when the sample material is absent
// each without and with a depth pre-pass (depth-only pass, then the colour pass with GL_EQUAL
// and depth writes off), and the interior materials also with rooms from ~10^3 to 4*10^6 per
// building (the room size shrinks on the same buildings; the cost must not change).
//
// Timing: every frame is timed twice, with a GL_TIME_ELAPSED query around its draw calls (GPU
// time) and with the wall clock between two glFinish calls (the clear is finished before the
// clock starts). Configurations are interleaved frame by frame (round r renders camera pose r with
// every configuration, in a rotated order), so a slow patch of a shared machine hits all of them
// alike; ratios are taken per round against the plain material at the same pose and round, and
// the median over rounds is reported with the quartiles. With --poses P < N the camera path has P
// poses and round r renders pose r mod P: the N / P sweeps over the same poses give the report
// (scripts/bench_interior.sh) the run-to-run spread of every ratio (its range over the sweeps).
//
// Usage: bench_interior_gl [--width W] [--height H] [--rounds N] [--poses P] [--warmup N] [--only SUBSTR]
//                          [--json FILE] [--csv FILE] [--md FILE] [--png FILE] [--smoke]
//                          [--require-raykit]
//        bench_interior_gl --list-materials | --dump-frag NAME   (no GL context needed)
//   --smoke: 64 x 48, 2 rounds, the 8 main configurations, sanity checks only (ctest).
//   --only SUBSTR: only configurations whose name contains SUBSTR (plus plain, the reference);
//   SUBSTR may be a comma-separated list (any entry matches), and an entry starting with '='
//   matches a whole name only (e.g. --only =thesis,=rk_min,=rk_full for the three main materials).
//   --png FILE: the four main materials at the first pose, side by side (downscaled to <= 400 px
//   per panel). --require-raykit: fail when samples/common/interior_building.* is missing.
//   --dump-frag: the fragment source exactly as compiled (includes inlined, macros injected), for
//   the SPIR-V instruction counts of scripts/bench_interior.sh.
// Exit codes: 0 done; 1 error (shader, GL, a failed sanity check); 77 no OpenGL 4.5 context (skip;
// 1 instead when CI=true).

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "raykit/paraboloid.hpp"
#include "raykit/shader_source.hpp"
#include "rk_gl.hpp"

#include "rk_png.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// Scene constants (object units): the thesis's test building, 6 x 6 windows and 31 floors.

constexpr int kGridX = 8;
constexpr int kGridZ = 8;
constexpr float kRoomW = 4.0f;     // room width and depth (window pitch)
constexpr float kStorey = 3.0f;    // storey height
constexpr int kRoomsAcross = 6;
constexpr int kFloors = 31;
constexpr float kBuildW = kRoomW * static_cast<float>(kRoomsAcross);   // 24
constexpr float kBuildH = kStorey * static_cast<float>(kFloors);       // 93
constexpr float kStreet = 16.0f;
constexpr float kPitch = kBuildW + kStreet;                            // 40
constexpr double kBaseRoomsPerBuilding = double(kRoomsAcross) * kRoomsAcross * kFloors;   // 1116

struct Options {
    int width = 512;
    int height = 384;
    int rounds = 15;
    int poses = 0;  // camera poses on the path; 0: one per round
    int warmup = 2;
    bool smoke = false;
    bool require_raykit = false;
    std::string only;
    std::string json, csv, md, png;
};

[[noreturn]] void usage_error(const std::string& what)
{
    throw std::invalid_argument(what + " (see the usage at the top of bench_interior_gl.cpp)");
}

Options parse_options(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage_error("missing value after " + a);
            return argv[++i];
        };
        auto int_value = [&]() {
            const std::string v = value();
            char* end = nullptr;
            const long n = std::strtol(v.c_str(), &end, 10);
            if (end == v.c_str() || *end != '\0' || n < 0 || n > 100000) usage_error("bad number " + v);
            return static_cast<int>(n);
        };
        if (a == "--width") o.width = int_value();
        else if (a == "--height") o.height = int_value();
        else if (a == "--rounds") o.rounds = int_value();
        else if (a == "--poses") o.poses = int_value();
        else if (a == "--warmup") o.warmup = int_value();
        else if (a == "--only") o.only = value();
        else if (a == "--json") o.json = value();
        else if (a == "--csv") o.csv = value();
        else if (a == "--md") o.md = value();
        else if (a == "--png") o.png = value();
        else if (a == "--smoke") o.smoke = true;
        else if (a == "--require-raykit") o.require_raykit = true;
        else usage_error("unknown argument " + a);
    }
    if (o.smoke) {
        o.width = 64;
        o.height = 48;
        o.rounds = 2;
        o.warmup = 0;
    }
    if (o.width < 8 || o.height < 8 || o.rounds < 1) usage_error("width, height >= 8 and rounds >= 1 required");
    if (o.poses == 0 || o.poses > o.rounds) o.poses = o.rounds;
    return o;
}

// ---------------------------------------------------------------------------------------------
// Procedural textures (deterministic).

float hash01(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return static_cast<float>(x >> 8) * (1.0f / 16777216.0f);
}

unsigned char to_u8(float v)
{
    return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

struct Image {
    int w = 0, h = 0;
    std::vector<unsigned char> rgba;
    Image(int width, int height) : w(width), h(height), rgba(static_cast<size_t>(width) * static_cast<size_t>(height) * 4u) {}
    void set(int x, int y, glm::vec3 c, float a)
    {
        const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4u;
        rgba[i] = to_u8(c.r);
        rgba[i + 1] = to_u8(c.g);
        rgba[i + 2] = to_u8(c.b);
        rgba[i + 3] = to_u8(a);
    }
};

// One room's share of the facade (kRoomW x kStorey): brick wall, a window (alpha 1) in a frame.
Image make_facade(int n)
{
    Image img(n, n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
            const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
            const bool window = u > 0.16f && u < 0.84f && v > 0.22f && v < 0.86f;
            const bool frame = u > 0.13f && u < 0.87f && v > 0.19f && v < 0.89f;
            const int row = y / 6;
            const int brick = (x + (row % 2) * 6) / 12;
            const bool mortar = (y % 6 == 0) || ((x + (row % 2) * 6) % 12 == 0);
            const float noise = hash01(static_cast<std::uint32_t>(row * 977 + brick * 131));
            glm::vec3 c = mortar ? glm::vec3(0.62f, 0.6f, 0.56f)
                                 : glm::vec3(0.55f, 0.3f, 0.22f) * (0.8f + 0.35f * noise);
            if (frame) c = glm::vec3(0.18f, 0.18f, 0.2f);
            img.set(x, y, c, window ? 1.0f : 0.0f);
        }
    }
    return img;
}

// Interior surfaces, one room face per texture tile; variant shifts colours (texture arrays).
Image make_interior(int kind, int variant, int n)
{
    Image img(n, n);
    const float hue = static_cast<float>(variant) * 0.37f;
    const glm::vec3 tint(0.75f + 0.25f * std::sin(hue * 6.28f), 0.75f + 0.25f * std::sin(hue * 6.28f + 2.1f),
                         0.75f + 0.25f * std::sin(hue * 6.28f + 4.2f));
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
            const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
            glm::vec3 c;
            switch (kind) {
            case 0: {   // ceiling: plaster and a lamp panel
                const bool lamp = std::abs(u - 0.5f) < 0.12f && std::abs(v - 0.5f) < 0.12f;
                c = lamp ? glm::vec3(1.0f, 0.97f, 0.85f) : glm::vec3(0.82f, 0.82f, 0.8f) * tint;
                break;
            }
            case 1: {   // floor: planks
                const int plank = static_cast<int>(u * 8.0f);
                const float g = hash01(static_cast<std::uint32_t>(plank * 31 + variant * 7));
                const bool seam = std::fmod(u * 8.0f, 1.0f) < 0.04f;
                c = seam ? glm::vec3(0.2f, 0.12f, 0.06f) : glm::vec3(0.5f, 0.32f, 0.16f) * (0.75f + 0.4f * g);
                break;
            }
            default: {   // walls: wallpaper stripes, skirting, a picture or a door
                const float stripe = std::fmod(u * 12.0f, 1.0f) < 0.5f ? 1.0f : 0.9f;
                c = (kind == 2 ? glm::vec3(0.85f, 0.78f, 0.6f) : glm::vec3(0.6f, 0.72f, 0.78f)) * tint * stripe;
                if (v < 0.06f) c = glm::vec3(0.3f, 0.25f, 0.2f);
                const bool picture = kind == 2 && std::abs(u - 0.5f) < 0.15f && std::abs(v - 0.6f) < 0.1f;
                const bool door = kind == 3 && std::abs(u - 0.3f) < 0.1f && v < 0.7f;
                if (picture) c = glm::vec3(0.2f, 0.35f, 0.25f);
                if (door) c = glm::vec3(0.45f, 0.3f, 0.18f);
                break;
            }
            }
            img.set(x, y, c, 1.0f);
        }
    }
    return img;
}

// A furniture sprite layer: a sofa/table/plant silhouette with alpha (0 = transparent).
Image make_furniture(int layer, int n)
{
    Image img(n, n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
            const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
            bool solid = false;
            glm::vec3 c(0.0f);
            switch (layer % 4) {
            case 0: solid = u > 0.1f && u < 0.6f && v < 0.35f && (v < 0.2f || u < 0.18f || u > 0.52f); c = glm::vec3(0.5f, 0.15f, 0.15f); break;
            case 1: solid = (u > 0.55f && u < 0.9f && v > 0.28f && v < 0.32f) || ((std::abs(u - 0.6f) < 0.02f || std::abs(u - 0.85f) < 0.02f) && v < 0.3f); c = glm::vec3(0.35f, 0.22f, 0.1f); break;
            case 2: solid = (std::abs(u - 0.8f) < 0.05f && v < 0.15f) || (glm::length(glm::vec2(u - 0.8f, v - 0.3f)) < 0.12f); c = glm::vec3(0.15f, 0.45f, 0.15f); break;
            default: solid = std::abs(u - 0.35f) < 0.08f && v < 0.6f && (v < 0.45f || std::abs(u - 0.35f) < 0.05f); c = glm::vec3(0.2f, 0.2f, 0.3f); break;
            }
            img.set(x, y, c, solid ? 1.0f : 0.0f);
        }
    }
    return img;
}

// The environment the windows reflect (world-space direction): sky, horizon haze, dark ground.
glm::vec3 env_colour(glm::vec3 d)
{
    const float y = d.y;
    if (y < 0.0f) return glm::mix(glm::vec3(0.35f, 0.36f, 0.38f), glm::vec3(0.12f, 0.12f, 0.13f), std::min(1.0f, -y * 4.0f));
    const glm::vec3 sky = glm::mix(glm::vec3(0.75f, 0.82f, 0.9f), glm::vec3(0.25f, 0.45f, 0.8f), std::sqrt(y));
    const float sun = std::pow(std::max(0.0f, glm::dot(d, glm::normalize(glm::vec3(0.5f, 0.33166f, 0.8f)))), 64.0f);
    return sky + glm::vec3(3.0f, 2.8f, 2.4f) * sun;
}

/// The number of mip levels of a full chain for an n-texel side.
int mip_levels(int n) { return 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(n)))); }

/// Builds the mip chain of `tex` (level 0 uploaded) and sets trilinear filtering; `wrap` (S and T)
/// unless 0.
void finish_trilinear(GLuint tex, GLenum wrap)
{
    glGenerateTextureMipmap(tex);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (wrap != 0) {
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
    }
}

GLuint make_texture_2d(const Image& img, GLenum wrap)
{
    GLuint tex = 0;
    const int levels = mip_levels(std::max(img.w, img.h));
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, levels, GL_RGBA8, img.w, img.h);
    glTextureSubImage2D(tex, 0, 0, 0, img.w, img.h, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    finish_trilinear(tex, wrap);
    return tex;
}

GLuint make_texture_array(const std::vector<Image>& layers, GLenum wrap)
{
    GLuint tex = 0;
    const int n = layers.front().w;
    const int levels = mip_levels(n);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tex);
    glTextureStorage3D(tex, levels, GL_RGBA8, n, n, static_cast<GLsizei>(layers.size()));
    for (size_t i = 0; i < layers.size(); ++i) {
        glTextureSubImage3D(tex, 0, 0, 0, static_cast<GLint>(i), n, n, 1, GL_RGBA, GL_UNSIGNED_BYTE, layers[i].rgba.data());
    }
    finish_trilinear(tex, wrap);
    return tex;
}

// A padded atlas: tiles x tiles cells of (n + 2 pad) texels, each cell's border repeating its tile
// (wrap-around), so that bilinear filtering and a few mips stay inside the cell.
Image make_atlas(const std::vector<Image>& tiles, int per_side, int pad)
{
    const int n = tiles.front().w;
    const int cell = n + 2 * pad;
    Image atlas(cell * per_side, cell * per_side);
    for (int t = 0; t < per_side * per_side; ++t) {
        const Image& src = tiles[static_cast<size_t>(t) % tiles.size()];
        const int cx = (t % per_side) * cell, cy = (t / per_side) * cell;
        for (int y = 0; y < cell; ++y) {
            for (int x = 0; x < cell; ++x) {
                const int sx = ((x - pad) % n + n) % n, sy = ((y - pad) % n + n) % n;
                const size_t si = (static_cast<size_t>(sy) * static_cast<size_t>(n) + static_cast<size_t>(sx)) * 4u;
                const size_t di = (static_cast<size_t>(cy + y) * static_cast<size_t>(atlas.w) + static_cast<size_t>(cx + x)) * 4u;
                std::memcpy(&atlas.rgba[di], &src.rgba[si], 4);
            }
        }
    }
    return atlas;
}

// Room cube maps (RK_IM_SHADING 3): `count` cubes of n x n faces, +-y ceiling / floor, the four
// walls from the two wall textures, each cube from another variant (the cube array's layer).
GLuint make_room_cubes(const std::vector<Image>& variants, int count, int n)
{
    GLuint tex = 0;
    const int levels = mip_levels(n);
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &tex);
    glTextureStorage3D(tex, levels, GL_RGBA8, n, n, 6 * count);
    // variants: family * 4 + variant, family 0 ceiling, 1 floor, 2 wall xy, 3 wall zy.
    const int family_of_face[6] = {3, 3, 0, 1, 2, 2};   // +x, -x, +y, -y, +z, -z
    for (int c = 0; c < count; ++c) {
        for (int face = 0; face < 6; ++face) {
            const Image& src = variants[static_cast<size_t>(family_of_face[face] * 4 + c % 4)];
            Image img(n, n);
            for (int y = 0; y < n; ++y) {
                for (int x = 0; x < n; ++x) {
                    const size_t si = (static_cast<size_t>(y * src.h / n) * static_cast<size_t>(src.w) + static_cast<size_t>(x * src.w / n)) * 4u;
                    std::memcpy(&img.rgba[(static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x)) * 4u], &src.rgba[si], 4);
                }
            }
            glTextureSubImage3D(tex, 0, 0, 0, c * 6 + face, n, n, 1, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
        }
    }
    finish_trilinear(tex, 0);
    return tex;
}

GLuint make_env_cube(int n)
{
    GLuint tex = 0;
    const int levels = mip_levels(n);
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &tex);
    glTextureStorage2D(tex, levels, GL_RGBA8, n, n);
    for (int face = 0; face < 6; ++face) {
        Image img(n, n);
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) img.set(i, j, env_colour(raykit::cube_texel_direction(face, i, j, n)), 1.0f);
        }
        glTextureSubImage3D(tex, 0, 0, 0, face, n, n, 1, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    }
    finish_trilinear(tex, 0);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return tex;
}

struct ParaboloidTexture {
    GLuint tex = 0;
    float guard_scale = 1.0f;
    float max_lod = 0.0f;
};

ParaboloidTexture make_env_paraboloid(int half_size, float max_lod)
{
    raykit::DualParaboloidBakeOptions o;
    o.half_size = half_size;
    o.max_lod = max_lod;
    o.supersample = 2;
    const raykit::DualParaboloidMap map = raykit::bake_dual_paraboloid_fn([](glm::vec3 d) { return env_colour(d); }, o);
    ParaboloidTexture out;
    out.guard_scale = map.guard_scale;
    out.max_lod = map.max_lod;
    glCreateTextures(GL_TEXTURE_2D, 1, &out.tex);
    const auto levels = static_cast<GLsizei>(map.levels.size());
    glTextureStorage2D(out.tex, levels, GL_RGBA16F, map.levels[0].width, map.levels[0].height);
    for (GLsizei l = 0; l < levels; ++l) {
        const raykit::EnvImage& im = map.levels[static_cast<size_t>(l)];
        glTextureSubImage2D(out.tex, l, 0, 0, im.width, im.height, GL_RGB, GL_FLOAT, im.rgb.data());
    }
    glTextureParameteri(out.tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(out.tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(out.tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(out.tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(out.tex, GL_TEXTURE_MAX_LEVEL, levels - 1);
    return out;
}

// ---------------------------------------------------------------------------------------------
// The city mesh: kGridX x kGridZ boxes (four facades and a roof), one vertex buffer, one draw.

struct Mesh {
    GLuint vao = 0, vbo = 0, ibo = 0;
    GLsizei index_count = 0;
    int buildings = 0;
};

Mesh make_city()
{
    struct Vertex {
        float p[3], n[3], uv[2];
    };
    std::vector<Vertex> verts;
    std::vector<std::uint32_t> idx;
    auto quad = [&](glm::vec3 o, glm::vec3 du, glm::vec3 dv, glm::vec3 n, glm::vec2 uv_size, bool roof) {
        const auto base = static_cast<std::uint32_t>(verts.size());
        const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (const glm::vec2& c : corners) {
            const glm::vec3 p = o + c.x * du + c.y * dv;
            // Facade UVs: one texture tile per room at the base room size; the roof maps to one
            // wall texel (alpha 0: no windows).
            const glm::vec2 uv = roof ? glm::vec2(0.05f, 0.05f) : c * uv_size;
            verts.push_back({{p.x, p.y, p.z}, {n.x, n.y, n.z}, {uv.x, uv.y}});
        }
        for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(base + k);
    };
    const glm::vec2 facade_uv(static_cast<float>(kRoomsAcross), static_cast<float>(kFloors));
    for (int gz = 0; gz < kGridZ; ++gz) {
        for (int gx = 0; gx < kGridX; ++gx) {
            const float x0 = static_cast<float>(gx) * kPitch, z0 = static_cast<float>(gz) * kPitch;
            const float x1 = x0 + kBuildW, z1 = z0 + kBuildW;
            const glm::vec3 up(0.0f, kBuildH, 0.0f);
            // Counter-clockwise seen from outside.
            quad({x0, 0, z1}, {kBuildW, 0, 0}, up, {0, 0, 1}, facade_uv, false);    // +z
            quad({x1, 0, z0}, {-kBuildW, 0, 0}, up, {0, 0, -1}, facade_uv, false);  // -z
            quad({x1, 0, z1}, {0, 0, -kBuildW}, up, {1, 0, 0}, facade_uv, false);   // +x
            quad({x0, 0, z0}, {0, 0, kBuildW}, up, {-1, 0, 0}, facade_uv, false);   // -x
            quad({x0, kBuildH, z1}, {kBuildW, 0, 0}, {0, 0, -kBuildW}, {0, 1, 0}, facade_uv, true);
        }
    }
    Mesh m;
    m.buildings = kGridX * kGridZ;
    glCreateVertexArrays(1, &m.vao);
    glCreateBuffers(1, &m.vbo);
    glCreateBuffers(1, &m.ibo);
    glNamedBufferStorage(m.vbo, static_cast<GLsizeiptr>(verts.size() * sizeof(Vertex)), verts.data(), 0);
    glNamedBufferStorage(m.ibo, static_cast<GLsizeiptr>(idx.size() * sizeof(std::uint32_t)), idx.data(), 0);
    glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, sizeof(Vertex));
    glVertexArrayElementBuffer(m.vao, m.ibo);
    for (GLuint a = 0; a < 3; ++a) glEnableVertexArrayAttrib(m.vao, a);
    glVertexArrayAttribFormat(m.vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, p));
    glVertexArrayAttribFormat(m.vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, n));
    glVertexArrayAttribFormat(m.vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, uv));
    for (GLuint a = 0; a < 3; ++a) glVertexArrayAttribBinding(m.vao, a, 0);
    m.index_count = static_cast<GLsizei>(idx.size());
    return m;
}

// The camera: down the street between building rows 3 and 4, at 40 units, turning a full circle
// over the path and pitching gently, so that facades at all angles and some overdraw are seen.
struct Camera {
    glm::mat4 view_proj;
    glm::vec3 pos;
};

Camera camera_at(int pose, int poses, float aspect)
{
    const float t = (static_cast<float>(pose) + 0.5f) / static_cast<float>(std::max(poses, 1));
    const float street_z = 3.0f * kPitch + kBuildW + 0.5f * kStreet;
    Camera c;
    c.pos = glm::vec3(10.0f + t * (static_cast<float>(kGridX - 1) * kPitch), 40.0f + 12.0f * std::sin(t * 6.2831853f), street_z);
    const float yaw = t * 6.2831853f;
    const float pitch = 0.15f * std::sin(t * 12.566371f);
    const glm::vec3 fwd(std::cos(yaw) * std::cos(pitch), std::sin(pitch), std::sin(yaw) * std::cos(pitch));
    const glm::mat4 view = glm::lookAt(c.pos, c.pos + fwd, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 proj = glm::perspective(glm::radians(60.0f), aspect, 0.5f, 1500.0f);
    c.view_proj = proj * view;
    return c;
}

// ---------------------------------------------------------------------------------------------
// Materials and configurations.

enum class Kind { plain, thesis, raykit };

struct Material {
    std::string name;
    Kind kind = Kind::plain;
    std::string vert_path, frag_path;
    std::vector<raykit::ShaderDefine> defines;
    std::string features;          // human-readable description
    int shading = 0;               // RK_IM_SHADING of a Kind::raykit material (texture unit 5); set from its defines
    GLuint color_prog = 0;
    GLuint depth_prog = 0;
};

struct Config {
    std::string name;
    size_t material = 0;
    bool prepass = false;
    double rooms_target = kBaseRoomsPerBuilding;   // rooms per building
    std::string group;                             // main | rooms | features
};

struct Sample {
    double gpu_ms = 0.0, wall_ms = 0.0;
    std::uint64_t fragments = 0;
};

bool file_exists(const std::string& path)
{
    std::ifstream f(path);
    return f.good();
}

std::string load(const std::string& path, const std::vector<raykit::ShaderDefine>& defines)
{
    return rkgl::shader_file(path, {RAYKIT_SHADER_DIR}, defines);
}

glm::vec3 room_size_for(double rooms_per_building)
{
    const double k = std::cbrt(kBaseRoomsPerBuilding / rooms_per_building);
    return glm::vec3(static_cast<float>(kRoomW * k), static_cast<float>(kStorey * k), static_cast<float>(kRoomW * k));
}

double rooms_per_building(glm::vec3 room)
{
    return double(kBuildW) * double(kBuildH) * double(kBuildW) / (double(room.x) * double(room.y) * double(room.z));
}

struct Textures {
    GLuint facade = 0, env_cube = 0;
    std::array<GLuint, 4> interior{};   // ceiling, floor, wall of constant z (xy), wall of constant x (zy)
    GLuint interior_array = 0;          // 4 families x 4 variants
    GLuint atlas = 0;
    GLuint furniture = 0;               // array of layers
    GLuint room_cubes = 0;              // cube map array, one room cube per layer (RK_IM_SHADING 3)
    ParaboloidTexture env_paraboloid;
};

void set_u(GLuint prog, const char* name, float v) { glProgramUniform1f(prog, glGetUniformLocation(prog, name), v); }
void set_u(GLuint prog, const char* name, glm::vec3 v) { glProgramUniform3fv(prog, glGetUniformLocation(prog, name), 1, glm::value_ptr(v)); }
void set_u(GLuint prog, const char* name, const glm::mat4& m)
{
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, name), 1, GL_FALSE, glm::value_ptr(m));
}

// Uniforms of the bench's own shaders (building.vert, plain.frag, thesis_im.frag,
// raykit_building.{vert,frag}); names a program does not have are ignored (location -1).
void set_bench_uniforms(GLuint prog, const Camera& cam, glm::vec3 room, float dp_guard)
{
    set_u(prog, "u_room_size", room);
    set_u(prog, "u_grid_origin", glm::vec3(0.0f));
    set_u(prog, "u_wall_jitter", glm::vec3(0.5f, 0.0f, 0.5f));
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_seed"), 1234u);
    set_u(prog, "u_lit_probability", 0.7f);
    set_u(prog, "u_fade_start", 160.0f);
    set_u(prog, "u_fade_end", 260.0f);
    set_u(prog, "u_interior_average", glm::vec3(0.62f, 0.56f, 0.5f));
    set_u(prog, "u_dp_guard", dp_guard);
    set_u(prog, "u_view_proj", cam.view_proj);
    set_u(prog, "u_model", glm::mat4(1.0f));
    set_u(prog, "u_cam_world", cam.pos);
    set_u(prog, "u_uv_multiplier", 1.0f);
    set_u(prog, "u_cam_obj", cam.pos);   // the model matrix is the identity
    set_u(prog, "u_wall_freq", glm::vec3(1.0f) / room);
}

// The raykit material's interface: filled in from samples/common/interior_building.{vert,frag}.
// Uniforms of samples/common/interior_building.{vert,frag} (the sample material; every uniform
// there has a usable default, only what differs from it is set).
void set_raykit_uniforms(GLuint prog, const Camera& cam, glm::vec3 room, float dp_guard)
{
    set_u(prog, "u_world_from_object", glm::mat4(1.0f));
    set_u(prog, "u_clip_from_world", cam.view_proj);
    set_u(prog, "u_camera_world", cam.pos);
    set_u(prog, "u_room_size", room);
    set_u(prog, "u_grid_origin", glm::vec3(0.0f));
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_seed"), 1234u);
    set_u(prog, "u_lit_probability", 0.7f);
    const float r = std::min(room.x, room.z);
    glProgramUniform4f(prog, glGetUniformLocation(prog, "u_furniture_depth"), 0.15f * r, 0.35f * r, 0.55f * r, 0.75f * r);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_flipbook_fps"), 0.0f);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_fade_range"), 160.0f, 260.0f);
    set_u(prog, "u_env_guard_scale", dp_guard);
}

// Texture units of interior_building.frag: 0 facade, 1 ceiling, 2 floor, 3 walls of constant x,
// 4 walls of constant z, 5 rooms (array / atlas / cube array by RK_IM_SHADING), 6 sprites,
// 7 dual-paraboloid environment.
void bind_raykit_textures(const Textures& t, int shading)
{
    glBindTextureUnit(0, t.facade);
    glBindTextureUnit(1, t.interior[0]);
    glBindTextureUnit(2, t.interior[1]);
    glBindTextureUnit(3, t.interior[3]);
    glBindTextureUnit(4, t.interior[2]);
    glBindTextureUnit(5, shading == 1 ? t.interior_array : shading == 2 ? t.atlas : shading == 3 ? t.room_cubes : 0);
    glBindTextureUnit(6, t.furniture);
    glBindTextureUnit(7, t.env_paraboloid.tex);
}

void bind_bench_textures(const Textures& t)
{
    glBindTextureUnit(0, t.facade);
    for (GLuint i = 0; i < 4; ++i) glBindTextureUnit(1 + i, t.interior[i]);
    glBindTextureUnit(5, t.env_cube);
    glBindTextureUnit(6, t.interior_array);
    glBindTextureUnit(7, t.atlas);
    glBindTextureUnit(8, t.furniture);
    glBindTextureUnit(9, t.env_paraboloid.tex);
}

// ---------------------------------------------------------------------------------------------
// Rendering and timing.

class Target {
public:
    Target(int w, int h) : w_(w), h_(h)
    {
        glCreateTextures(GL_TEXTURE_2D, 1, &color_);
        glTextureStorage2D(color_, 1, GL_RGBA8, w, h);
        glCreateRenderbuffers(1, &depth_);
        glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT24, w, h);
        glCreateFramebuffers(1, &fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
        glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("incomplete framebuffer");
        }
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, w, h);
    }
    ~Target()
    {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &fbo_);
        glDeleteRenderbuffers(1, &depth_);
        glDeleteTextures(1, &color_);
    }
    Target(const Target&) = delete;
    Target& operator=(const Target&) = delete;

    std::vector<unsigned char> read_rgba8_top_first() const
    {
        std::vector<unsigned char> px(static_cast<size_t>(w_) * static_cast<size_t>(h_) * 4u);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, w_, h_, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        std::vector<unsigned char> out(px.size());
        const size_t row = static_cast<size_t>(w_) * 4u;
        for (int y = 0; y < h_; ++y) {
            std::memcpy(&out[static_cast<size_t>(y) * row], &px[static_cast<size_t>(h_ - 1 - y) * row], row);
        }
        return out;
    }

private:
    int w_, h_;
    GLuint color_ = 0, depth_ = 0, fbo_ = 0;
};

class Renderer {
public:
    Renderer(const Mesh& mesh, const Textures& tex) : mesh_(mesh), tex_(tex)
    {
        glCreateQueries(GL_TIME_ELAPSED, 1, &timer_);
        glCreateQueries(GL_SAMPLES_PASSED, 1, &samples_);
    }
    ~Renderer()
    {
        glDeleteQueries(1, &timer_);
        glDeleteQueries(1, &samples_);
    }
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    Sample frame(const Material& m, bool prepass, const Camera& cam, glm::vec3 room)
    {
        glBindVertexArray(mesh_.vao);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glClearColor(0.55f, 0.65f, 0.8f, 1.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        set_uniforms(m, m.color_prog, cam, room);
        if (prepass) set_uniforms(m, m.depth_prog, cam, room);
        if (m.kind == Kind::raykit) {
            bind_raykit_textures(tex_, m.shading);
        } else {
            bind_bench_textures(tex_);
        }
        glFinish();

        const auto t0 = std::chrono::steady_clock::now();
        glBeginQuery(GL_TIME_ELAPSED, timer_);
        if (prepass) {
            glUseProgram(m.depth_prog);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glDepthFunc(GL_LESS);
            glDrawElements(GL_TRIANGLES, mesh_.index_count, GL_UNSIGNED_INT, nullptr);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDepthMask(GL_FALSE);
            glDepthFunc(GL_EQUAL);
        } else {
            glDepthFunc(GL_LESS);
        }
        glUseProgram(m.color_prog);
        glBeginQuery(GL_SAMPLES_PASSED, samples_);
        glDrawElements(GL_TRIANGLES, mesh_.index_count, GL_UNSIGNED_INT, nullptr);
        glEndQuery(GL_SAMPLES_PASSED);
        glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        const auto t1 = std::chrono::steady_clock::now();

        GLuint64 ns = 0, frags = 0;
        glGetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
        glGetQueryObjectui64v(samples_, GL_QUERY_RESULT, &frags);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
        Sample s;
        s.gpu_ms = static_cast<double>(ns) * 1e-6;
        s.wall_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
        s.fragments = frags;
        return s;
    }

private:
    void set_uniforms(const Material& m, GLuint prog, const Camera& cam, glm::vec3 room)
    {
        if (m.kind == Kind::raykit) {
            set_raykit_uniforms(prog, cam, room, tex_.env_paraboloid.guard_scale);
        } else {
            set_bench_uniforms(prog, cam, room, tex_.env_paraboloid.guard_scale);
        }
    }

    const Mesh& mesh_;
    const Textures& tex_;
    GLuint timer_ = 0, samples_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Statistics and reports.

double quantile(std::vector<double> v, double q)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<size_t>(std::floor(pos));
    const size_t hi = std::min(lo + 1, v.size() - 1);
    const double f = pos - static_cast<double>(lo);
    return v[lo] * (1.0 - f) + v[hi] * f;
}

struct Summary {
    double gpu_med = 0, gpu_q1 = 0, gpu_q3 = 0;
    double wall_med = 0, wall_q1 = 0, wall_q3 = 0;
    double ratio_gpu = 0, ratio_gpu_q1 = 0, ratio_gpu_q3 = 0;     // vs plain, same pre-pass mode
    double ratio_wall = 0, ratio_wall_q1 = 0, ratio_wall_q3 = 0;
    double ratio_gpu_vs_plain_nopre = 0;                          // vs plain without pre-pass
    double fragments = 0;                                        // median colour-pass fragments
    double rooms = 0;
};

std::string fmt(double v, int prec)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", prec, v);
    return buf;
}

std::string json_escape(const std::string& s)
{
    std::string o;
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        o += c;
    }
    return o;
}

// Box-filters an RGBA8 image (top row first) down by an integer factor.
std::vector<unsigned char> downscale(const std::vector<unsigned char>& px, int w, int h, int f)
{
    const int ow = w / f, oh = h / f;
    std::vector<unsigned char> out(static_cast<size_t>(ow) * static_cast<size_t>(oh) * 4u);
    for (int y = 0; y < oh; ++y) {
        for (int x = 0; x < ow; ++x) {
            for (int c = 0; c < 4; ++c) {
                int sum = 0;
                for (int j = 0; j < f; ++j) {
                    for (int i = 0; i < f; ++i) {
                        sum += px[(static_cast<size_t>(y * f + j) * static_cast<size_t>(w) + static_cast<size_t>(x * f + i)) * 4u + static_cast<size_t>(c)];
                    }
                }
                out[(static_cast<size_t>(y) * static_cast<size_t>(ow) + static_cast<size_t>(x)) * 4u + static_cast<size_t>(c)] =
                    static_cast<unsigned char>(sum / (f * f));
            }
        }
    }
    return out;
}

// The images side by side in a grid of up to 2 columns, each panel box-filtered down to at most
// 400 pixels wide (the PNG goes into docs/).
void write_png_strip(const std::string& path, std::vector<std::vector<unsigned char>> images, int w, int h)
{
    const int f = std::max(1, (w + 399) / 400);
    if (f > 1) {
        for (auto& im : images) im = downscale(im, w, h, f);
        w /= f;
        h /= f;
    }
    const int cols = images.size() > 1 ? 2 : 1;
    const int rows = static_cast<int>((images.size() + 1) / 2);
    std::vector<unsigned char> out(static_cast<size_t>(w * cols) * static_cast<size_t>(h * rows) * 4u, 255);
    for (size_t k = 0; k < images.size(); ++k) {
        const int ox = static_cast<int>(k % 2) * w, oy = static_cast<int>(k / 2) * h;
        for (int y = 0; y < h; ++y) {
            std::memcpy(&out[(static_cast<size_t>(oy + y) * static_cast<size_t>(w * cols) + static_cast<size_t>(ox)) * 4u],
                        &images[k][static_cast<size_t>(y) * static_cast<size_t>(w) * 4u], static_cast<size_t>(w) * 4u);
        }
    }
    if (!rkgl::write_png_rgba8(path, w * cols, h * rows, out.data())) {
        throw std::runtime_error("cannot write " + path);
    }
}

// The 1-minute load average (Linux /proc/loadavg), "?" elsewhere: other jobs on the machine.
std::string load_average()
{
    std::ifstream f("/proc/loadavg");
    std::string v;
    if (!(f >> v)) return "?";
    return v;
}

int distinct_colours(const std::vector<unsigned char>& px)
{
    std::vector<std::uint32_t> c;
    for (size_t i = 0; i + 3 < px.size(); i += 4) {
        c.push_back(std::uint32_t(px[i]) | std::uint32_t(px[i + 1]) << 8 | std::uint32_t(px[i + 2]) << 16);
    }
    std::sort(c.begin(), c.end());
    return static_cast<int>(std::unique(c.begin(), c.end()) - c.begin());
}

// ---------------------------------------------------------------------------------------------

std::vector<Material> material_list(std::string& note);   // defined below

int run(const Options& opt)
{
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) {
        return rkgl::no_context_exit("bench_interior_gl", ctx.error());
    }
    const std::string renderer = ctx.renderer();
    std::printf("renderer: %s\n", renderer.c_str());

    // Materials.
    std::string raykit_note;
    std::vector<Material> materials = material_list(raykit_note);
    if (!raykit_note.empty()) {
        std::printf("raykit material: %s\n", raykit_note.c_str());
        if (opt.require_raykit) throw std::runtime_error("--require-raykit: " + raykit_note);
    }
    const std::string depth_frag = load(std::string(BENCH_GL_DIR) + "/depth_only.frag", {});
    for (Material& m : materials) {
        const std::string vert = load(m.vert_path, m.defines);
        m.color_prog = rkgl::build_program({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, load(m.frag_path, m.defines)}});
        m.depth_prog = rkgl::build_program({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, depth_frag}});
    }
    auto find_material = [&](const std::string& name) -> long {
        for (size_t i = 0; i < materials.size(); ++i) {
            if (materials[i].name == name) return static_cast<long>(i);
        }
        return -1;
    };

    // Configurations.
    std::vector<Config> configs;
    auto add_config = [&](const std::string& mat, bool prepass, double rooms, const std::string& group) {
        const long mi = find_material(mat);
        if (mi < 0) return;
        Config c;
        c.material = static_cast<size_t>(mi);
        c.prepass = prepass;
        c.rooms_target = rooms;
        c.group = group;
        c.name = mat + (prepass ? " +prepass" : "");
        if (group == "rooms") {
            char buf[64];
            std::snprintf(buf, sizeof buf, " rooms=%.0e", rooms);
            c.name += buf;
        }
        if (!opt.only.empty() && mat != "plain") {
            bool match = false;
            size_t start = 0;
            while (start <= opt.only.size()) {
                size_t comma = opt.only.find(',', start);
                if (comma == std::string::npos) comma = opt.only.size();
                const std::string entry = opt.only.substr(start, comma - start);
                if (!entry.empty() && entry[0] == '=') match = match || c.name == entry.substr(1);
                else if (!entry.empty()) match = match || c.name.find(entry) != std::string::npos;
                start = comma + 1;
            }
            if (!match) return;
        }
        configs.push_back(c);
    };
    const char* main_mats[] = {"plain", "thesis", "rk_min", "rk_full"};
    for (bool pre : {false, true}) {
        for (const char* m : main_mats) add_config(m, pre, kBaseRoomsPerBuilding, "main");
    }
    if (!opt.smoke) {
        for (double rooms : {1e4, 1e5, 1e6, 4e6}) {
            for (const char* m : {"thesis", "rk_min", "rk_full"}) add_config(m, false, rooms, "rooms");
        }
        for (const Material& m : materials) {
            const bool main_material = m.name == "plain" || m.name == "thesis" || m.name == "rk_min" || m.name == "rk_full";
            if (!main_material) add_config(m.name, false, kBaseRoomsPerBuilding, "features");
        }
    }

    Mesh mesh = make_city();
    Textures tex;
    tex.facade = make_texture_2d(make_facade(128), GL_REPEAT);
    std::vector<Image> variants;
    for (int kind = 0; kind < 4; ++kind) {
        tex.interior[static_cast<size_t>(kind)] = make_texture_2d(make_interior(kind, 0, 256), GL_REPEAT);
    }
    // Layer = family * 4 + variant; family 0 ceiling, 1 floor, 2 wall xy, 3 wall zy.
    for (int kind = 0; kind < 4; ++kind) {
        for (int v = 0; v < 4; ++v) variants.push_back(make_interior(kind, v, 256));
    }
    tex.interior_array = make_texture_array(variants, GL_REPEAT);
    tex.atlas = make_texture_2d(make_atlas(variants, 4, 8), GL_CLAMP_TO_EDGE);
    std::vector<Image> furn;
    for (int l = 0; l < 4; ++l) furn.push_back(make_furniture(l, 256));
    tex.furniture = make_texture_array(furn, GL_CLAMP_TO_EDGE);
    tex.env_cube = make_env_cube(64);
    tex.room_cubes = make_room_cubes(variants, 4, 128);
    tex.env_paraboloid = make_env_paraboloid(128, 4.0f);

    Target target(opt.width, opt.height);
    Renderer renderer_obj(mesh, tex);
    const float aspect = static_cast<float>(opt.width) / static_cast<float>(opt.height);
    const int poses = opt.poses;

    // Warm-up: every configuration renders a couple of frames (shader compilation, caches).
    for (int w = 0; w < std::max(opt.warmup, 1); ++w) {
        for (const Config& c : configs) {
            renderer_obj.frame(materials[c.material], c.prepass, camera_at(w, poses, aspect), room_size_for(c.rooms_target));
        }
    }

    std::vector<std::vector<Sample>> samples(configs.size());
    const std::string load_start = load_average();
    const auto bench_start = std::chrono::steady_clock::now();
    for (int r = 0; r < opt.rounds; ++r) {
        const Camera cam = camera_at(r % poses, poses, aspect);
        for (size_t k = 0; k < configs.size(); ++k) {
            const size_t ci = (k + static_cast<size_t>(r)) % configs.size();
            const Config& c = configs[ci];
            samples[ci].push_back(renderer_obj.frame(materials[c.material], c.prepass, cam, room_size_for(c.rooms_target)));
        }
        std::fprintf(stderr, "round %d/%d done\n", r + 1, opt.rounds);
    }
    const double bench_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - bench_start).count();
    const std::string load_end = load_average();

    // Summaries and ratios (per round, against plain with the same pre-pass mode).
    auto plain_index = [&](bool prepass) -> long {
        for (size_t i = 0; i < configs.size(); ++i) {
            if (materials[configs[i].material].name == "plain" && configs[i].prepass == prepass) return static_cast<long>(i);
        }
        return -1;
    };
    std::vector<Summary> sums(configs.size());
    for (size_t i = 0; i < configs.size(); ++i) {
        std::vector<double> g, w, rg, rw, rg0, fr;
        const long pi = plain_index(configs[i].prepass);
        const long p0 = plain_index(false);
        for (size_t r = 0; r < samples[i].size(); ++r) {
            const Sample& s = samples[i][r];
            g.push_back(s.gpu_ms);
            w.push_back(s.wall_ms);
            fr.push_back(static_cast<double>(s.fragments));
            if (pi >= 0) {
                const Sample& p = samples[static_cast<size_t>(pi)][r];
                rg.push_back(s.gpu_ms / std::max(p.gpu_ms, 1e-9));
                rw.push_back(s.wall_ms / std::max(p.wall_ms, 1e-9));
            }
            if (p0 >= 0) rg0.push_back(s.gpu_ms / std::max(samples[static_cast<size_t>(p0)][r].gpu_ms, 1e-9));
        }
        Summary& S = sums[i];
        S.gpu_med = quantile(g, 0.5);
        S.gpu_q1 = quantile(g, 0.25);
        S.gpu_q3 = quantile(g, 0.75);
        S.wall_med = quantile(w, 0.5);
        S.wall_q1 = quantile(w, 0.25);
        S.wall_q3 = quantile(w, 0.75);
        S.ratio_gpu = quantile(rg, 0.5);
        S.ratio_gpu_q1 = quantile(rg, 0.25);
        S.ratio_gpu_q3 = quantile(rg, 0.75);
        S.ratio_wall = quantile(rw, 0.5);
        S.ratio_wall_q1 = quantile(rw, 0.25);
        S.ratio_wall_q3 = quantile(rw, 0.75);
        S.ratio_gpu_vs_plain_nopre = quantile(rg0, 0.5);
        S.fragments = quantile(fr, 0.5);
        S.rooms = rooms_per_building(room_size_for(configs[i].rooms_target));
    }

    // Console table.
    std::printf("%-34s %10s %10s %8s %8s %12s\n", "configuration", "gpu ms", "wall ms", "x plain", "x(wall)", "fragments");
    for (size_t i = 0; i < configs.size(); ++i) {
        const Summary& S = sums[i];
        std::printf("%-34s %10.3f %10.3f %8.2f %8.2f %12.0f\n", configs[i].name.c_str(), S.gpu_med, S.wall_med, S.ratio_gpu,
                    S.ratio_wall, S.fragments);
    }
    std::printf("benchmark loop: %.1f s\n", bench_s);

    // Sanity checks (the smoke test's assertions): every configuration shaded fragments and took
    // a finite positive time; each material's image is not flat and has no NaN-black holes beyond
    // what the scene has (checked loosely: more than 8 distinct colours at any size >= 64 x 48).
    int failures = 0;
    for (size_t i = 0; i < configs.size(); ++i) {
        const Summary& S = sums[i];
        if (!(S.fragments > 0.0) || !std::isfinite(S.gpu_med) || !std::isfinite(S.wall_med) || !(S.wall_med > 0.0)) {
            std::fprintf(stderr, "FAIL: %s shaded %.0f fragments in %.3f ms\n", configs[i].name.c_str(), S.fragments, S.wall_med);
            ++failures;
        }
    }
    std::vector<std::vector<unsigned char>> images;
    std::vector<std::string> image_names;
    for (const Material& m : materials) {
        if (m.name != "plain" && m.name != "thesis" && m.name != "rk_min" && m.name != "rk_full") continue;
        renderer_obj.frame(m, false, camera_at(0, 4, aspect), room_size_for(kBaseRoomsPerBuilding));
        images.push_back(target.read_rgba8_top_first());
        image_names.push_back(m.name);
        const int n = distinct_colours(images.back());
        if (n <= 8) {
            std::fprintf(stderr, "FAIL: material %s renders a flat image (%d colours)\n", m.name.c_str(), n);
            ++failures;
        }
    }
    if (!opt.png.empty()) {
        write_png_strip(opt.png, images, opt.width, opt.height);
        std::string order;
        for (const std::string& n : image_names) order += (order.empty() ? "" : ", ") + n;
        std::printf("wrote %s (%s, left to right, top to bottom)\n", opt.png.c_str(), order.c_str());
    }

    // JSON.
    if (!opt.json.empty()) {
        std::ofstream f(opt.json);
        f << "{\n  \"renderer\": \"" << json_escape(renderer) << "\",\n";
        f << "  \"width\": " << opt.width << ", \"height\": " << opt.height << ", \"rounds\": " << opt.rounds
          << ", \"poses\": " << opt.poses << ", \"warmup\": " << opt.warmup << ", \"buildings\": " << mesh.buildings
          << ", \"triangles\": " << mesh.index_count / 3 << ", \"loop_seconds\": " << fmt(bench_s, 2)
          << ", \"load\": [\"" << load_start << "\", \"" << load_end << "\"], \"cpus\": " << std::thread::hardware_concurrency() << ",\n";
        f << "  \"materials\": [\n";
        for (size_t i = 0; i < materials.size(); ++i) {
            f << "    {\"name\": \"" << json_escape(materials[i].name) << "\", \"features\": \"" << json_escape(materials[i].features)
              << "\", \"defines\": \"";
            for (const auto& d : materials[i].defines) f << d.name << "=" << d.value << " ";
            f << "\"}" << (i + 1 < materials.size() ? "," : "") << "\n";
        }
        f << "  ],\n  \"configs\": [\n";
        for (size_t i = 0; i < configs.size(); ++i) {
            const Summary& S = sums[i];
            f << "    {\"name\": \"" << json_escape(configs[i].name) << "\", \"material\": \"" << materials[configs[i].material].name
              << "\", \"group\": \"" << configs[i].group << "\", \"prepass\": " << (configs[i].prepass ? "true" : "false")
              << ", \"rooms_per_building\": " << fmt(S.rooms, 0)
              << ", \"gpu_ms\": {\"median\": " << fmt(S.gpu_med, 4) << ", \"q1\": " << fmt(S.gpu_q1, 4) << ", \"q3\": " << fmt(S.gpu_q3, 4) << "}"
              << ", \"wall_ms\": {\"median\": " << fmt(S.wall_med, 4) << ", \"q1\": " << fmt(S.wall_q1, 4) << ", \"q3\": " << fmt(S.wall_q3, 4) << "}"
              << ", \"ratio_gpu\": {\"median\": " << fmt(S.ratio_gpu, 4) << ", \"q1\": " << fmt(S.ratio_gpu_q1, 4) << ", \"q3\": " << fmt(S.ratio_gpu_q3, 4) << "}"
              << ", \"ratio_wall\": {\"median\": " << fmt(S.ratio_wall, 4) << ", \"q1\": " << fmt(S.ratio_wall_q1, 4) << ", \"q3\": " << fmt(S.ratio_wall_q3, 4) << "}"
              << ", \"ratio_gpu_vs_plain_no_prepass\": " << fmt(S.ratio_gpu_vs_plain_nopre, 4)
              << ", \"fragments\": " << fmt(S.fragments, 0) << ", \"gpu_ms_per_round\": [";
            for (size_t r = 0; r < samples[i].size(); ++r) f << (r ? ", " : "") << fmt(samples[i][r].gpu_ms, 4);
            f << "], \"wall_ms_per_round\": [";
            for (size_t r = 0; r < samples[i].size(); ++r) f << (r ? ", " : "") << fmt(samples[i][r].wall_ms, 4);
            f << "]}" << (i + 1 < configs.size() ? "," : "") << "\n";
        }
        f << "  ]\n}\n";
    }
    // CSV.
    if (!opt.csv.empty()) {
        std::ofstream f(opt.csv);
        f << "config,material,group,prepass,rooms_per_building,gpu_ms_median,gpu_ms_q1,gpu_ms_q3,wall_ms_median,wall_ms_q1,"
             "wall_ms_q3,ratio_gpu,ratio_gpu_q1,ratio_gpu_q3,ratio_wall,ratio_wall_q1,ratio_wall_q3,fragments\n";
        for (size_t i = 0; i < configs.size(); ++i) {
            const Summary& S = sums[i];
            f << configs[i].name << "," << materials[configs[i].material].name << "," << configs[i].group << ","
              << (configs[i].prepass ? 1 : 0) << "," << fmt(S.rooms, 0) << "," << fmt(S.gpu_med, 4) << "," << fmt(S.gpu_q1, 4)
              << "," << fmt(S.gpu_q3, 4) << "," << fmt(S.wall_med, 4) << "," << fmt(S.wall_q1, 4) << "," << fmt(S.wall_q3, 4)
              << "," << fmt(S.ratio_gpu, 4) << "," << fmt(S.ratio_gpu_q1, 4) << "," << fmt(S.ratio_gpu_q3, 4) << ","
              << fmt(S.ratio_wall, 4) << "," << fmt(S.ratio_wall_q1, 4) << "," << fmt(S.ratio_wall_q3, 4) << ","
              << fmt(S.fragments, 0) << "\n";
        }
    }
    // Markdown tables.
    if (!opt.md.empty()) {
        std::ofstream f(opt.md);
        f << "Renderer: `" << renderer << "`; " << opt.width << "x" << opt.height << ", " << mesh.buildings << " buildings ("
          << mesh.index_count / 3 << " triangles, one draw call per pass), " << opt.rounds << " measured frames per configuration (" << opt.poses << " camera poses "
          << "along the path, swept " << opt.rounds / opt.poses << " time(s); configurations interleaved) after " << std::max(opt.warmup, 1) << " warm-up round(s); loop " << fmt(bench_s, 1)
          << " s.\n\n";
        auto table = [&](const std::string& group, const std::string& title) {
            bool any = false;
            for (const Config& c : configs) any = any || c.group == group;
            if (!any) return;
            f << "**" << title << "**\n\n";
            f << "| configuration | rooms / building | GPU ms (median [q1, q3]) | wall ms (median [q1, q3]) | x plain, GPU time | "
                 "x plain, wall time | colour-pass fragments |\n";
            f << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
            for (size_t i = 0; i < configs.size(); ++i) {
                if (configs[i].group != group && !(group != "main" && materials[configs[i].material].name == "plain" && !configs[i].prepass)) continue;
                const Summary& S = sums[i];
                f << "| " << configs[i].name << " | " << fmt(S.rooms, 0) << " | " << fmt(S.gpu_med, 2) << " [" << fmt(S.gpu_q1, 2) << ", "
                  << fmt(S.gpu_q3, 2) << "] | " << fmt(S.wall_med, 2) << " [" << fmt(S.wall_q1, 2) << ", " << fmt(S.wall_q3, 2) << "] | "
                  << fmt(S.ratio_gpu, 2) << " [" << fmt(S.ratio_gpu_q1, 2) << ", " << fmt(S.ratio_gpu_q3, 2) << "] | " << fmt(S.ratio_wall, 2)
                  << " [" << fmt(S.ratio_wall_q1, 2) << ", " << fmt(S.ratio_wall_q3, 2) << "] | " << fmt(S.fragments, 0) << " |\n";
            }
            f << "\n";
        };
        table("main", "Materials, without and with a depth pre-pass (ratios against plain in the same mode)");
        table("rooms", "Room count (room size shrinks on the same buildings; no pre-pass)");
        table("features", "Feature attribution (no pre-pass): rk_full minus one feature, rk_min plus one feature");
        f << "| material | features | defines |\n| --- | --- | --- |\n";
        for (const Material& m : materials) {
            f << "| " << m.name << " | " << m.features << " | ";
            for (const auto& d : m.defines) f << "`" << d.name << "=" << d.value << "` ";
            f << "|\n";
        }
    }
    if (failures) {
        std::fprintf(stderr, "bench_interior_gl: %d sanity check(s) failed\n", failures);
        return 1;
    }
    return 0;
}

// ---------------------------------------------------------------------------------------------
// The raykit material (the sample material, samples/common/interior_building.{vert,frag}).

void add_raykit_materials(std::vector<Material>& out, const std::string& vert, const std::string& frag);

/// base with the macro name set to value (replaced when present, appended otherwise).
std::vector<raykit::ShaderDefine> with(std::vector<raykit::ShaderDefine> base, const std::string& name, const std::string& value)
{
    for (auto& d : base) {
        if (d.name == name) {
            d.value = value;
            return base;
        }
    }
    base.push_back({name, value});
    return base;
}

/// Every material the benchmark knows, without GL objects (so --list-materials and --dump-frag
/// work without a context). `note` says why the raykit materials are missing, if they are.
std::vector<Material> material_list(std::string& note)
{
    std::vector<Material> out;
    const std::string bench_dir = BENCH_GL_DIR;
    auto add = [&](const std::string& name, Kind kind, const std::string& frag, const std::string& features) {
        Material m;
        m.name = name;
        m.kind = kind;
        m.vert_path = bench_dir + "/building.vert";
        m.frag_path = bench_dir + "/" + frag;
        m.features = features;
        out.push_back(m);
    };
    add("plain", Kind::plain, "plain.frag", "facade texture + cube-map reflection in the windows");
    add("thesis", Kind::thesis, "thesis_im.frag", "thesis appendix port: 4 textures, cube reflection added");
    const std::string dir = SAMPLES_COMMON_DIR;
    const std::string vert = dir + "/interior_building.vert", frag = dir + "/interior_building.frag";
    const bool sample_material = file_exists(frag) && file_exists(vert);
    if (!sample_material) {
        note = "samples/common/interior_building.{vert,frag} not found: the rk_* variants use bench/gl/raykit_building.frag";
    } else {
        add_raykit_materials(out, vert, frag);
    }
    // The bench's own raykit material: rk_* when the sample material is absent, rkb_* otherwise.
    const std::string prefix = sample_material ? "rkb_" : "rk_";
    using D = std::vector<raykit::ShaderDefine>;
    const D full = {{"RK_IM_SHADING", "1"}, {"RK_IM_ROOM_LIGHTS", "1"}, {"RK_IM_FURNITURE_LAYERS", "2"},
                    {"RK_IM_REFLECTION", "1"}, {"RK_IM_FADE", "1"}};
    auto add_rk = [&](const std::string& name, const D& defines, const std::string& features) {
        Material m;
        m.name = prefix + name;
        m.kind = Kind::thesis;   // the bench's uniforms and texture units
        m.vert_path = bench_dir + "/raykit_building.vert";
        m.frag_path = bench_dir + "/raykit_building.frag";
        m.defines = defines;
        m.features = "bench/gl/raykit_building.frag: " + features;
        out.push_back(m);
    };
    if (sample_material) {
        // Only what the sample material cannot show: the opaque-texel skip, textureGrad vs
        // implicit LOD, and the reflection's derivatives.
        add_rk("min", {}, "minimal: four textures, no reflection, all features off");
        add_rk("full", full, "texture array, room lights, 2 furniture planes, Fresnel dual-paraboloid reflection, fade");
        add_rk("min-skip", {{"BENCH_SKIP_OPAQUE", "0"}}, "rkb_min tracing opaque facade texels too");
        add_rk("full-skip", with(full, "BENCH_SKIP_OPAQUE", "0"), "rkb_full tracing opaque facade texels too");
        add_rk("min~implicit", {{"BENCH_IMPLICIT_LOD", "1"}}, "rkb_min with implicit-LOD texture() instead of textureGrad");
        add_rk("full~implicit", with(full, "BENCH_IMPLICIT_LOD", "1"), "rkb_full with implicit-LOD texture() instead of textureGrad");
        add_rk("full~reflectlod", with(full, "BENCH_REFLECTION_LOD", "1"), "rkb_full with the reflection at LOD 0 (no derivatives)");
        return out;
    }
    add_rk("min", {}, "minimal: four textures, no reflection, all features off");
    add_rk("full", full, "texture array, room lights, 2 furniture planes, Fresnel dual-paraboloid reflection, fade");
    add_rk("full-array", with(full, "RK_IM_SHADING", "0"), "rk_full with four textures instead of the array");
    add_rk("full~atlas", with(full, "RK_IM_SHADING", "2"), "rk_full with the padded atlas instead of the array");
    add_rk("full-lights", with(full, "RK_IM_ROOM_LIGHTS", "0"), "rk_full without room lights");
    add_rk("full-furniture", with(full, "RK_IM_FURNITURE_LAYERS", "0"), "rk_full without furniture");
    add_rk("full-reflection", with(full, "RK_IM_REFLECTION", "0"), "rk_full without the reflection");
    add_rk("full-fade", with(full, "RK_IM_FADE", "0"), "rk_full without the fade");
    add_rk("full-skip", with(full, "BENCH_SKIP_OPAQUE", "0"), "rk_full tracing opaque facade texels too");
    add_rk("full~fastfresnel", with(full, "RK_WINDOW_GLASS_FRESNEL", "1"), "rk_full with the fast Fresnel approximation");
    add_rk("full~reflectlod", with(full, "BENCH_REFLECTION_LOD", "1"), "rk_full with the reflection at LOD 0 (no derivatives)");
    add_rk("full~lean",
           {{"RK_IM_SHADING", "1"}, {"RK_IM_ROOM_LIGHTS", "1"}, {"RK_IM_FURNITURE_LAYERS", "1"}, {"RK_IM_REFLECTION", "1"},
            {"BENCH_REFLECTION_LOD", "1"}},
           "rk_full with 1 furniture plane, the reflection at LOD 0 and no fade");
    add_rk("full+walls", with(full, "RK_IM_VARYING_WALLS", "1"), "rk_full with varying wall positions");
    add_rk("min+array", {{"RK_IM_SHADING", "1"}}, "rk_min with the texture array");
    add_rk("min+atlas", {{"RK_IM_SHADING", "2"}}, "rk_min with the atlas");
    add_rk("min+lights", {{"RK_IM_ROOM_LIGHTS", "1"}}, "rk_min with room lights");
    add_rk("min+furniture1", {{"RK_IM_FURNITURE_LAYERS", "1"}}, "rk_min with 1 furniture plane");
    add_rk("min+furniture2", {{"RK_IM_FURNITURE_LAYERS", "2"}}, "rk_min with 2 furniture planes");
    add_rk("min+reflection", {{"RK_IM_REFLECTION", "1"}}, "rk_min with the Fresnel reflection");
    add_rk("min+fade", {{"RK_IM_FADE", "1"}}, "rk_min with the fade");
    add_rk("min+walls", {{"RK_IM_VARYING_WALLS", "1"}}, "rk_min with varying wall positions");
    add_rk("min-skip", {{"BENCH_SKIP_OPAQUE", "0"}}, "rk_min tracing opaque facade texels too");
    add_rk("min~implicit", {{"BENCH_IMPLICIT_LOD", "1"}}, "rk_min with implicit-LOD texture() instead of textureGrad");
    add_rk("full~implicit", with(full, "BENCH_IMPLICIT_LOD", "1"), "rk_full with implicit-LOD texture() instead of textureGrad");
    return out;
}

// The sample material, samples/common/interior_building.{vert,frag}, with the facade texture
// (RK_IM_BUILDING_FACADE 1, the same facade as plain and thesis) and linear output.
void add_raykit_materials(std::vector<Material>& out, const std::string& vert, const std::string& frag)
{
    using D = std::vector<raykit::ShaderDefine>;
    // The bench's sprites are single images (no flipbook): RK_IM_FURNITURE_FLIPBOOK 0, as
    // raykit::interior_defines emits for InteriorSceneDesc::furniture_flipbook = false.
    // rk_min names RK_IM_SHADING 0 (four textures, as the thesis) explicitly: the library's default
    // is the texture array.
    const D min = {{"RK_IM_BUILDING_FACADE", "1"}, {"RK_IM_SHADING", "0"}, {"RK_IM_FURNITURE_FLIPBOOK", "0"}};
    const D full = {{"RK_IM_BUILDING_FACADE", "1"}, {"RK_IM_SHADING", "1"}, {"RK_IM_ROOM_LIGHTS", "1"},
                    {"RK_IM_FURNITURE_LAYERS", "2"}, {"RK_IM_FURNITURE_FLIPBOOK", "0"}, {"RK_IM_REFLECTION", "1"},
                    {"RK_IM_FADE", "1"}};
    auto add = [&](const std::string& name, const D& defines, const std::string& features) {
        Material m;
        m.name = "rk_" + name;
        m.kind = Kind::raykit;
        m.vert_path = vert;
        m.frag_path = frag;
        m.defines = defines;
        m.features = "samples/common/interior_building.frag: " + features;
        m.shading = 1;  // interior_shading.glsl's default (the texture array) unless a define says otherwise
        for (const auto& d : defines) {
            if (d.name == "RK_IM_SHADING") m.shading = std::atoi(d.value.c_str());
        }
        out.push_back(m);
    };
    add("min", min, "minimal: four textures, flat sky colour in Fresnel glass, all features off");
    add("full", full, "texture array, room lights, 2 furniture planes, Fresnel dual-paraboloid reflection, fade");
    add("full-array", with(full, "RK_IM_SHADING", "0"), "rk_full with four textures instead of the array");
    add("full~atlas", with(full, "RK_IM_SHADING", "2"), "rk_full with the padded atlas instead of the array");
    add("full~cube", with(full, "RK_IM_SHADING", "3"), "rk_full with a cube map per room instead of the array");
    add("full-lights", with(full, "RK_IM_ROOM_LIGHTS", "0"), "rk_full without room lights");
    add("full-furniture", with(full, "RK_IM_FURNITURE_LAYERS", "0"), "rk_full without furniture");
    add("full-reflection", with(full, "RK_IM_REFLECTION", "0"), "rk_full with a flat sky colour instead of the environment");
    add("full-fade", with(full, "RK_IM_FADE", "0"), "rk_full without the fade");
    add("full~fastfresnel", with(full, "RK_WINDOW_GLASS_FRESNEL", "1"), "rk_full with the fast Fresnel approximation");
    add("full~flipbook", with(full, "RK_IM_FURNITURE_FLIPBOOK", "1"),
        "rk_full with the per-room flipbook lookup compiled in (one-frame sheets)");
    add("full~lean", with(with(full, "RK_IM_FURNITURE_LAYERS", "1"), "RK_IM_FADE", "0"),
        "rk_full with 1 furniture plane and no fade");
    add("full+walls", with(full, "RK_IM_VARYING_WALLS", "1"), "rk_full with varying wall positions");
    add("min+array", with(min, "RK_IM_SHADING", "1"), "rk_min with the texture array");
    add("min+atlas", with(min, "RK_IM_SHADING", "2"), "rk_min with the atlas");
    add("min+lights", with(min, "RK_IM_ROOM_LIGHTS", "1"), "rk_min with room lights");
    add("min+furniture1", with(min, "RK_IM_FURNITURE_LAYERS", "1"), "rk_min with 1 furniture plane");
    add("min+furniture2", with(min, "RK_IM_FURNITURE_LAYERS", "2"), "rk_min with 2 furniture planes");
    add("min+reflection", with(min, "RK_IM_REFLECTION", "1"), "rk_min with the dual-paraboloid environment");
    add("min+fade", with(min, "RK_IM_FADE", "1"), "rk_min with the fade");
    add("min+walls", with(min, "RK_IM_VARYING_WALLS", "1"), "rk_min with varying wall positions");
    add("min~additive", with(min, "RK_IM_COMPOSE_MODE", "1"), "rk_min with the thesis's additive window instead of Fresnel");
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        // --list-materials / --dump-frag NAME: no context needed (scripts/bench_interior.sh
        // compiles each material's fragment stage to SPIR-V from this exact text).
        if (argc >= 2 && (std::string(argv[1]) == "--list-materials" || std::string(argv[1]) == "--dump-frag")) {
            std::string note;
            const std::vector<Material> mats = material_list(note);
            for (const Material& m : mats) {
                if (std::string(argv[1]) == "--list-materials") {
                    std::printf("%s\n", m.name.c_str());
                } else if (argc >= 3 && m.name == argv[2]) {
                    std::printf("%s", load(m.frag_path, m.defines).c_str());
                    return 0;
                }
            }
            if (std::string(argv[1]) == "--dump-frag") {
                std::fprintf(stderr, "bench_interior_gl: no material %s\n", argc >= 3 ? argv[2] : "(missing)");
                return 1;
            }
            return 0;
        }
        return run(parse_options(argc, argv));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_interior_gl: %s\n", e.what());
        return 1;
    }
}
