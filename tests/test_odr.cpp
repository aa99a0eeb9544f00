// Feature macros must not break the one-definition rule: this test links two translation units
// that include the same headers with different RK_* macros (tests/parts/test_odr/other_config.cpp
// sets every one of them), built at -O0 where the linker would keep one copy of a shared inline
// definition for both. Each TU checks its own behaviour against macro-free functions; the
// configured functions live in inline namespaces named after the macro values (RK_CONFIGURED_BEGIN,
// docs/dialect.md), so each keeps its own.
#include <gtest/gtest.h>

#include "odr_probe.hpp"  // this TU: the defaults

OdrProbe odr_probe_other_config();

static OdrProbe odr_probe_defaults()
{
    RK_ODR_PROBE_BODY(rk_agx(odr::kHdr, 0),
                      rk_fresnel_slab_sp(rk_fresnel_dielectric_sp(0.7f, 1.5f)),
                      rk_fresnel_slab_sp(rk_fresnel_dielectric_sp(0.7f, 1.5f)),
                      rk_im_window_fresnel(glm::vec3(0.2f, 0.3f, 0.4f), glm::vec3(0.9f, 0.8f, 0.7f), 0.7f, glm::vec3(0.9f),
                                           1.5f, 2.0f),
                      rk_im_trace_grad(odr::kP, odr::kCam, odr::kN, glm::vec3(0.01f, 0.0f, 0.0f),
                                       glm::vec3(0.0f, 0.01f, 0.0f), odr::grid()).t)
}

TEST(Odr, EachTranslationUnitKeepsItsMacros)
{
    const OdrProbe a = odr_probe_defaults(), b = odr_probe_other_config();
    for (const OdrProbe* p : {&a, &b}) {
        const char* which = p == &a ? "defaults" : "other config";
        EXPECT_EQ(p->tonemap, p->tonemap_want) << which;
        EXPECT_EQ(p->fresnel, p->fresnel_want) << which;
        EXPECT_EQ(p->glass, p->glass_want) << which;
        EXPECT_EQ(p->window, p->window_want) << which;
        EXPECT_EQ(p->trace_t, p->trace_t_want) << which;
    }
    // The two configurations really differ on these inputs (else the test could not fail).
    EXPECT_NE(a.tonemap, b.tonemap);
    EXPECT_NE(a.fresnel, b.fresnel);
    EXPECT_NE(a.glass, b.glass);
    EXPECT_NE(a.window, b.window);
    EXPECT_NE(a.trace_t, b.trace_t);
}
