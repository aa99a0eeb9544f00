// The probe of tests/test_odr.cpp: each translation unit computes the macro-configured functions
// (rk_tonemap, rk_fresnel_window, rk_window_glass_reflectance, rk_im_window, rk_im_trace_auto)
// with its own macros, and the same quantities from macro-free functions chosen by hand for that
// configuration. Included by both TUs, after each has set its macros.
#pragma once

#include "raykit/interior_compose.hpp"
#include "raykit/tonemap.hpp"

struct OdrProbe {
    glm::vec3 tonemap, tonemap_want;
    float fresnel = 0.0f, fresnel_want = 0.0f;
    float glass = 0.0f, glass_want = 0.0f;
    glm::vec3 window, window_want;
    float trace_t = 0.0f, trace_t_want = 0.0f;
};

namespace odr {
inline raykit::rk_im_grid grid()
{
    raykit::rk_im_grid g;
    g.room_size = glm::vec3(4.0f, 3.0f, 4.0f);
    g.origin = glm::vec3(0.0f);
    return g;
}
// The inputs every probe uses.
const glm::vec3 kHdr(2.0f, 1.0f, 0.5f);
const glm::vec3 kP(2.3f, 1.7f, 0.0f), kCam(5.0f, 2.5f, 9.0f), kN(0.0f, 0.0f, 1.0f), kJitter(0.4f, 0.0f, 0.4f);
}  // namespace odr

/// The probe of the calling translation unit's configuration; `want` picks the macro-free twins.
#define RK_ODR_PROBE_BODY(TONEMAP_WANT, FRESNEL_WANT, GLASS_WANT, WINDOW_WANT, TRACE_WANT)                       \
    using namespace raykit;                                                                                     \
    OdrProbe r;                                                                                                 \
    r.tonemap = rk_tonemap(odr::kHdr, 4.0f);                                                                    \
    r.tonemap_want = TONEMAP_WANT;                                                                              \
    r.fresnel = rk_fresnel_window(0.7f, 1.5f, 2.0f);                                                            \
    r.fresnel_want = FRESNEL_WANT;                                                                              \
    r.glass = rk_window_glass_reflectance(0.7f, 1.5f, 2.0f);                                                    \
    r.glass_want = GLASS_WANT;                                                                                  \
    r.window = rk_im_window(glm::vec3(0.2f, 0.3f, 0.4f), glm::vec3(0.9f, 0.8f, 0.7f), 0.7f, glm::vec3(0.9f), 1.5f, 2.0f); \
    r.window_want = WINDOW_WANT;                                                                                \
    r.trace_t = rk_im_trace_auto(odr::kP, odr::kCam, odr::kN, glm::vec3(0.01f, 0.0f, 0.0f), glm::vec3(0.0f, 0.01f, 0.0f), \
                                 odr::grid(), odr::kJitter, 7u).t;                                              \
    r.trace_t_want = TRACE_WANT;                                                                                \
    return r;
