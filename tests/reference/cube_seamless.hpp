// A float64 CPU reference of cube-map LINEAR filtering with and without seamless filtering, for
// the cube shadow-map tests (tests/test_shadow_cube_seamless.cpp, tests/test_shadow_omni.cpp,
// tests/gpu/parity_shadow_cube_seamless.cpp), written from the OpenGL 4.6 core specification, not
// from any driver's code:
//   - §8.13 "Cube Map Texture Selection", Table 8.19: the face is the direction's major axis, and
//     s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2 with (sc, tc) per face (ties between axes
//     are left to the implementation; here x before y before z, as rk_sh_cube_face_uv);
//   - §8.14.2 "Coordinate Wrapping and Texel Selection": LINEAR takes the texels
//     i0 = floor(u - 1/2), i1 = i0 + 1 (u = s N) and j0, j1 likewise, with the weights
//     (1 - a)(1 - b), a (1 - b), (1 - a) b, a b for a = frac(u - 1/2), b = frac(v - 1/2);
//   - §8.13.1 "Seamless Cube Map Filtering" (TEXTURE_CUBE_MAP_SEAMLESS): the wrap mode is taken as
//     CLAMP_TO_BORDER, and a texel that falls outside the face in i or in j "is instead selected
//     from the corresponding texel of the appropriate neighboring face"; one outside in both (a
//     corner of the cube) has no unique neighbour, and the specification recommends the average of
//     the three available samples (an implementation may do otherwise, provided three equal samples
//     give that value).
// The neighbouring face's texel is found by geometry, not by a table: the out-of-face texel's
// centre, ma + (2 (i + 1/2) / N - 1) sc + (2 (j + 1/2) / N - 1) tc, is a direction whose major axis
// is the neighbouring face's (its coordinate across the edge is 1 + 1/N), and that face's texel
// under it is the one sharing the edge (the along-edge index is kept; test_shadow_cube_seamless
// checks it). Without seamless filtering every face is filtered on its own with CLAMP_TO_EDGE.
//
// For a depth texture with TEXTURE_COMPARE_MODE, LINEAR filtering weights the four texels' compare
// results (§8.23.1 leaves the exact method to the implementation, "a value in [0, 1] proportional
// to the number of comparison passes"); the corner's fourth sample is the average of the other
// three compare results (CornerRule::average_results) or the compare of the average of their depths
// (CornerRule::average_depths). Nothing from raykit is included.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/glm.hpp>

