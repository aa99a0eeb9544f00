// svo_hybrid.glsl (C++ build) against float64 references: the window depth of a point equals the
// rasteriser's (Gritzner's Table 5.1 values for the OpenGL convention; closed forms for
// zero-to-one and reversed-Z, finite and infinite far planes), the pixel ray passes through the
// unprojected pixel at every depth, rk_svo_depth_to_t inverts the depth along the ray, and
// svo_hybrid_view composes model, view and projection so an object-space point gets the depth of
// its world-space image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/svo_hybrid.hpp"

using namespace raykit;

namespace {

const SvoDepthConvention kConventions[] = {SvoDepthConvention::gl_minus_one_to_one, SvoDepthConvention::zero_to_one,
                                          SvoDepthConvention::reversed_zero_to_one};
const char* name_of(SvoDepthConvention c)
{
    return c == SvoDepthConvention::gl_minus_one_to_one ? "gl" : c == SvoDepthConvention::zero_to_one ? "zo" : "reversed";
}

/// Window depth of a point at eye distance z (> 0) in double, by convention, closed forms.
double depth64(SvoDepthConvention c, double n, double f, double z)
{
    switch (c) {
    case SvoDepthConvention::gl_minus_one_to_one: return 0.5 * ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * z)) + 0.5;
    case SvoDepthConvention::zero_to_one: return f / (f - n) - f * n / ((f - n) * z);
    case SvoDepthConvention::reversed_zero_to_one: return std::isinf(f) ? n / z : n * (f - z) / ((f - n) * z);
    }
    return 0.0;
}

}  // namespace

TEST(SvoHybrid, ThesisDepthTable)
{
    // Gritzner, Table 5.1 (OpenGL NDC): Z = n -> -1, 2n -> n/(f-n), 3n -> (n + f/3)/(f-n),
    // 4n -> (n + f/2)/(f-n), f -> 1; here as window depths (ndc * 0.5 + 0.5).
    const float n = 0.5f, f = 100.0f;
    const glm::mat4 P = svo_perspective(1.0f, 1.0f, n, f, SvoDepthConvention::gl_minus_one_to_one);
    const SvoHybridView v = svo_hybrid_view(glm::mat4(1.0f), glm::mat4(1.0f), P, SvoDepthConvention::gl_minus_one_to_one);
    const double N = n, F = f;
    const double table[5][2] = {{N, -1.0}, {2 * N, N / (F - N)}, {3 * N, (N + F / 3) / (F - N)}, {4 * N, (N + F / 2) / (F - N)}, {F, 1.0}};
    for (const auto& row : table) {
        const float d = rk_svo_window_depth(v.obj_to_clip, glm::vec3(0.1f, -0.2f, -float(row[0])), v.depth_range);
        EXPECT_NEAR(d, 0.5 * row[1] + 0.5, 2e-7) << "Z = " << row[0];
    }
}

TEST(SvoHybrid, WindowDepthMatchesClosedForms)
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (SvoDepthConvention c : kConventions) {
        for (float f : {50.0f, 1000.0f, std::numeric_limits<float>::infinity()}) {
            if (std::isinf(f) && c != SvoDepthConvention::reversed_zero_to_one) continue;
            const float n = 0.1f;
            const glm::mat4 P = svo_perspective(1.2f, 1.5f, n, f, c);
            const SvoHybridView v = svo_hybrid_view(glm::mat4(1.0f), glm::mat4(1.0f), P, c);
            double worst = 0.0;
            for (int i = 0; i < 20000; ++i) {
                const double z = n * std::pow(std::isinf(f) ? 1e6 : double(f) / n, U(rng));
                const glm::vec3 p(float((U(rng) - 0.5) * z), float((U(rng) - 0.5) * z), -float(z));
                const double ref = depth64(c, n, f, -double(p.z));
                const double got = rk_svo_window_depth(v.obj_to_clip, p, v.depth_range);
                // Absolute error in units of 2^-24 (half the float spacing at depth 1, a 24-bit
                // fixed-point depth step): a float matrix product and division carry ~1e-7 of
                // absolute error near |ndc| = 1 whatever the depth's own magnitude, as the
                // rasteriser's do.
                worst = std::max(worst, std::abs(got - ref) / 0x1p-24);
            }
            std::printf("[hybrid] %-8s far %-6g: window depth within %.1f x 2^-24 of the closed form\n", name_of(c),
                        double(f), worst);
            EXPECT_LT(worst, 4.0) << name_of(c) << " far " << f;  // measured <= 2.5
        }
    }
}

