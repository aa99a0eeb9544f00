// GPU parity for shaders/raykit/relief.glsl: every method marches a real texture on the driver (a
// 64 x 64 RG32F map, depth and cone ratio, REPEAT, LINEAR, level 0 through textureLod, in a compute
// shader) and the CPU twin (ReliefMapCpu's bilinear read) in C++, over 4096 rays. The driver's
// bilinear weights are fixed point (llvmpipe: 8 fractional bits), so a read differs by up to
// ~1/512 of a texel-to-texel step: a hit moves by a small fraction of a texel, except where the
// ray grazes a feature and one build hits it while the other passes (a discontinuity of the
// method itself). Tolerance: |Δ hit uv| <= 0.05 texel on at least 98% of the rays per method, and
// the shadow test agrees on at least 98%.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/relief.hpp"
#include "relief_reference.hpp"

using namespace raykit;

TEST(GpuParity, Relief)
{
    const int w = 64;
    const std::vector<double> d = relief_ref::test_depths(w, w, 7u);
    ReliefMapCpu cones;
    cones.width = cones.height = w;
    for (double x : d) cones.texels.push_back(vec2(float(x), 0.0f));
    ReliefMapCpu relaxed = cones;
    relief_build_cones(cones);
    relief_build_relaxed_cones(relaxed, 8);

    GLuint tex[2] = {0, 0}, smp = 0;
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    for (int k = 0; k < 2; ++k) {
        glTextureStorage2D(tex[k], 1, GL_RG32F, w, w);
        glTextureSubImage2D(tex[k], 0, 0, 0, w, w, GL_RG, GL_FLOAT, (k == 0 ? cones : relaxed).texels.data());
    }
    glCreateSamplers(1, &smp);
    glSamplerParameteri(smp, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(smp, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(smp, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glSamplerParameteri(smp, GL_TEXTURE_WRAP_T, GL_REPEAT);
    for (GLuint u = 0; u < 2; ++u) {
        glBindTextureUnit(u, tex[u]);
        glBindSampler(u, smp);
    }

    // Inputs: uv, view direction (up to 80 degrees), light direction.
    std::mt19937 rng(29u);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    const int rows = 4096;
    std::vector<float> in;
    for (int i = 0; i < rows; ++i) {
        in.push_back(-0.5f + 2.0f * U(rng));
        in.push_back(-0.5f + 2.0f * U(rng));
        for (int k = 0; k < 2; ++k) {
            const float cz = 0.18f + 0.82f * U(rng), ph = 6.2831853f * U(rng), sz = std::sqrt(1.0f - cz * cz);
            in.push_back(sz * std::cos(ph));
            in.push_back(sz * std::sin(ph));
            in.push_back(cz);
        }
    }
    const int n_out = 19;
    const std::string body =
        "  vec2 uv = vec2(rk_in[8u * i], rk_in[8u * i + 1u]);\n"
        "  vec3 v = vec3(rk_in[8u * i + 2u], rk_in[8u * i + 3u], rk_in[8u * i + 4u]);\n"
        "  vec3 l = vec3(rk_in[8u * i + 5u], rk_in[8u * i + 6u], rk_in[8u * i + 7u]);\n"
        "  vec3 r[6];\n"
        "  r[0] = rk_relief_parallax(u_cones, uv, v, 0.08);\n"
        "  r[1] = rk_relief_steep(u_cones, uv, v, 0.08, 16u);\n"
        "  r[2] = rk_relief_pom(u_cones, uv, v, 0.08, 16u);\n"
        "  r[3] = rk_relief_relief(u_cones, uv, v, 0.08, 16u, 6u);\n"
        "  r[4] = rk_relief_cone(u_cones, uv, v, 0.08, 32u);\n"
        "  r[5] = rk_relief_relaxed_cone(u_relaxed, uv, v, 0.08, 8u, 6u);\n"
        "  for (uint k = 0u; k < 6u; ++k) { rk_out[19u * i + 3u * k] = r[k].x; rk_out[19u * i + 3u * k + 1u] = r[k].y; rk_out[19u * i + 3u * k + 2u] = r[k].z; }\n"
        "  rk_out[19u * i + 18u] = rk_relief_shadow(u_cones, r[3], l, 0.08, 32u, 0.01);\n";
    const std::string src = std::string("#version 450 core\n#extension GL_GOOGLE_include_directive : require\n") +
                            "layout(local_size_x = 64) in;\n"
                            "layout(std430, binding = 0) readonly buffer In { float rk_in[]; };\n"
                            "layout(std430, binding = 1) writeonly buffer Out { float rk_out[]; };\n"
                            "layout(binding = 0) uniform sampler2D u_cones;\n"
                            "layout(binding = 1) uniform sampler2D u_relaxed;\n"
                            "#include \"raykit/relief.glsl\"\n"
                            "void main() {\n"
                            "  uint i = gl_GlobalInvocationID.x;\n"
                            "  if (i >= 4096u) return;\n" +
                            body + "}\n";
    const GLuint prog = rkgl::build_program({{GL_COMPUTE_SHADER, rkgl::resolved_shader(src, "parity_relief.comp", parity::shader_dir(), {parity::shader_dir()})}});
    const GLuint bin = rkgl::make_buffer(in.size() * sizeof(float), in.data());
    const GLuint bout = rkgl::make_buffer(size_t(rows) * size_t(n_out) * sizeof(float), nullptr);
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
    glDispatchCompute(rows / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<float> gpu = rkgl::read_floats(bout, size_t(rows) * size_t(n_out));
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));

    const char* names[6] = {"parallax", "steep 16", "pom 16", "relief 16+6", "cone 32", "relaxed 8+6"};
    double worst[6] = {0, 0, 0, 0, 0, 0};
    int beyond[6] = {0, 0, 0, 0, 0, 0}, shadow_differs = 0, non_finite = 0;
    for (int i = 0; i < rows; ++i) {
        const float* a = &in[size_t(i) * 8u];
        const vec2 uv(a[0], a[1]);
        const vec3 v(a[2], a[3], a[4]), l(a[5], a[6], a[7]);
        vec3 c[6];
        c[0] = rk_relief_parallax(cones, uv, v, 0.08f);
        c[1] = rk_relief_steep(cones, uv, v, 0.08f, 16u);
        c[2] = rk_relief_pom(cones, uv, v, 0.08f, 16u);
        c[3] = rk_relief_relief(cones, uv, v, 0.08f, 16u, 6u);
        c[4] = rk_relief_cone(cones, uv, v, 0.08f, 32u);
        c[5] = rk_relief_relaxed_cone(relaxed, uv, v, 0.08f, 8u, 6u);
        const float* g = &gpu[size_t(i) * size_t(n_out)];
        for (int k = 0; k < 6; ++k) {
            for (int j = 0; j < 3; ++j) non_finite += std::isfinite(g[3 * k + j]) ? 0 : 1;
            const double du = double(g[3 * k]) - c[k].x, dv = double(g[3 * k + 1]) - c[k].y;
            const double e = std::sqrt(du * du + dv * dv) * w;
            worst[k] = std::max(worst[k], e);
            beyond[k] += e > 0.05 ? 1 : 0;
        }
        shadow_differs += g[18] != rk_relief_shadow(cones, c[3], l, 0.08f, 32u, 0.01f) ? 1 : 0;
    }
    std::printf("[parity] relief (64^2 RG32F, REPEAT, LINEAR, %d rays): max |gpu - cpu| hit uv in texels / rays beyond 0.05 texel:\n", rows);
    for (int k = 0; k < 6; ++k) {
        std::printf("[parity]   %-12s %8.4f  %4d\n", names[k], worst[k], beyond[k]);
        EXPECT_LE(beyond[k], rows / 50) << names[k];
    }
    std::printf("[parity]   shadow (32 samples) differs on %d rays\n", shadow_differs);
    EXPECT_LE(shadow_differs, rows / 50);
    EXPECT_EQ(non_finite, 0);
    glDeleteProgram(prog);
    glDeleteBuffers(1, &bin);
    glDeleteBuffers(1, &bout);
    glDeleteSamplers(1, &smp);
    glDeleteTextures(2, tex);
}
