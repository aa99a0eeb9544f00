// raykit — common.glsl: the shared-dialect prelude, constants and small robust helpers.
//
// Shared GLSL/C++ source. In GLSL, include it with GL_GOOGLE_include_directive (or let
// raykit::resolve_shader_includes() inline it for a driver). In C++, include raykit/common.hpp.
// The dialect rules (docs/dialect.md) in one breath: qualify functions with RK_INLINE, write
// out/inout parameters as RK_OUT(T)/RK_INOUT(T), no swizzles (use .x/.y/.z/.w and constructors),
// every float literal with an `f` suffix, build structs field by field, unsigned math with `uint`
// and `u`-suffixed literals, no implicit int->float conversion.
//
// @rk-es 310
// @rk-es300
#ifndef RK_COMMON_GLSL
#define RK_COMMON_GLSL

#ifdef __cplusplus
#define RK_INLINE inline
#define RK_OUT(T) T&
#define RK_INOUT(T) T&
#define RK_UNUSED(x) (void)(x)
#else
#define RK_INLINE
#define RK_OUT(T) out T
#define RK_INOUT(T) inout T
#define RK_UNUSED(x)
#endif


// RK_CONFIGURED_BEGIN(name) ... RK_CONFIGURED_END: brackets the functions whose body depends on
// option macros. GLSL: nothing. C++: `inline namespace name { ... }`, with `name` built from the
// macro values (RK_PP_CAT), so two translation units that include a header with different values
// get differently mangled functions instead of one silently shared inline definition (the
// one-definition rule). Types and macro-free functions stay outside: they are the same everywhere.
#ifdef __cplusplus
#define RK_PP_CAT2(a, b) a##b
#define RK_PP_CAT(a, b) RK_PP_CAT2(a, b)
#define RK_CONFIGURED_BEGIN(name) inline namespace name {
#define RK_CONFIGURED_END }
#else
#define RK_CONFIGURED_BEGIN(name)
#define RK_CONFIGURED_END
#endif

// RK_OPTION_CHECK(constant, MACRO): next to each option macro's range check (an #error that lists
// the valid values), makes a value that is not an integer a compile error too: the preprocessor
// reads an unknown identifier such as `aces` in RK_TONEMAP_OPERATOR=aces as 0, a valid value, so the
// macro is also used once as an integer expression, where the identifier is undeclared.
#ifdef __cplusplus
#define RK_OPTION_CHECK(constant, value) static_assert((value) == (value), #constant ": the option must be an integer")
#else
#define RK_OPTION_CHECK(constant, value) const uint constant = uint(value)
#endif

// RK_PRECISE: qualifies a local whose value depends on the written order of its operations (a
// cancellation-free rewrite such as (1 - x) + n x, a tie test). GLSL 4.00+ and ES 3.20: `precise`,
// which forbids the compiler to reassociate or fuse the operations that compute the value
// (NVIDIA's compiler turns (1 - x) + n x into 1 + (n - 1) x, which is 0 for x = 1, n = 2e-20,
// unless it is precise; docs/gpu-drivers.md). C++ and older GLSL: nothing (C++ compilers keep the
// written order unless told otherwise, e.g. by -ffast-math).
#if defined(__cplusplus)
#define RK_PRECISE
#elif defined(GL_ES) && __VERSION__ < 320
#define RK_PRECISE
#elif !defined(GL_ES) && __VERSION__ < 400
#define RK_PRECISE
#else
#define RK_PRECISE precise
#endif

#define RK_PI 3.14159265358979323846f
#define RK_HALF_PI 1.57079632679489661923f
#define RK_INV_PI 0.31830988618379067154f
// Smallest positive normal float. Used as a floor wherever a quantity is divided by, so that
// denormal inputs behave like zero on every backend (GPUs may flush denormals, CPUs do not).
#define RK_FLT_MIN 1.175494351e-38f
#define RK_FLT_MAX 3.402823466e+38f

/// rk_saturate: clamp to [0, 1].
/// Domain: any finite x. Exact. Cost: 1 clamp (a free output modifier on most GPUs).
RK_INLINE float rk_saturate(float x) { return clamp(x, 0.0f, 1.0f); }

/// rk_pow5: x^5 by three multiplies (the Schlick kernel).
/// Domain: any float; |x| > ~4.3e7 overflows to ±inf, callers keep x in [0, 1].
/// Max error: 3.0 ulp vs float64 (three roundings; every float in [0, 4.3e7]). Cost: 3 mul.
RK_INLINE float rk_pow5(float x)
{
    float x2 = x * x;
    return x2 * x2 * x;
}

/// rk_sqr: x*x. Exact up to one rounding. Cost: 1 mul.
RK_INLINE float rk_sqr(float x) { return x * x; }

/// rk_safe_sqrt: sqrt(max(x, 0)); never NaN for finite x (round-off can make a squared
/// difference slightly negative). Max error: that of sqrt. Cost: 1 max + 1 sqrt.
RK_INLINE float rk_safe_sqrt(float x) { return sqrt(max(x, 0.0f)); }

