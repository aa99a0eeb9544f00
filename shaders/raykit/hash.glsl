// raykit — hash.glsl: integer hashes that give bit-identical results on the CPU and every GPU.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/hash.hpp. All arithmetic is
// 32-bit unsigned (wrap-around modulo 2^32 in both languages), so the same input gives the same
// bits everywhere; tests/gpu/parity_interior.cpp checks that on a real driver, and
// tests/test_interior_mapping.cpp against an independently written PCG3D.
//
// Sources: Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020 (PCG3D: an
// LCG step per lane, then two rounds of lane mixing around a xorshift); O'Neill, "PCG: A Family of
// Simple Fast Space-Efficient Statistically Good Algorithms for Random Number Generation", 2014
// (the RXS-M-XS 32-bit output permutation, used here as a single-word hash as in Jarzynski &
// Olano's "pcg" entry).
//
// No feature macros.
//
// @rk-es 310
// @rk-es300
#ifndef RK_HASH_GLSL
#define RK_HASH_GLSL

#include "common.glsl"

/// rk_pcg3d: PCG3D (Jarzynski & Olano 2020), a 3-in/3-out 32-bit integer hash of high quality
/// for per-cell randomness (rooms, tiles, voxels). Domain: every uvec3. Exact: bit-identical on
/// CPU and GPU (integer multiply/add/xor/shift only). Cost: 3 mad + 6 mul + 6 add + 3 shift + 3 xor.
RK_INLINE uvec3 rk_pcg3d(uvec3 v)
{
    uint x = v.x * 1664525u + 1013904223u;
    uint y = v.y * 1664525u + 1013904223u;
    uint z = v.z * 1664525u + 1013904223u;
    x += y * z;
    y += z * x;
    z += x * y;
    x ^= x >> 16u;
    y ^= y >> 16u;
    z ^= z >> 16u;
    x += y * z;
    y += z * x;
    z += x * y;
    return uvec3(x, y, z);
}

/// rk_hash_u32: a single-word 32-bit hash, the PCG-RXS-M-XS output permutation applied to one LCG
/// step of x. A bijection on uint (every output occurs once), so distinct keys never collide.
/// Domain: every uint. Exact: bit-identical on CPU and GPU. Cost: 2 mul, 2 add, 3 shift, 2 xor.
RK_INLINE uint rk_hash_u32(uint x)
{
    uint state = x * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// rk_u32_to_unit: maps a hash to [0, 1) exactly: float(x >> 8) * 2^-24, i.e. the top 24 bits as
/// a multiple of 2^-24 (every value exactly representable, so the result is bit-identical on
/// every backend). Range [0, 1 - 2^-24]. Cost: 1 shift, 1 int-to-float, 1 mul.
RK_INLINE float rk_u32_to_unit(uint x) { return float(x >> 8u) * 5.9604644775390625e-8f; }

#endif  // RK_HASH_GLSL
