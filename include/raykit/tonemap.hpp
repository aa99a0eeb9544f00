// raykit — tonemap.hpp: the CPU build of shaders/raykit/tonemap.glsl (and color.glsl).
//
// Every rk_* operator is compiled from the same text the GPU runs; tests/gpu/parity_tonemap.cpp
// checks both builds agree on a real driver. Exposure and adaptation live in raykit/exposure.hpp.
#pragma once

#include <string>
#include <vector>

#include "raykit/color.hpp"
#include "raykit/shader_define.hpp"

namespace raykit {
#include "raykit/tonemap.glsl"

/// The operators of tonemap.glsl, numbered as RK_TONEMAP_OPERATOR.
enum class ToneOperator : int {
    clamp = 0,
    reinhard = 1,
    aces_narkowicz = 2,
    aces_hill = 3,
    agx = 4,
    pbr_neutral = 5,
    hable = 6,
    lottes = 7,
    uchimura = 8,
};

/// Run-time dispatch over the operators (CPU tools, LUT baking, tests); the shader selects at
/// compile time instead. `agx_look` as in RK_AGX_LOOK; `reinhard_white` for Reinhard only.
inline vec3 tonemap(ToneOperator op, vec3 rgb, int agx_look = 0, float reinhard_white = RK_HDR_MAX)
{
    switch (op) {
    case ToneOperator::clamp: return glm::clamp(rk_hdr_sanitize(rgb), vec3(0.0f), vec3(1.0f));
    case ToneOperator::reinhard: return rk_tonemap_reinhard(rgb, reinhard_white);
    case ToneOperator::aces_narkowicz: return rk_aces_narkowicz(rgb);
    case ToneOperator::aces_hill: return rk_aces_hill(rgb);
    case ToneOperator::agx: return rk_agx(rgb, agx_look);
    case ToneOperator::pbr_neutral: return rk_pbr_neutral(rgb);
    case ToneOperator::hable: return rk_hable(rgb);
    case ToneOperator::lottes: return rk_lottes(rgb);
    case ToneOperator::uchimura: return rk_uchimura(rgb);
    }
    return vec3(0.0f);
}

/// Human-readable name of an operator (sample captions, bench labels).
inline const char* tonemap_operator_name(ToneOperator op)
{
    switch (op) {
    case ToneOperator::clamp: return "clamp";
    case ToneOperator::reinhard: return "Reinhard";
    case ToneOperator::aces_narkowicz: return "ACES (Narkowicz)";
    case ToneOperator::aces_hill: return "ACES (Hill)";
    case ToneOperator::agx: return "AgX";
    case ToneOperator::pbr_neutral: return "PBR Neutral";
    case ToneOperator::hable: return "Hable";
    case ToneOperator::lottes: return "Lottes";
    case ToneOperator::uchimura: return "Uchimura";
    }
    return "?";
}

/// The minimal macro set for a shader that tone-maps with `op` (and `agx_look` for AgX): pass it to
/// raykit::load_shader_file, or as NAME=VALUE to raykit_compile_shaders(DEFINES ...). RK_AGX_LOOK
/// is only emitted for AgX, so shaders of other operators share one variant.
inline std::vector<ShaderDefine> tonemap_defines(ToneOperator op, int agx_look = 0)
{
    std::vector<ShaderDefine> d{{"RK_TONEMAP_OPERATOR", std::to_string(static_cast<int>(op))}};
    if (op == ToneOperator::agx) d.push_back({"RK_AGX_LOOK", std::to_string(agx_look)});
    return d;
}

}  // namespace raykit
