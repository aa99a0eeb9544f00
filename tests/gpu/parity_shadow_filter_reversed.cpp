// The reversed-Z C++ side of parity_shadow_filter.cpp: shadow_filter.hpp built with
// RK_SH_REVERSED_Z 1 in a translation unit of its own (the macro is per translation unit; its
// functions live in their own inline namespace, docs/dialect.md).
#define RK_SH_REVERSED_Z 1
#include "raykit/shadow_filter.hpp"

namespace rkparity {

/// The four filter outputs of parity_shadow_filter.cpp's shader, for a reversed-Z map.
void shadow_filters_reversed(const raykit::ShadowMapCpu& m, const float* a, const raykit::vec2* taps16, float* out)
{
    using namespace raykit;
    vec2 taps[16];
    for (int i = 0; i < 16; ++i) taps[i] = taps16[i];
    const vec3 uvz(a[0], a[1], a[2]);
    out[0] = rk_sh_compare(m, vec2(uvz.x, uvz.y), uvz.z);
    out[1] = rk_sh_pcf_taps(m, uvz, a[3], taps, 16u, a[4]);
    out[2] = rk_sh_pcf_vogel(m, uvz, a[3], 16u, a[4]);
    out[3] = rk_sh_pcss(m, m, uvz, 4.0f / 64.0f, 2.0f, 10.0f, 1.0f, 1.0f / 8.0f, 0.5f / 64.0f, 16u, a[4]);
}

}  // namespace rkparity
