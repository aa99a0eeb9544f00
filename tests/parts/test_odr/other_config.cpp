// The second translation unit of tests/test_odr.cpp: every macro differs from the defaults of the
// first (tone map Reinhard with another AgX look, single-surface Fresnel, fast window glass, additive window, varying
// walls, another nudge).
#define RK_TONEMAP_OPERATOR 1
#define RK_AGX_LOOK 2
#define RK_FRESNEL_WINDOW_MODE 0
#define RK_WINDOW_GLASS_FRESNEL 1
#define RK_IM_COMPOSE_MODE 1
#define RK_IM_VARYING_WALLS 1
#define RK_IM_NUDGE 0.000244140625f
#define RK_IM_NUDGE_TAG 2em12
#include "odr_probe.hpp"

OdrProbe odr_probe_other_config()
{
    RK_ODR_PROBE_BODY(rk_tonemap_reinhard(odr::kHdr, 4.0f),
                      rk_fresnel_dielectric(0.7f, 1.5f),
                      rk_window_glass_reflectance_fast(0.7f, rk_fresnel_fast_params(1.5f), 2.0f),
                      rk_im_window_additive(glm::vec3(0.2f, 0.3f, 0.4f), glm::vec3(0.9f, 0.8f, 0.7f)),
                      rk_im_trace_varying_grad(odr::kP, odr::kCam, odr::kN, glm::vec3(0.01f, 0.0f, 0.0f),
                                               glm::vec3(0.0f, 0.01f, 0.0f), odr::grid(), odr::kJitter, 7u).t)
}