/// rk_safe_rcp_pos: 1/x for x expected >= 0, with x floored at RK_FLT_MIN so zero and
/// denormals give a large finite value instead of inf. Cost: 1 max + 1 div.
RK_INLINE float rk_safe_rcp_pos(float x) { return 1.0f / max(x, RK_FLT_MIN); }

/// rk_div: a / b, with |b| above 2^100 brought down first: a and b both scaled by 2^-100 (exact
/// powers of two). GLSL (4.50 §4.7.1) specifies division only for divisors up to 2^126, and a driver
/// that divides through the reciprocal (NVIDIA's) gets 0 beyond, so x / FLT_MAX is 0 there. The same
/// bits as a / b wherever |b| <= 2^100, and wherever the quotient is at least RK_FLT_MIN. b = 0 and
/// non-finite operands behave as in a / b. Cost: 1 abs, 1 compare, 2 selects, 1 div (+2 mul).
RK_INLINE float rk_div(float a, float b)
{
    bool big = abs(b) > 1.2676506e30f;
    return (big ? a * 7.8886091e-31f : a) / (big ? b * 7.8886091e-31f : b);
}

/// rk_div3: rk_div for each component of a over one divisor b. Cost: 3 div (+4 mul).
RK_INLINE vec3 rk_div3(vec3 a, float b)
{
    bool big = abs(b) > 1.2676506e30f;
    return (big ? a * 7.8886091e-31f : a) / (big ? b * 7.8886091e-31f : b);
}

/// rk_div4: rk_div for each component of a over one divisor b. Cost: 4 div (+5 mul).
RK_INLINE vec4 rk_div4(vec4 a, float b)
{
    bool big = abs(b) > 1.2676506e30f;
    return (big ? a * 7.8886091e-31f : a) / (big ? b * 7.8886091e-31f : b);
}

/// rk_flush_subnormal: v with each component below RK_FLT_MIN in magnitude (subnormal, or ±0) made
/// +0, as a GPU that flushes subnormals stores it, so that what follows decides alike on every
/// backend. NaN passes unchanged. Exact. Cost: 1 abs, 1 compare, 1 select (vec3).
RK_INLINE vec3 rk_flush_subnormal(vec3 v) { return mix(v, vec3(0.0f), lessThan(abs(v), vec3(RK_FLT_MIN))); }

/// rk_normalize_safe: v / |v|, scaled by its largest component first so that neither the squares
/// overflow nor denormals lose their direction; a zero or all-denormal vector, or one with a NaN or
/// infinite component, gives `fallback`. Max error: 3.5 ulp per component of a unit result.
/// Cost: 1 div, 1 rsqrt, ~10 flops.
RK_INLINE vec3 rk_normalize_safe(vec3 v, vec3 fallback)
{
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    // Each component checked: max() may drop a NaN operand.
    if (!(m >= RK_FLT_MIN) || !(abs(v.x) <= RK_FLT_MAX) || !(abs(v.y) <= RK_FLT_MAX) || !(abs(v.z) <= RK_FLT_MAX))
        return fallback;
    // Above 2^100, scale by 2^-100 first (exact): GLSL only specifies division by values up to 2^126.
    if (m > 1.2676506e30f) {
        v *= 7.8886091e-31f;
        m *= 7.8886091e-31f;
    }
    vec3 p = v / m;
    return p * inversesqrt(dot(p, p));
}

/// rk_oct_fold: the octahedral map's fold between the upper and lower half: (u, v) ->
/// ((1 - |v|) s(u), (1 - |u|) s(v)), s(x) = +1 for x >= 0 (also -0), else -1. Its own inverse on
/// the square [-1, 1]^2. Exact to one rounding per component. Cost: 2 selects, 4 flops.
RK_INLINE vec2 rk_oct_fold(float u, float v)
{
    return vec2((1.0f - abs(v)) * (u >= 0.0f ? 1.0f : -1.0f), (1.0f - abs(u)) * (v >= 0.0f ? 1.0f : -1.0f));
}

/// rk_bit_count_portable / rk_find_msb_portable: bitCount and findMSB of a uint without the
/// built-ins (GLSL ES 3.00 / WebGL 2 lacks them; there, these replace the built-ins, see below).
/// Exact: the built-ins' results for every uint (-1 for findMSB(0)). Cost: ~12 and ~10 integer ops.
RK_INLINE int rk_bit_count_portable(uint v)
{
    v = v - ((v >> 1u) & 0x55555555u);
    v = (v & 0x33333333u) + ((v >> 2u) & 0x33333333u);
    return int((((v + (v >> 4u)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24u);
}
RK_INLINE int rk_find_msb_portable(uint v)
{
    if (v == 0u) return -1;
    int n = 0;
    if (v >= 0x10000u) {
        n += 16;
        v >>= 16u;
    }
    if (v >= 0x100u) {
        n += 8;
        v >>= 8u;
    }
    if (v >= 0x10u) {
        n += 4;
        v >>= 4u;
    }
    if (v >= 0x4u) {
        n += 2;
        v >>= 2u;
    }
    return n + (v >= 0x2u ? 1 : 0);
}
#if !defined(__cplusplus) && defined(GL_ES)
#if __VERSION__ < 310
#define bitCount rk_bit_count_portable
#define findMSB rk_find_msb_portable
#endif
#endif

#endif  // RK_COMMON_GLSL
