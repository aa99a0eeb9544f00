// GPU parity for shaders/raykit/volume.glsl (see parity.hpp): spans, visible length, the depth
// conversion, the opacity functions, the falloff sphere's optical depth, the sphere's edge fade and
// billboard size, the slice uv correction and alpha, on the driver against the C++ build.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/volume.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {
parity::Domain coord() { return {-4.0f, 4.0f, false, {0.0f, 1.0f, -1.0f}}; }
parity::Domain dist() { return {0.0f, 40.0f, false, {0.0f, 1.0f, 10.0f}}; }
}  // namespace

TEST(GpuParity, Volume)
{
    const char* S = "raykit/volume.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_vol_span_slab / rk_vol_span_pyramid / rk_vol_visible_length", S, (dist(), dist(), dom::signed_unit(), dom::signed_unit()), 3,
                  vec2 s = rk_vol_span_slab(a[0], 0.25f * a[1]);
                  vec2 p = rk_vol_span_pyramid(a[0], 0.25f * a[1], vec2(a[2], a[3]));
                  o[0] = rk_vol_visible_length(s, a[1], 0.5f); o[1] = rk_vol_visible_length(p, a[1], 0.0f);
                  o[2] = s.y;),
        RK_PARITY("sphere: visible length, edge fade, optical depth", S, (coord(), coord(), dist(), dom::unit()), 3,
                  vec3 d = rk_normalize_safe(vec3(0.1f * a[0], 0.1f * a[1], -1.0f), vec3(0.0f, 0.0f, -1.0f));
                  vec2 sp = rk_ray_sphere(vec3(0.0f), d, vec3(0.3f, -0.2f, -12.0f), 1.0f + a[3]);
                  o[0] = rk_vol_visible_length(sp, a[2], 0.0f);
                  o[1] = rk_vol_sphere_edge_fade(sp, 1.0f + a[3]);
                  o[2] = rk_vol_optical_depth_falloff(vec3(0.0f), d, vec3(0.3f, -0.2f, -12.0f), 1.0f + a[3], 2.0f, 0.0f, a[2]);),
        RK_PARITY("rk_vol_scene_distance / rk_vol_near_distance", S, (dom::unit(), coord(), coord()), 2,
                  vec3 d = rk_normalize_safe(vec3(0.2f * a[1], 0.2f * a[2], -1.0f), vec3(0.0f, 0.0f, -1.0f));
                  o[0] = rk_vol_scene_distance(a[0], vec3(10.0f, 0.002f, 0.0f), d);
                  o[1] = rk_vol_near_distance(0.1f, d);),
        RK_PARITY("opacity functions", S, (dist(), dom::unit()), 4,
                  o[0] = rk_vol_opacity_linear(a[0], 10.0f * a[1]); o[1] = rk_vol_opacity_log(a[0], 10.0f * a[1]);
                  o[2] = rk_vol_opacity_sqrt(a[0], 10.0f * a[1]); o[3] = rk_vol_opacity_beer(a[0], a[1]);),
        RK_PARITY("rk_vol_billboard_half_size / rk_vol_slice_alpha", S, (dom::unit(), dist(), dom::unit()), 2,
                  o[0] = rk_vol_billboard_half_size(a[0], a[1]);
                  o[1] = rk_vol_slice_alpha(a[2], uint(1.0f + 78.0f * clamp(a[0], 0.0f, 1.0f)));),
        RK_PARITY("rk_vol_slice_uv", S, (coord(), coord(), coord()), 2,
                  vec3 n = rk_normalize_safe(vec3(0.1f, 0.2f, 1.0f), vec3(0.0f, 0.0f, 1.0f));
                  vec3 au = rk_normalize_safe(cross(vec3(0.0f, 1.0f, 0.0f), n), vec3(1.0f, 0.0f, 0.0f));
                  vec3 av = cross(n, au);
                  vec2 uv = rk_vol_slice_uv(vec3(a[0], a[1], 0.3f * a[2]), vec3(0.5f, 0.5f, 12.0f), vec3(0.0f), n, au, av, vec2(2.0f, 1.5f));
                  o[0] = uv.x; o[1] = uv.y;),
    };
    for (parity::Case& c : cases) {
        // log, exp, sqrt and division: the driver's precision (GLSL leaves it to the implementation);
        // the harness's default tolerances (2e-6 absolute + 2e-5 relative).
        // On a hardware driver, the slice uv of a vertex 1e20 away cancels terms of that size: within
        // 1e-6 of the row's largest output (NVIDIA: 5.5e-10).
        if (c.name == "rk_vol_slice_uv") c.tie = parity::hw_row_scale_tie(c.n_out, 1e-6);
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}

