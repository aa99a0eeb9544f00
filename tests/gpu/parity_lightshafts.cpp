// GPU parity for shaders/raykit/lightshafts.glsl: the light's screen position, the fade and the
// disk through the parity harness (parity.hpp), and the accumulation reading a real RGBA32F texture
// (LINEAR, clamp to edge) in a compute shader against the CPU twin (LsMapCpu's bilinear read).
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/lightshafts.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {
parity::Domain clipc() { return {-4.0f, 4.0f, false, {0.0f, 1.0f, -1.0f}}; }
}  // namespace

TEST(GpuParity, LightShaftsFunctions)
{
    const char* S = "raykit/lightshafts.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_ls_light_uv / rk_ls_fade", S, (clipc(), clipc(), clipc(), clipc()), 3,
                  vec2 uv = rk_ls_light_uv(vec4(a[0], a[1], a[2], a[3]));
                  o[0] = uv.x; o[1] = uv.y; o[2] = rk_ls_fade(vec4(a[0], a[1], a[2], a[3]), 0.3f);),
        RK_PARITY("rk_ls_disk", S, (dom::unit(), dom::unit(), dom::unit()), 1,
                  o[0] = rk_ls_disk(vec2(clamp(a[0], -2.0f, 2.0f), clamp(a[1], -2.0f, 2.0f)), vec2(0.5f, 0.45f), 0.05f + clamp(a[2], 0.0f, 1.0f), 1.5f);),
    };
    for (parity::Case& c : cases) {
        c.abs_tol = 2e-6;
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}

TEST(GpuParity, LightShaftsAccumulate)
{
    const int w = 80, h = 60;
    LsMapCpu m;
    m.width = w;
    m.height = h;
    std::vector<float> rgba;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // A sky disk with bars across it (the occluders), plus a gradient.
            const float dx = (float(x) - 40.0f) / 30.0f, dy = (float(y) - 35.0f) / 30.0f;
            float v = std::max(0.0f, 1.0f - std::sqrt(dx * dx + dy * dy));
            if (x % 9 < 2 || y < 12) v = 0.0f;
            const vec3 c(v, 0.5f * v + 0.002f * float(x), v * v);
            m.v.push_back(c);
            rgba.insert(rgba.end(), {c.x, c.y, c.z, 1.0f});
        }
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, w, h);
    glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTextureUnit(0, tex);
    std::mt19937 rng(5u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const int rows = 4096;
    std::vector<float> in;
    for (int i = 0; i < rows; ++i) {
        in.push_back(-0.05f + 1.1f * u(rng));  // uv
        in.push_back(-0.05f + 1.1f * u(rng));
        in.push_back(-0.5f + 2.0f * u(rng));   // light uv (some off screen)
        in.push_back(-0.5f + 2.0f * u(rng));
        in.push_back(0.2f + u(rng));           // density
        in.push_back(0.9f + 0.1f * u(rng));    // decay
    }
    const std::string src = std::string("#version 450 core\n#extension GL_GOOGLE_include_directive : require\n") +
                            "layout(local_size_x = 64) in;\n"
                            "layout(std430, binding = 0) readonly buffer In { float rk_in[]; };\n"
                            "layout(std430, binding = 1) writeonly buffer Out { float rk_out[]; };\n"
                            "layout(binding = 0) uniform sampler2D u_occ;\n"
                            "#include \"raykit/lightshafts.glsl\"\n"
                            "void main() {\n"
                            "  uint i = gl_GlobalInvocationID.x;\n"
                            "  if (i >= 4096u) return;\n"
                            "  uint b = 6u * i;\n"
                            "  vec3 r = rk_ls_accumulate(u_occ, vec2(rk_in[b], rk_in[b + 1u]), vec2(rk_in[b + 2u], rk_in[b + 3u]), 48u, rk_in[b + 4u], 1.0 / 48.0, rk_in[b + 5u], 1.5);\n"
                            "  rk_out[3u * i] = r.x; rk_out[3u * i + 1u] = r.y; rk_out[3u * i + 2u] = r.z;\n"
                            "}\n";
    const GLuint prog =
        rkgl::build_program({{GL_COMPUTE_SHADER, rkgl::resolved_shader(src, "parity_lightshafts.comp", parity::shader_dir(), {parity::shader_dir()})}});
    const GLuint bin = rkgl::make_buffer(in.size() * sizeof(float), in.data());
    const GLuint bout = rkgl::make_buffer(size_t(rows) * 3u * sizeof(float), nullptr);
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
    glDispatchCompute(rows / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<float> gpu = rkgl::read_floats(bout, size_t(rows) * 3u);
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    double worst = 0.0;
    for (int i = 0; i < rows; ++i) {
        const float* a = &in[size_t(i) * 6u];
        const vec3 c = rk_ls_accumulate(m, vec2(a[0], a[1]), vec2(a[2], a[3]), 48u, a[4], 1.0f / 48.0f, a[5], 1.5f);
        for (int k = 0; k < 3; ++k) {
            const float g = gpu[size_t(i) * 3u + size_t(k)];
            ASSERT_TRUE(std::isfinite(g));
            worst = std::max(worst, double(std::abs(g - c[k])));
        }
    }
    // The driver's bilinear weights are fixed point (llvmpipe: 8 fractional bits): each sample may
    // differ by up to its texels' difference / 512 (a bar edge: 1 / 512); 48 samples of weight
    // 1.5 / 48 keep that: 3e-3 at worst. llvmpipe filters RGBA32F exactly (2.4e-7).
    std::printf("[parity] light shafts accumulate: max |gpu - cpu| %.3g over %d rows\n", worst, rows);
    EXPECT_LT(worst, 5e-3);
    glDeleteProgram(prog);
    glDeleteBuffers(1, &bin);
    glDeleteBuffers(1, &bout);
    glDeleteTextures(1, &tex);
}
