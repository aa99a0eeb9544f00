// svo_secondary.glsl built with RK_SVO_SECONDARY_FRESNEL_FAST=1, in a translation unit of its own
// inside test_svo_secondary (whose other units use the exact default): rk_svo_interface_at's
// reflectance against the suite's float64 Fresnel (reference/fresnel_ref.hpp). External reflection
// uses the fast form, within its documented error (fresnel.glsl: 1.7e-3 at eta 1.52, 3.7e-3 at
// 1.33, 3.5e-4 at 2.0); internal reflection stays exact, TIR gives 1; directions are unchanged.
#define RK_SVO_SECONDARY_FRESNEL_FAST 1
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "raykit/svo_secondary.hpp"
#include "reference/fresnel_ref.hpp"

using namespace raykit;

TEST(SvoSecondaryFastFresnel, ExternalWithinItsBoundInternalExact)
{
    static_assert(RK_SVO_SECONDARY_FRESNEL_FAST == 1, "this translation unit tests the fast build");
    struct Case { double n1, n2, bound; };
    // External: the fast form's documented maxima (plus float rounding); internal: the exact form
    // in float (a few 1e-6 where k = cos^2(theta_t) is near its 1e-3 cut-off below; the fast form,
    // made for eta >= 1, would be off by up to 1 there).
    const Case cases[] = {{1.0, 1.52, 1.8e-3}, {1.0, 1.33, 3.8e-3}, {1.0, 2.0, 4e-4}, {1.5, 1.0, 5e-6}, {1.33, 1.0, 5e-6}};
    for (const Case& c : cases) {
        double worst = 0.0, worst_dir = 0.0;
        for (int k = 0; k <= 900; ++k) {
            const double th = (89.9 * k / 900.0) * 3.14159265358979323846 / 180.0;
            const glm::vec3 d(float(std::sin(th)), 0.0f, float(-std::cos(th)));
            const rk_svo_interface f = rk_svo_interface_at(d, glm::vec3(0.0f, 0.0f, 1.0f), float(c.n1), float(c.n2));
            // The reference on the float inputs the library sees (the index and the direction).
            const double cos_i = -double(d.z) / glm::length(glm::dvec3(d));
            const double r = double(float(c.n1)) / double(float(c.n2)), kt = 1.0 - r * r * (1.0 - cos_i * cos_i);
            // Within 1e-3 of the critical angle's k = 0, float's ~1e-7 error in k moves R by about
            // 1e-7 / (2 sqrt(k)) relative to 1 - R: left out (TIR itself is checked below).
            if (kt > 0.0 && kt < 1e-3) continue;
            worst = std::max(worst, std::abs(double(f.reflectance) - ref::fresnel(cos_i, double(float(c.n2)) / double(float(c.n1)))));
            // The mirror direction does not depend on the Fresnel form.
            worst_dir = std::max(worst_dir, glm::length(glm::dvec3(f.reflected) - glm::dvec3(d.x, d.y, -d.z)));
            const bool tir = (c.n1 / c.n2) * std::sin(th) > 1.0 + 1e-6;
            if (tir) {
                EXPECT_EQ(f.reflectance, 1.0f) << c.n1 << " -> " << c.n2 << " at " << th;
            }
        }
        std::printf("[secondary] fast Fresnel build, %.2f -> %.2f: reflectance within %.1e of float64 (bound %.1e), mirror "
                    "direction within %.1e\n", c.n1, c.n2, worst, c.bound, worst_dir);
        EXPECT_LE(worst, c.bound) << c.n1 << " -> " << c.n2;
        EXPECT_LT(worst_dir, 1e-6);
    }
    // The fast form is really used: at 60 degrees into glass it differs from the exact reflectance.
    const double th = 60.0 * 3.14159265358979323846 / 180.0;
    const rk_svo_interface f = rk_svo_interface_at(glm::vec3(float(std::sin(th)), 0.0f, float(-std::cos(th))),
                                                   glm::vec3(0.0f, 0.0f, 1.0f), 1.0f, 1.52f);
    EXPECT_GT(std::abs(double(f.reflectance) - ref::fresnel(std::cos(th), 1.52)), 1e-5);
}