TEST(GpuParity, VolumeMarch)
{
    // A 16^3 R32F density (a falloff sphere plus a slab), LINEAR + CLAMP_TO_EDGE on the driver,
    // VolDensityCpu's trilinear twin in C++.
    VolDensityCpu m;
    m.w = m.h = m.d = 16;
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const float px = (float(x) + 0.5f) / 8.0f - 1.0f, py = (float(y) + 0.5f) / 8.0f - 1.0f, pz = (float(z) + 0.5f) / 8.0f - 1.0f;
                m.v.push_back(std::max(0.0f, 1.0f - (px * px + py * py + pz * pz)) + (y < 3 ? 0.5f : 0.0f));
            }
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &tex);
    glTextureStorage3D(tex, 1, GL_R32F, 16, 16, 16);
    glTextureSubImage3D(tex, 0, 0, 0, 0, 16, 16, 16, GL_RED, GL_FLOAT, m.v.data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(tex, wrap, GL_CLAMP_TO_EDGE);
    glBindTextureUnit(0, tex);
    std::mt19937 rng(3u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const int rows = 4096;
    std::vector<float> in;
    for (int i = 0; i < rows; ++i) {
        in.insert(in.end(), {1.5f * u(rng), 1.5f * u(rng), 4.0f, 0.3f * u(rng), 0.3f * u(rng), -1.0f, 2.0f + 4.0f * std::abs(u(rng)), 0.5f + 0.5f * u(rng)});
    }
    const std::string src = std::string("#version 450 core\n#extension GL_GOOGLE_include_directive : require\n") +
                            "layout(local_size_x = 64) in;\n"
                            "layout(std430, binding = 0) readonly buffer In { float rk_in[]; };\n"
                            "layout(std430, binding = 1) writeonly buffer Out { float rk_out[]; };\n"
                            "layout(binding = 0) uniform sampler3D u_density;\n"
                            "#include \"raykit/volume.glsl\"\n"
                            "void main() {\n"
                            "  uint i = gl_GlobalInvocationID.x;\n"
                            "  if (i >= 4096u) return;\n"
                            "  uint b = 8u * i;\n"
                            "  vec3 d = normalize(vec3(rk_in[b + 3u], rk_in[b + 4u], rk_in[b + 5u]));\n"
                            "  rk_out[i] = rk_vol_march_box(u_density, vec3(rk_in[b], rk_in[b + 1u], rk_in[b + 2u]), d, vec3(-1.0), vec3(1.0), 0.0, rk_in[b + 6u], 1.5, 24u, rk_in[b + 7u]);\n"
                            "}\n";
    const GLuint prog =
        rkgl::build_program({{GL_COMPUTE_SHADER, rkgl::resolved_shader(src, "parity_volume_march.comp", parity::shader_dir(), {parity::shader_dir()})}});
    const GLuint bin = rkgl::make_buffer(in.size() * sizeof(float), in.data());
    const GLuint bout = rkgl::make_buffer(size_t(rows) * sizeof(float), nullptr);
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
    glDispatchCompute(rows / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<float> gpu = rkgl::read_floats(bout, size_t(rows));
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    double worst = 0.0;
    int hits = 0;
    for (int i = 0; i < rows; ++i) {
        const float* a = &in[size_t(i) * 8u];
        const vec3 d = glm::normalize(vec3(a[3], a[4], a[5]));
        const float c = rk_vol_march_box(m, vec3(a[0], a[1], a[2]), d, vec3(-1.0f), vec3(1.0f), 0.0f, a[6], 1.5f, 24u, a[7]);
        ASSERT_TRUE(std::isfinite(gpu[size_t(i)]));
        worst = std::max(worst, double(std::abs(gpu[size_t(i)] - c)));
        hits += c > 0.0f ? 1 : 0;
    }
    // A driver's trilinear weights may be fixed point (8 fractional bits: 1/256 of the texels'
    // difference per read); llvmpipe filters R32F exactly.
    std::printf("[parity] volume march: max |gpu - cpu| %.3g over %d rows (%d through the density)\n", worst, rows, hits);
    EXPECT_GT(hits, rows / 4);
    EXPECT_LT(worst, 2e-2);
    glDeleteProgram(prog);
    glDeleteBuffers(1, &bin);
    glDeleteBuffers(1, &bout);
    glDeleteTextures(1, &tex);
}