namespace rkref {

using glm::dvec3;

/// Table 8.19: face f (0..5 = +X, -X, +Y, -Y, +Z, -Z), its major axis and the directions of sc, tc.
inline dvec3 cube_ma(int f)
{
    const dvec3 t[6] = {dvec3(1, 0, 0), dvec3(-1, 0, 0), dvec3(0, 1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1)};
    return t[f];
}
inline dvec3 cube_sc(int f)
{
    const dvec3 t[6] = {dvec3(0, 0, -1), dvec3(0, 0, 1), dvec3(1, 0, 0), dvec3(1, 0, 0), dvec3(1, 0, 0), dvec3(-1, 0, 0)};
    return t[f];
}
inline dvec3 cube_tc(int f)
{
    const dvec3 t[6] = {dvec3(0, -1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1), dvec3(0, -1, 0), dvec3(0, -1, 0)};
    return t[f];
}

/// The face of direction v (major axis; ties x, y, z in that order, +0 as +) and its (s, t).
/// v = 0 gives face 0 at (0.5, 0.5).
inline int cube_face_st(dvec3 v, double& s, double& t)
{
    const double ax = std::abs(v.x), ay = std::abs(v.y), az = std::abs(v.z);
    const int f = ax >= ay && ax >= az ? (v.x < 0 ? 1 : 0) : ay >= az ? (v.y < 0 ? 3 : 2) : (v.z < 0 ? 5 : 4);
    const double ma = glm::dot(v, cube_ma(f));
    if (!(ma > 0.0)) {
        s = t = 0.5;
        return 0;
    }
    s = 0.5 * (glm::dot(v, cube_sc(f)) / ma + 1.0);
    t = 0.5 * (glm::dot(v, cube_tc(f)) / ma + 1.0);
    return f;
}

/// (s, t) of direction v on a given face f (v must point into the face's half-space: v . ma > 0).
inline void cube_st_on(int f, dvec3 v, double& s, double& t)
{
    const double ma = glm::dot(v, cube_ma(f));
    s = 0.5 * (glm::dot(v, cube_sc(f)) / ma + 1.0);
    t = 0.5 * (glm::dot(v, cube_tc(f)) / ma + 1.0);
}

/// The direction through the centre of texel (i, j) of face f on N x N faces (i, j may lie one
/// outside [0, N - 1]: the face's plane continued).
inline dvec3 cube_texel_dir(int f, int i, int j, int n)
{
    return cube_ma(f) + (2.0 * (i + 0.5) / n - 1.0) * cube_sc(f) + (2.0 * (j + 0.5) / n - 1.0) * cube_tc(f);
}

struct CubeTexel {
    int face = 0, i = 0, j = 0;
};

/// Seamless filtering's texel for (i, j) of face f when exactly one of i, j is outside [0, N - 1]
/// (by one): the neighbouring face's texel under the out-of-face texel's centre direction.
inline CubeTexel cube_texel_across(int f, int i, int j, int n)
{
    double s, t;
    CubeTexel r;
    r.face = cube_face_st(cube_texel_dir(f, i, j, n), s, t);
    r.i = std::min(std::max(static_cast<int>(std::floor(s * n)), 0), n - 1);
    r.j = std::min(std::max(static_cast<int>(std::floor(t * n)), 0), n - 1);
    return r;
}

/// One of the four samples of a LINEAR lookup: a texel and its weight, or (corner) the missing
/// fourth texel at a cube corner, whose value comes from the other three.
struct CubeTap {
    CubeTexel texel;
    double weight = 0.0;
    bool corner = false;
};

/// The four samples of a LINEAR lookup in direction v on N x N faces, read from face `face` at
/// (s, t) (normally v's own face: cube_linear_taps below), seamless or per face with CLAMP_TO_EDGE.
inline std::array<CubeTap, 4> cube_linear_taps_on(int face, double s, double t, int n, bool seamless)
{
    const double u = s * n - 0.5, w = t * n - 0.5;
    const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(w));
    const double a = u - i0, b = w - j0;
    std::array<CubeTap, 4> taps;
    const int di[4] = {0, 1, 0, 1}, dj[4] = {0, 0, 1, 1};
    const double wt[4] = {(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
    for (int k = 0; k < 4; ++k) {
        int i = i0 + di[k], j = j0 + dj[k];
        CubeTap& tp = taps[size_t(k)];
        tp.weight = wt[k];
        const bool out_i = i < 0 || i >= n, out_j = j < 0 || j >= n;
        if (!seamless) {
            i = std::min(std::max(i, 0), n - 1);
            j = std::min(std::max(j, 0), n - 1);
            tp.texel = {face, i, j};
        } else if (out_i && out_j) {
            tp.corner = true;
            tp.texel = {face, i, j};
        } else if (out_i || out_j) {
            tp.texel = cube_texel_across(face, i, j, n);
        } else {
            tp.texel = {face, i, j};
        }
    }
    return taps;
}

inline std::array<CubeTap, 4> cube_linear_taps(dvec3 v, int n, bool seamless)
{
    double s, t;
    const int f = cube_face_st(v, s, t);
    return cube_linear_taps_on(f, s, t, n, seamless);
}

/// Whether a seamless LINEAR lookup in direction v reads a texel of another face (or a corner)
/// with a nonzero weight: the receivers whose filtering differs between seamless and per-face.
inline bool cube_footprint_crosses_edge(dvec3 v, int n)
{
    double s, t;
    const int f = cube_face_st(v, s, t);
    for (const CubeTap& tp : cube_linear_taps_on(f, s, t, n, true))
        if (tp.weight > 0.0 && (tp.corner || tp.texel.face != f)) return true;
    return false;
}

enum class CornerRule { average_results, average_depths };

/// The LINEAR depth compare (LEQUAL: 1 where ref <= stored) of the taps; depth(face, i, j) reads a
/// texel.
template <class Depth>
double cube_compare_taps(const std::array<CubeTap, 4>& taps, double ref, Depth depth, CornerRule rule = CornerRule::average_results)
{
    double sum = 0.0, others = 0.0, other_depth = 0.0;
    int n_others = 0;
    for (const CubeTap& tp : taps) {
        if (tp.corner) continue;
        const double d = depth(tp.texel.face, tp.texel.i, tp.texel.j);
        const double lit = ref <= d ? 1.0 : 0.0;
        sum += tp.weight * lit;
        others += lit;
        other_depth += d;
        ++n_others;
    }
    for (const CubeTap& tp : taps) {
        if (!tp.corner || n_others == 0) continue;
        const double fourth = rule == CornerRule::average_results ? others / n_others : (ref <= other_depth / n_others ? 1.0 : 0.0);
        sum += tp.weight * fourth;
    }
    return sum;
}

/// texture(samplerCubeShadow, vec4(v, ref)) with LINEAR filtering, seamless or not, in float64.
template <class Depth>
double cube_compare(dvec3 v, double ref, int n, bool seamless, Depth depth, CornerRule rule = CornerRule::average_results)
{
    return cube_compare_taps(cube_linear_taps(v, n, seamless), ref, depth, rule);
}

}  // namespace rkref