TEST(SvoHybrid, PixelRayThroughUnprojectedPoints)
{
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -1.0f, 2.0f)) *
                            glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))) *
                            glm::scale(glm::mat4(1.0f), glm::vec3(2.5f));
    const glm::mat4 view = glm::lookAt(glm::vec3(4.0f, 5.0f, 9.0f), glm::vec3(3.0f, -1.0f, 2.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    for (SvoDepthConvention c : kConventions) {
        for (int ortho = 0; ortho < 2; ++ortho) {
            const float far_plane = c == SvoDepthConvention::reversed_zero_to_one && !ortho ? std::numeric_limits<float>::infinity() : 60.0f;
            glm::mat4 P = svo_perspective(0.9f, 1.3f, 0.2f, far_plane, c);
            if (ortho) {
                P = c == SvoDepthConvention::gl_minus_one_to_one ? glm::orthoRH_NO(-4.0f, 4.0f, -3.0f, 3.0f, 0.2f, 60.0f)
                                                                 : glm::orthoRH_ZO(-4.0f, 4.0f, -3.0f, 3.0f, 0.2f, 60.0f);
                if (c == SvoDepthConvention::reversed_zero_to_one) P = glm::orthoRH_ZO(-4.0f, 4.0f, -3.0f, 3.0f, 60.0f, 0.2f);
            }
            const SvoHybridView v = svo_hybrid_view(model, view, P, c);
            const glm::dmat4 M = glm::dmat4(P) * glm::dmat4(view) * glm::dmat4(model);
            double worst_line = 0.0, worst_t = 0.0;
            for (int i = 0; i < 5000; ++i) {
                const glm::vec2 ndc(U(rng), U(rng));
                glm::vec3 o, d;
                rk_svo_pixel_ray(v.clip_to_obj, ndc, v.z_near_ndc, o, d);
                // The origin is on the near plane at this pixel.
                const glm::dvec4 co = M * glm::dvec4(glm::dvec3(o), 1.0);
                EXPECT_NEAR(co.x / co.w, ndc.x, 2e-5);
                EXPECT_NEAR(co.y / co.w, ndc.y, 2e-5);
                EXPECT_NEAR(co.z / co.w, v.z_near_ndc, 2e-4);
                // Points of the ray at any t project to the same pixel; their depth maps back to t.
                for (float t : {0.5f, 3.0f, 20.0f}) {
                    const glm::vec3 p = o + t * d;
                    const glm::dvec4 cp = M * glm::dvec4(glm::dvec3(p), 1.0);
                    if (cp.w <= 0.0 && !ortho) continue;
                    const double ndc_z = cp.z / cp.w;
                    if (ndc_z < (c == SvoDepthConvention::gl_minus_one_to_one ? -1.0 : 0.0) || ndc_z > 1.0) continue;  // clipped
                    worst_line = std::max(worst_line, std::max(std::abs(cp.x / cp.w - ndc.x), std::abs(cp.y / cp.w - ndc.y)));
                    const float depth = rk_svo_window_depth(v.obj_to_clip, p, v.depth_range);
                    const float tb = rk_svo_depth_to_t(v.clip_to_obj, ndc, depth, v.depth_range, o, d);
                    // Depth quantises t: compare through the depth's own sensitivity.
                    const float depth_b = rk_svo_window_depth(v.obj_to_clip, o + tb * d, v.depth_range);
                    worst_t = std::max(worst_t, std::abs(double(depth_b) - double(depth)) / 0x1p-24);
                }
            }
            std::printf("[hybrid] %-8s %s: pixel ray off its pixel by %.1e NDC; depth -> t -> depth within %.1f x 2^-24\n",
                        name_of(c), ortho ? "ortho      " : "perspective", worst_line, worst_t);
            EXPECT_LT(worst_line, 5e-6);  // measured 3.4e-6
            EXPECT_LT(worst_t, 48.0);
        }
    }
}

TEST(SvoHybrid, InfiniteFarAndDegenerateInputs)
{
    const glm::mat4 P = svo_perspective(1.0f, 1.0f, 0.1f, std::numeric_limits<float>::infinity(), SvoDepthConvention::reversed_zero_to_one);
    const SvoHybridView v = svo_hybrid_view(glm::mat4(1.0f), glm::mat4(1.0f), P, SvoDepthConvention::reversed_zero_to_one);
    glm::vec3 o, d;
    rk_svo_pixel_ray(v.clip_to_obj, glm::vec2(0.25f, -0.5f), v.z_near_ndc, o, d);
    // The cleared reversed-Z depth (0) is at infinity: no limit on the ray.
    EXPECT_EQ(rk_svo_depth_to_t(v.clip_to_obj, glm::vec2(0.25f, -0.5f), 0.0f, v.depth_range, o, d), RK_FLT_MAX);
    // Near plane depth 1 -> t = 0; behind the near plane clamps to 0.
    EXPECT_NEAR(rk_svo_depth_to_t(v.clip_to_obj, glm::vec2(0.25f, -0.5f), 1.0f, v.depth_range, o, d), 0.0f, 1e-5f);
    // A point behind the camera gets a finite clamped depth, never NaN.
    const float behind = rk_svo_window_depth(v.obj_to_clip, glm::vec3(0.0f, 0.0f, 5.0f), v.depth_range);
    EXPECT_TRUE(behind >= 0.0f && behind <= 1.0f);
    const float at_eye = rk_svo_window_depth(v.obj_to_clip, glm::vec3(0.0f), v.depth_range);
    EXPECT_TRUE(at_eye >= 0.0f && at_eye <= 1.0f);
}
