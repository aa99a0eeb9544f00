// GPU parity for shaders/raykit/shadow_filter.glsl: the filters read a real depth texture on the
// driver (a DEPTH_COMPONENT32F map with a LINEAR compare sampler and a NEAREST raw sampler, in a
// compute shader) and the CPU twin (ShadowMapCpu) in C++; both must agree: the single compare (the
// hardware 2x2 PCF against rk_sh_compare's bilinear weights), the thesis's taps, Vogel PCF and PCSS.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/shadow_filter.hpp"

using namespace raykit;

namespace rkparity {
void shadow_filters_reversed(const raykit::ShadowMapCpu& m, const float* a, const raykit::vec2* taps16, float* out);
}

namespace {

/// A 64 x 64 depth pattern: a slope with blocks of nearer depth (blockers) and a few isolated texels.
ShadowMapCpu pattern_map(bool reversed)
{
    ShadowMapCpu m;
    m.width = m.height = 64;
    m.reversed = reversed;
    std::mt19937 rng(3u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            float d = 0.6f + 0.3f * float(x) / 64.0f;
            if ((x / 8 + y / 8) % 3 == 0) d = 0.2f + 0.05f * float(y % 8);
            if (u(rng) < 0.03f) d = u(rng);
            m.depth.push_back(reversed ? 1.0f - d : d);
        }
    return m;
}

}  // namespace

