// GPU parity for shaders/raykit/ssao.glsl: the occlusion functions read a real R32F depth texture on
// the driver (NEAREST, clamp to edge, in a compute shader) and the CPU twin (AoMapCpu) in C++: the
// rebuilt view position, the hemisphere and sphere-counting occlusion and the depth-aware blur, over
// 4,096 pixels of an analytic inner corner (floor and wall) and an AO buffer of random values.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "parity.hpp"
#include "raykit/ssao.hpp"

using namespace raykit;

TEST(GpuParity, Ssao)
{
    const int w = 96, h = 64;
    const double n_plane = 0.1, f_plane = 100.0;
    const glm::dmat4 P = glm::perspective(1.0, double(w) / h, n_plane, f_plane);
    const glm::dvec3 eye(0.3, 1.4, 1.8);
    const glm::dmat4 V = glm::lookAt(eye, glm::dvec3(0.0, 0.3, -1.6), glm::dvec3(0, 1, 0)), inv = glm::inverse(P * V);
    AoMapCpu depth, ao;
    depth.width = ao.width = w;
    depth.height = ao.height = h;
    std::mt19937 rng(9u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::dvec4 q = inv * glm::dvec4((x + 0.5) / w * 2 - 1, (y + 0.5) / h * 2 - 1, 0.5, 1.0);
            const glm::dvec3 d = glm::normalize(glm::dvec3(q) / q.w - eye);
            double t = 1e300;
            if (d.y < 0.0) t = std::min(t, -eye.y / d.y);
            if (d.z < 0.0) t = std::min(t, (-2.0 - eye.z) / d.z);
            const double dist = t < 1e299 ? -(V * glm::dvec4(eye + t * d, 1.0)).z : 1e300;
            depth.v.push_back(dist < f_plane ? float((1.0 / dist - 1.0 / f_plane) / (1.0 / n_plane - 1.0 / f_plane)) : 0.0f);
            ao.v.push_back(u(rng));
        }
    const vec3 k = gbuffer_depth_params(n_plane, f_plane, true);
    const vec4 ray = gbuffer_view_ray(mat4(P));
    const vec4 proj = vec4(float(P[0][0]), float(P[1][1]), float(P[2][0]), float(P[2][1]));

    GLuint tex[2] = {0, 0};
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    for (int i = 0; i < 2; ++i) {
        glTextureStorage2D(tex[i], 1, GL_R32F, w, h);
        glTextureSubImage2D(tex[i], 0, 0, 0, w, h, GL_RED, GL_FLOAT, (i == 0 ? depth : ao).v.data());
        glTextureParameteri(tex[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(tex[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(tex[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(tex[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glBindTextureUnit(GLuint(i), tex[i]);
    }
    const std::vector<vec3> kh = ao_kernel_hemisphere(16, 7u), ks = ao_kernel_sphere(16, 7u);
    vec3 kern_h[RK_AO_MAX_SAMPLES], kern_s[RK_AO_MAX_SAMPLES];
    std::string glsl_h = "const vec3 k_h[16] = vec3[16](", glsl_s = "const vec3 k_s[16] = vec3[16](";
    for (int i = 0; i < RK_AO_MAX_SAMPLES; ++i) {
        kern_h[i] = i < 16 ? kh[size_t(i)] : vec3(0.0f);
        kern_s[i] = i < 16 ? ks[size_t(i)] : vec3(0.0f);
    }
    for (int i = 0; i < 16; ++i) {
        char b[160];
        std::snprintf(b, sizeof b, "%svec3(%.9g, %.9g, %.9g)", i ? ", " : "", double(kh[size_t(i)].x), double(kh[size_t(i)].y), double(kh[size_t(i)].z));
        glsl_h += b;
        std::snprintf(b, sizeof b, "%svec3(%.9g, %.9g, %.9g)", i ? ", " : "", double(ks[size_t(i)].x), double(ks[size_t(i)].y), double(ks[size_t(i)].z));
        glsl_s += b;
    }
    glsl_h += ");\n";
    glsl_s += ");\n";
    char uni[512];
    std::snprintf(uni, sizeof uni,
                  "const vec3 K = vec3(%.9g, %.9g, %.9g);\nconst vec4 RAY = vec4(%.9g, %.9g, %.9g, %.9g);\n"
                  "const vec4 PROJ = vec4(%.9g, %.9g, %.9g, %.9g);\n",
                  double(k.x), double(k.y), double(k.z), double(ray.x), double(ray.y), double(ray.z), double(ray.w), double(proj.x),
                  double(proj.y), double(proj.z), double(proj.w));
    const int rows = 4096;
    std::vector<float> in;  // uv, normal (view space, from a random rotation of the true one), rot angle
    std::vector<vec3> nrm;
    const glm::dvec3 nf = glm::dvec3(V * glm::dvec4(0, 1, 0, 0)), nw = glm::dvec3(V * glm::dvec4(0, 0, 1, 0));
    for (int i = 0; i < rows; ++i) {
        const float ux = u(rng), uy = u(rng);
        in.push_back(ux);
        in.push_back(uy);
        in.push_back(6.2831853f * u(rng));
        nrm.push_back(vec3(u(rng) < 0.5f ? nf : nw));
    }
    for (int i = 0; i < rows; ++i) {
        in.push_back(nrm[size_t(i)].x);
        in.push_back(nrm[size_t(i)].y);
        in.push_back(nrm[size_t(i)].z);
    }
    const std::string src = std::string("#version 450 core\n#extension GL_GOOGLE_include_directive : require\n") +
                            "layout(local_size_x = 64) in;\n"
                            "layout(std430, binding = 0) readonly buffer In { float rk_in[]; };\n"
                            "layout(std430, binding = 1) writeonly buffer Out { float rk_out[]; };\n"
                            "layout(binding = 0) uniform sampler2D u_depth;\n"
                            "layout(binding = 1) uniform sampler2D u_ao;\n"
                            "#include \"raykit/ssao.glsl\"\n" +
                            glsl_h + glsl_s + uni +
                            "void main() {\n"
                            "  uint i = gl_GlobalInvocationID.x;\n"
                            "  if (i >= 4096u) return;\n"
                            "  vec2 uv = vec2(rk_in[3u * i], rk_in[3u * i + 1u]);\n"
                            "  float a = rk_in[3u * i + 2u];\n"
                            "  vec3 n = vec3(rk_in[12288u + 3u * i], rk_in[12288u + 3u * i + 1u], rk_in[12288u + 3u * i + 2u]);\n"
                            "  vec3 kh[RK_AO_MAX_SAMPLES]; vec3 ks[RK_AO_MAX_SAMPLES];\n"
                            "  for (int j = 0; j < RK_AO_MAX_SAMPLES; ++j) { kh[j] = j < 16 ? k_h[j] : vec3(0.0); ks[j] = j < 16 ? k_s[j] : vec3(0.0); }\n"
                            "  vec3 p = rk_ao_view_pos(u_depth, uv, K, RAY);\n"
                            "  rk_out[6u * i] = p.x; rk_out[6u * i + 1u] = p.y; rk_out[6u * i + 2u] = p.z;\n"
                            "  rk_out[6u * i + 3u] = rk_ao_hemisphere(u_depth, p, n, 0.5, kh, 16u, vec2(cos(a), sin(a)), 0.01, vec2(1.0 / 96.0, 1.0 / 64.0), K, RAY, PROJ);\n"
                            "  rk_out[6u * i + 4u] = rk_ao_sphere_count(u_depth, p, 0.5, ks, 16u, vec3(cos(a), sin(a), 1.0), 0.01, true, K, RAY, PROJ);\n"
                            "  rk_out[6u * i + 5u] = rk_ao_blur(u_ao, u_depth, uv, vec2(1.0 / 96.0, 0.0), 3, 20.0, K);\n"
                            "}\n";
    const GLuint prog = rkgl::build_program({{GL_COMPUTE_SHADER, rkgl::resolved_shader(src, "parity_ssao.comp", parity::shader_dir(), {parity::shader_dir()})}});
    const GLuint bin = rkgl::make_buffer(in.size() * sizeof(float), in.data());
    const GLuint bout = rkgl::make_buffer(size_t(rows) * 6u * sizeof(float), nullptr);
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
    glDispatchCompute(rows / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<float> gpu = rkgl::read_floats(bout, size_t(rows) * 6u);
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));

    double worst_p = 0.0, worst_blur = 0.0;
    int ao_rows_off = 0, ao_rows_far = 0;
    for (int i = 0; i < rows; ++i) {
        const vec2 uv(in[3u * size_t(i)], in[3u * size_t(i) + 1u]);
        const float a = in[3u * size_t(i) + 2u];
        const vec3 p = rk_ao_view_pos(depth, uv, k, ray);
        for (int c = 0; c < 3; ++c)
            worst_p = std::max(worst_p, std::abs(double(gpu[6u * size_t(i) + size_t(c)]) - double(p[c])) / std::max(1.0, double(glm::length(p))));
        const float hcpu = rk_ao_hemisphere(depth, p, nrm[size_t(i)], 0.5f, kern_h, 16u, vec2(std::cos(a), std::sin(a)), 0.01f, vec2(1.0f / 96.0f, 1.0f / 64.0f), k,
                                            ray, proj);
        const float scpu = rk_ao_sphere_count(depth, p, 0.5f, kern_s, 16u, vec3(std::cos(a), std::sin(a), 1.0f), 0.01f, true, k, ray, proj);
        const float bcpu = rk_ao_blur(ao, depth, uv, vec2(1.0f / 96.0f, 0.0f), 3, 20.0f, k);
        // A sample within rounding of a texel edge or of the bias may flip: one sample of 16.
        for (float e : {std::abs(gpu[6u * size_t(i) + 3u] - hcpu), std::abs(gpu[6u * size_t(i) + 4u] - scpu)}) {
            if (e > 1e-4f) ++ao_rows_off;
            if (e > 1.0f / 16.0f + 1e-4f) ++ao_rows_far;
        }
        worst_blur = std::max(worst_blur, double(std::abs(gpu[6u * size_t(i) + 5u] - bcpu)));
    }
    std::printf("[parity] ssao: view position max rel %.3g, occlusion rows differing %d of %d (beyond one sample: %d), blur max %.3g\n",
                worst_p, ao_rows_off, 2 * rows, ao_rows_far, worst_blur);
    EXPECT_LT(worst_p, 1e-5);
    EXPECT_LE(ao_rows_off, 2 * rows / 100) << "occlusion rows whose sample classification differs";
    EXPECT_EQ(ao_rows_far, 0);
    EXPECT_LT(worst_blur, 1e-4);
    glDeleteProgram(prog);
    glDeleteBuffers(1, &bin);
    glDeleteBuffers(1, &bout);
    glDeleteTextures(2, tex);
}
