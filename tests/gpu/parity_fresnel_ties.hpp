// A hardware driver's tie rule for the glazing sum (rk_fresnel_glazing_sp over
// rk_fresnel_dielectric_sp): shared by the Fresnel and window-glass parity tests.
#pragma once

#include <cmath>
#include <functional>

#include "parity.hpp"
#include "raykit/fresnel.hpp"

namespace parity {

/// With few panes (N -> 0) the glazing sum 2NR / ((1 - R) + 2NR) jumps from 0 to 1 as R -> 1: its
/// derivative at R = 1 is 1 / (2N), 5e19 for N = 1e-20. A driver whose Rs or Rp differs by an ulp
/// from the C++ build's (its sqrt and division are not correctly rounded; GLSL allows that) then
/// returns anything in [0, 1]. On hardware drivers only (llvmpipe keeps the strict check), a row is
/// a tie when the GPU value is the glazing of the C++ build's (Rs, Rp) moved by at most 4 ulps each.
/// Inputs of the row: cos_i, eta, panes (the first three).
inline std::function<bool(const float*, const float*, const float*)> hw_glazing_tie()
{
    return [](const float* in, const float* g, const float*) {
        if (!hardware_allowances()) return false;
        const glm::vec2 rsp = raykit::rk_fresnel_dielectric_sp(in[0], in[1]);
        for (int i = -4; i <= 4; ++i) {
            for (int j = -4; j <= 4; ++j) {
                const float rs = std::min(std::max(ulp_step(rsp.x, i, false), 0.0f), 1.0f);
                const float rp = std::min(std::max(ulp_step(rsp.y, j, false), 0.0f), 1.0f);
                const float v = raykit::rk_fresnel_glazing_sp(glm::vec2(rs, rp), in[2]);
                if (std::abs(static_cast<double>(v) - g[0]) <= 2e-6 + 2e-5 * std::abs(static_cast<double>(v))) return true;
            }
        }
        return false;
    };
}

}  // namespace parity