TEST(GpuParity, ShadowFilter)
{
    for (bool reversed : {false, true}) {
        const ShadowMapCpu cpu = pattern_map(reversed);
        GLuint tex = 0, s_cmp = 0, s_raw = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_DEPTH_COMPONENT32F, 64, 64);
        glTextureSubImage2D(tex, 0, 0, 0, 64, 64, GL_DEPTH_COMPONENT, GL_FLOAT, cpu.depth.data());
        glCreateSamplers(1, &s_cmp);
        glSamplerParameteri(s_cmp, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glSamplerParameteri(s_cmp, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glSamplerParameteri(s_cmp, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(s_cmp, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(s_cmp, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(s_cmp, GL_TEXTURE_COMPARE_FUNC, reversed ? GL_GEQUAL : GL_LEQUAL);
        glCreateSamplers(1, &s_raw);
        glSamplerParameteri(s_raw, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(s_raw, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glSamplerParameteri(s_raw, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(s_raw, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glBindTextureUnit(0, tex);
        glBindTextureUnit(1, tex);
        glBindSampler(0, s_cmp);
        glBindSampler(1, s_raw);

        // Inputs: uv (some outside [0, 1]), reference depth, radius (texels), rotation.
        std::mt19937 rng(11u);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        const int rows = 4096;
        std::vector<float> in;
        for (int i = 0; i < rows; ++i) {
            in.push_back(-0.1f + 1.2f * u(rng));
            in.push_back(-0.1f + 1.2f * u(rng));
            in.push_back(u(rng));
            in.push_back((0.5f + 3.0f * u(rng)) / 64.0f);
            in.push_back(6.2831853f * u(rng));
        }
        vec2 taps[16];
        const std::vector<vec2> pd = poisson_disk(16, 5u);
        for (int i = 0; i < 16; ++i) taps[i] = pd[size_t(i)];
        std::string taps_glsl = "const vec2 k_taps[16] = vec2[16](";
        for (int i = 0; i < 16; ++i) {
            char b[96];
            std::snprintf(b, sizeof b, "%svec2(%.9g, %.9g)", i ? ", " : "", double(taps[i].x), double(taps[i].y));
            taps_glsl += b;
        }
        taps_glsl += ");\n";
        const std::string src = std::string("#version 450 core\n#extension GL_GOOGLE_include_directive : require\n") +
                                "#define RK_SH_REVERSED_Z " + (reversed ? "1" : "0") + "\n" +
                                "layout(local_size_x = 64) in;\n"
                                "layout(std430, binding = 0) readonly buffer In { float rk_in[]; };\n"
                                "layout(std430, binding = 1) writeonly buffer Out { float rk_out[]; };\n"
                                "layout(binding = 0) uniform sampler2DShadow u_cmp;\n"
                                "layout(binding = 1) uniform sampler2D u_raw;\n"
                                "#include \"raykit/shadow_filter.glsl\"\n" +
                                taps_glsl +
                                "void main() {\n"
                                "  uint i = gl_GlobalInvocationID.x;\n"
                                "  if (i >= 4096u) return;\n"
                                "  vec3 uvz = vec3(rk_in[5u * i], rk_in[5u * i + 1u], rk_in[5u * i + 2u]);\n"
                                "  float r = rk_in[5u * i + 3u]; float phi = rk_in[5u * i + 4u];\n"
                                "  vec2 t[16] = k_taps;\n"
                                "  rk_out[4u * i] = rk_sh_compare(u_cmp, vec2(uvz.x, uvz.y), uvz.z);\n"
                                "  rk_out[4u * i + 1u] = rk_sh_pcf_taps(u_cmp, uvz, r, t, 16u, phi);\n"
                                "  rk_out[4u * i + 2u] = rk_sh_pcf_vogel(u_cmp, uvz, r, 16u, phi);\n"
                                "  rk_out[4u * i + 3u] = rk_sh_pcss(u_cmp, u_raw, uvz, 4.0 / 64.0, 2.0, 10.0, 1.0, 1.0 / 8.0, 0.5 / 64.0, 16u, phi);\n"
                                "}\n";
        const GLuint prog =
            rkgl::build_program({{GL_COMPUTE_SHADER, rkgl::resolved_shader(src, "parity_shadow_filter.comp", parity::shader_dir(), {parity::shader_dir()})}});
        const GLuint bin = rkgl::make_buffer(in.size() * sizeof(float), in.data());
        const GLuint bout = rkgl::make_buffer(size_t(rows) * 4u * sizeof(float), nullptr);
        glUseProgram(prog);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
        glDispatchCompute(rows / 64, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<float> gpu = rkgl::read_floats(bout, size_t(rows) * 4u);
        ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));

        // The CPU twin, built with the same macro value (reversed-Z: parity_shadow_filter_reversed.cpp).
        double worst[4] = {0, 0, 0, 0};
        int bad = 0;
        for (int i = 0; i < rows; ++i) {
            const float* a = &in[size_t(i) * 5u];
            const vec3 uvz(a[0], a[1], a[2]);
            float cpu_out[4];
            if (reversed) {
                rkparity::shadow_filters_reversed(cpu, a, taps, cpu_out);
            } else {
                cpu_out[0] = rk_sh_compare(cpu, vec2(uvz.x, uvz.y), uvz.z);
                cpu_out[1] = rk_sh_pcf_taps(cpu, uvz, a[3], taps, 16u, a[4]);
                cpu_out[2] = rk_sh_pcf_vogel(cpu, uvz, a[3], 16u, a[4]);
                cpu_out[3] = rk_sh_pcss(cpu, cpu, uvz, 4.0f / 64.0f, 2.0f, 10.0f, 1.0f, 1.0f / 8.0f, 0.5f / 64.0f, 16u, a[4]);
            }
            for (int k = 0; k < 4; ++k) {
                const double e = std::abs(double(gpu[size_t(i) * 4u + size_t(k)]) - cpu_out[k]);
                worst[k] = std::max(worst[k], e);
                // The driver's bilinear weights are fixed point (llvmpipe: 8 fractional bits), and a
                // tap landing within that of a texel boundary may pick the neighbour: 1/64 per row
                // of the average, and PCSS's kernel radius follows its blocker average.
                if (e > (k == 3 ? 0.1 : 1.0 / 32.0)) ++bad;
            }
        }
        std::printf("[parity] shadow filters%s: max |gpu - cpu| compare %.3g, thesis/Poisson taps %.3g, Vogel %.3g, PCSS %.3g; %d rows beyond tolerance\n",
                    reversed ? " (reversed-Z)" : "", worst[0], worst[1], worst[2], worst[3], bad);
        EXPECT_LE(bad, rows / 200) << "rows whose filters disagree beyond the fixed-point tolerance";
        EXPECT_LE(worst[0], 1.0 / 32.0) << "the 2x2 compare itself";
        glDeleteProgram(prog);
        glDeleteBuffers(1, &bin);
        glDeleteBuffers(1, &bout);
        glDeleteSamplers(1, &s_cmp);
        glDeleteSamplers(1, &s_raw);
        glDeleteTextures(1, &tex);
    }
}
