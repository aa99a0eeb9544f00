// raykit — GLSL-on-C++ compatibility layer.
//
// The shared .glsl files under shaders/raykit/ are written in a subset of GLSL that is also valid
// C++17 once this header has mapped GLSL's vocabulary onto GLM (docs/dialect.md lists the rules).
// Every include/raykit/<x>.hpp includes this header first, then includes the .glsl text *inside*
// `namespace raykit`, so the CPU build of a shader function is `raykit::rk_<name>`.
//
// Nothing here is meant to be used directly by applications.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace raykit {

// Types. `uint` is a typedef in glibc's <sys/types.h> at global scope; this one shadows it inside
// namespace raykit so the shared code means exactly GLSL's 32-bit unsigned int.
using glm::bvec2;
using glm::bvec3;
using glm::bvec4;
using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
using glm::mat2;
using glm::mat3;
using glm::mat4;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;

// Built-in functions used by shared code. GLM provides the GLSL semantics (clamp order, mix,
// sign of zero...); only what shared code uses is pulled in, so a missing mapping is a compile
// error in C++ rather than a silent call to a different overload.
using glm::abs;
using glm::acos;
using glm::asin;
using glm::atan;
using glm::bitCount;
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::exp2;
using glm::faceforward;
using glm::floatBitsToUint;
using glm::findMSB;
using glm::floor;
using glm::fract;
using glm::inversesqrt;
using glm::isinf;
using glm::isnan;
using glm::length;
using glm::log;
using glm::log2;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::pow;
using glm::reflect;
using glm::sign;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
using glm::step;
using glm::tan;
using glm::uintBitsToFloat;

// bitCount and findMSB of a scalar uint: the same results as GLM's (and GLSL's), without GLM's
// 64-bit-wide bit tricks, which GCC 12 turns into a call to libgcc's __popcountdi2 on targets
// without POPCNT (the octree traversal's child rank and pop use these on every step). The choice
// of code never depends on compile flags, so every translation unit gets the same function.
inline int bitCount(uint v)
{
    v = v - ((v >> 1u) & 0x55555555u);
    v = (v & 0x33333333u) + ((v >> 2u) & 0x33333333u);
    return static_cast<int>((((v + (v >> 4u)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24u);
}
inline int findMSB(uint v)
{
#if defined(__GNUC__) || defined(__clang__)
    return v == 0u ? -1 : 31 - __builtin_clz(v);
#else
    int n = -1;
    while (v != 0u) {
        v >>= 1u;
        ++n;
    }
    return n;
#endif
}

}  // namespace raykit
