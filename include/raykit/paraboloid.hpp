// raykit — paraboloid.hpp: the CPU build of shaders/raykit/paraboloid.glsl plus CPU-only baking:
// cube map (six float images) -> dual-paraboloid atlas with supersampled (box-filtered) texels and
// 2x2 box mips, the inverse (atlas -> cube) for tests, and an octahedral map for comparison.
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_paraboloid.cpp checks that both builds agree on a real driver.
//
// The thesis's offline pipeline (Fahlén 2005 §3.2.3): render a high-resolution cube map per window
// mesh, resample it into a paraboloid map, compress. bake_dual_paraboloid is step 2 for both
// hemispheres at once (the atlas of paraboloid.glsl), filling the guard band with the
// continuation of the projection so that the seam is invisible; sample it in a shader with
// paraboloid_sample.glsl.
//
// Images: EnvImage is RGB float, row-major, row 0 first (v = 0, GL's upload order). Cube faces use
// the OpenGL cube-map conventions (GL 4.6 §8.13 table 8.19): order +X, -X, +Y, -Y, +Z, -Z, and for
// a face the texel (i, j) is at (s, t) = ((i + 0.5) / size, (j + 0.5) / size), so the six images
// upload as GL_TEXTURE_CUBE_MAP_POSITIVE_X + face unchanged.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/status.hpp"

namespace raykit {
#include "raykit/paraboloid.glsl"
// The cube-face rule of the cube-map helpers below: shadow.glsl's rk_sh_cube_face_uv (shadow.glsl
// is option-free and includes only common.glsl and paraboloid.glsl; raykit/shadow.hpp's own
// include of it is then a no-op).
#include "raykit/shadow.glsl"

/// An RGB float image: width * height texels, 3 floats each, row-major, row 0 first.
struct EnvImage {
    int width = 0, height = 0;
    std::vector<float> rgb;

    EnvImage() = default;
    /// A black w x h image; a size below 1 gives an empty image (0 x 0), which every bake and
    /// resampling function below refuses with a Status instead of reading it.
    EnvImage(int w, int h)
        : width(w > 0 && h > 0 ? w : 0), height(w > 0 && h > 0 ? h : 0),
          rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3u, 0.0f)
    {
    }
    std::size_t index(int x, int y) const
    {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3u;
    }
    vec3 texel(int x, int y) const
    {
        const std::size_t i = index(x, y);
        return vec3(rgb[i], rgb[i + 1], rgb[i + 2]);
    }
    void set(int x, int y, vec3 c)
    {
        const std::size_t i = index(x, y);
        rgb[i] = c.x;
        rgb[i + 1] = c.y;
        rgb[i + 2] = c.z;
    }
};

/// A cube map: six square faces of `size` texels in GL order +X, -X, +Y, -Y, +Z, -Z.
struct EnvCubeMap {
    int size = 0;
    std::array<EnvImage, 6> faces;
};

/// Whether a cube map can be sampled: size >= 1 and six faces of size x size texels.
inline bool env_cube_valid(const EnvCubeMap& cube)
{
    if (cube.size < 1) return false;
    for (const EnvImage& f : cube.faces) {
        if (f.width != cube.size || f.height != cube.size ||
            f.rgb.size() != static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height) * 3u) {
            return false;
        }
    }
    return true;
}

/// A dual-paraboloid atlas (paraboloid.glsl): levels[0] is 2 half_size x half_size, left half
/// +z (hemi = +1), right half -z; levels[l] is the 2x2 box mip of levels[l - 1]. guard_scale is the
/// g to pass to rk_dual_paraboloid_uv & co; lookups must stay at or below max_lod.
struct DualParaboloidMap {
    int half_size = 0;
    float guard_scale = 1.0f;
    float max_lod = 0.0f;
    /// The seam cross-fade's half-width for rk_dual_paraboloid_seam_weight (in z): the band whose
    /// lookups in the other half stay seam_fade level-0 texels beyond the rim, (r^2 - 1) / (r^2 + 1)
    /// with r = 1 + 2 seam_fade / (guard_scale H); 0 when baked without a fade.
    float seam_band = 0.0f;
    std::vector<EnvImage> levels;
};

/// An octahedral map (Cigolle et al. 2014, "A Survey of Efficient Representations for Independent
/// Unit Vectors", +z hemisphere in the inner diamond), size x size texels, for comparison.
struct OctahedralMap {
    int size = 0;
    EnvImage image;
};

// ---------------------------------------------------------------------------------------------
// Filtering helpers

/// Bilinear lookup at uv (texel centres at (i + 0.5) / size, GL_LINEAR) with clamp-to-edge: the
/// CPU mirror of texture(sampler, uv) on one level.
/// Domain: finite uv with |uv * size| < 2^31 (the texel index is an int); uv outside [0, 1] reads
/// the edge texels. Edge cases: a texel centre returns that texel exactly.
/// Max error vs float64 bilinear interpolation at the same uv: 1.4e-7 for values in [0, 1]
/// (128 x 64 image, uv in [-0.1, 1.1]^2; 2e7 random uv + refinement; tests/test_paraboloid.cpp
/// Bake.BilinearAgainstFloat64 asserts 1e-5). uv * size is exact for power-of-two sizes; otherwise
/// its rounding (an ulp of uv * size) moves the weights by as much.
/// Cost: 4 texel reads, 2 floor, 3 vec3 mix (9 lerps), ~6 flops.
inline vec3 sample_image_bilinear(const EnvImage& img, vec2 uv)
{
    const float x = uv.x * static_cast<float>(img.width) - 0.5f;
    const float y = uv.y * static_cast<float>(img.height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    auto at = [&](int i, int j) {
        return img.texel(std::clamp(i, 0, img.width - 1), std::clamp(j, 0, img.height - 1));
    };
    const vec3 a = glm::mix(at(x0, y0), at(x0 + 1, y0), ax);
    const vec3 b = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), ax);
    return glm::mix(a, b, ay);
}

/// The next mip level by a 2x2 box (GL's glGenerateMipmap for even sizes): the sum of the four
/// quarters, so that texels up to ±FLT_MAX average without overflow (a power-of-two scale is
/// exact: the same bits as a quarter of the sum wherever that is finite and not denormal). Odd
/// sizes (an odd level would mix the halves of an atlas), or an image whose texel count does not
/// match its size: an empty image, described in *st (status.hpp).
inline EnvImage downsample_box(const EnvImage& src, Status* st = nullptr)
{
    detail::reset(st);
    if (src.width % 2 != 0 || src.height % 2 != 0 || src.width < 2 || src.height < 2 ||
        src.rgb.size() != static_cast<std::size_t>(src.width) * static_cast<std::size_t>(src.height) * 3u) {
        detail::report(st, "raykit::downsample_box: both sizes must be even (and the texels match them)");
        return {};
    }
    EnvImage dst(src.width / 2, src.height / 2);
    for (int y = 0; y < dst.height; ++y) {
        for (int x = 0; x < dst.width; ++x) {
            dst.set(x, y, 0.25f * src.texel(2 * x, 2 * y) + 0.25f * src.texel(2 * x + 1, 2 * y) +
                              0.25f * src.texel(2 * x, 2 * y + 1) + 0.25f * src.texel(2 * x + 1, 2 * y + 1));
        }
    }
    return dst;
}

/// A mip chain of `levels` levels (levels[0] = base) by repeated 2x2 boxes. When a level would have
/// an odd size (see downsample_box) or levels < 1: an empty vector, described in *st.
inline std::vector<EnvImage> generate_env_mips(const EnvImage& base, int levels, Status* st = nullptr)
{
    detail::reset(st);
    if (levels < 1) {
        detail::report(st, "raykit::generate_env_mips: levels must be >= 1");
        return {};
    }
    std::vector<EnvImage> chain{base};
    for (int l = 1; l < levels; ++l) {
        chain.push_back(downsample_box(chain.back(), st));
        if (chain.back().width == 0) {
            detail::report(st, "raykit::generate_env_mips: level " + std::to_string(l) + " would have an odd size");
            return {};
        }
    }
    return chain;
}

// ---------------------------------------------------------------------------------------------
// Cube maps (GL conventions)

/// The (not normalised) direction through face coordinates (sc, tc) in [-1, 1] of `face`
/// (GL table 8.19 inverted); values beyond ±1 continue the face's plane (seamless filtering).
inline vec3 cube_face_direction(int face, float sc, float tc)
{
    switch (face) {
    case 0: return vec3(1.0f, -tc, -sc);
    case 1: return vec3(-1.0f, -tc, sc);
    case 2: return vec3(sc, 1.0f, tc);
    case 3: return vec3(sc, -1.0f, -tc);
    case 4: return vec3(sc, -tc, 1.0f);
    default: return vec3(-sc, -tc, -1.0f);
    }
}

namespace detail {
/// (s, t, face) of direction d: rk_sh_cube_face_uv (shadow.glsl), the one cube-face rule that the
/// shaders and the CPU share (OpenGL's Table 8.19; ties between axes x before y before z, +0 and
/// -0 alike), except for two inputs it maps to the centre of +X: the zero vector reads the centre
/// of +Z, and a vector whose components are all denormal is scaled by 2^64 (exact) first, so that
/// it selects the face of its direction.
inline vec3 cube_face_st(vec3 d)
{
    const float m = std::max(std::abs(d.x), std::max(std::abs(d.y), std::abs(d.z)));
    if (m == 0.0f) return vec3(0.5f, 0.5f, 4.0f);
    return rk_sh_cube_face_uv(m < RK_FLT_MIN ? d * 18446744073709551616.0f : d);
}
}  // namespace detail

/// The face a direction selects (largest |component|; ties between axes, at the cube's edges and
/// corners, x before y before z, as rk_sh_cube_face_uv of shadow.glsl, which this is) and its face
/// coordinates sc, tc in [-1, 1] (GL table 8.19): 2 s - 1, 2 t - 1 of rk_sh_cube_face_uv. Max error
/// against the float64 ratios: 9e-8 (1e7 random directions). At a tie either face holds the same
/// point of the shared edge. The zero vector selects +Z's centre. Domain: finite d.
inline int cube_face_select(vec3 d, float& sc, float& tc)
{
    const vec3 r = detail::cube_face_st(d);
    sc = 2.0f * r.x - 1.0f;
    tc = 2.0f * r.y - 1.0f;
    return static_cast<int>(r.z);
}

/// The unit direction of texel (i, j)'s centre on `face` of a cube of `size` texels.
inline vec3 cube_texel_direction(int face, int i, int j, int size)
{
    const float n = static_cast<float>(size);
    return glm::normalize(cube_face_direction(face, 2.0f * (static_cast<float>(i) + 0.5f) / n - 1.0f,
                                              2.0f * (static_cast<float>(j) + 0.5f) / n - 1.0f));
}

namespace detail {
/// Texel (i, j) of `face`, where i, j may be one texel outside the face: such texels are taken
/// from the neighbouring face, at the texel nearest to the continued direction (seamless cube
/// filtering, like GL_TEXTURE_CUBE_MAP_SEAMLESS). A texel outside in both i and j (next to a cube
/// corner) is equally near two faces: it is read from the first in x, y, z order (the tie rule of
/// cube_face_select).
inline vec3 cube_fetch_seamless(const EnvCubeMap& cube, int face, int i, int j)
{
    const int n = cube.size;
    if (i >= 0 && i < n && j >= 0 && j < n) return cube.faces[static_cast<std::size_t>(face)].texel(i, j);
    const float fn = static_cast<float>(n);
    const vec3 d = cube_face_direction(face, 2.0f * (static_cast<float>(i) + 0.5f) / fn - 1.0f,
                                       2.0f * (static_cast<float>(j) + 0.5f) / fn - 1.0f);
    const vec3 st = cube_face_st(d);
    const int i2 = std::clamp(static_cast<int>(std::floor(st.x * fn)), 0, n - 1);
    const int j2 = std::clamp(static_cast<int>(std::floor(st.y * fn)), 0, n - 1);
    return cube.faces[static_cast<std::size_t>(st.z)].texel(i2, j2);
}
}  // namespace detail

/// Seamless bilinear lookup of a cube map along dir (any non-zero length): the CPU mirror of
/// texture(samplerCube, dir) with GL_LINEAR and GL_TEXTURE_CUBE_MAP_SEAMLESS (taps past a face
/// edge come from the adjacent face, at the texel nearest to the continued direction).
/// Domain: finite dir; the zero vector reads +Z's centre. cube.size >= 1 (an empty cube is not
/// checked). Max error, as the angle between the lookup of a self-direction cube (64 texels, one
/// sample per texel) and the direction: 3.7e-3 rad = 0.12 texel (2 / size), at the cube's corners
/// where the off-face taps are nearest-texel (5e6 random directions + refinement); second order
/// inside a face (tests/test_paraboloid.cpp Bake.SelfDirectionMapsTexelsAndLookups asserts 0.15
/// texel).
/// Cost: face selection (rk_sh_cube_face_uv: 3 abs, 1 div), 4 texel reads (an off-face one adds a
/// face direction, a face selection and 2 floor), 2 floor, 3 vec3 mix.
inline vec3 sample_cube_map(const EnvCubeMap& cube, vec3 dir)
{
    const vec3 st = detail::cube_face_st(dir);
    const int face = static_cast<int>(st.z);
    const float n = static_cast<float>(cube.size);
    const float x = st.x * n - 0.5f, y = st.y * n - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const vec3 a = glm::mix(detail::cube_fetch_seamless(cube, face, x0, y0),
                            detail::cube_fetch_seamless(cube, face, x0 + 1, y0), ax);
    const vec3 b = glm::mix(detail::cube_fetch_seamless(cube, face, x0, y0 + 1),
                            detail::cube_fetch_seamless(cube, face, x0 + 1, y0 + 1), ax);
    return glm::mix(a, b, ay);
}

/// Bakes a cube map of `size` texels per face from a function of direction, each texel the mean
/// of supersample x supersample evaluations spread evenly over its area (a box filter in texel
/// space). `env(vec3 unit_dir) -> vec3`. size outside [1, 65536] or supersample outside [1, 64]:
/// an empty map (size 0), described in *st (status.hpp).
/// Max error, self-direction content (env(d) = d), against the float64 texel-centre direction of
/// GL's table 8.19: 4.2e-8 rad with supersample 1 (the texel centre itself); 2.5e-5 rad = 0.0008
/// texel with 4 (the box filter's mean, size 64; tests/test_paraboloid.cpp
/// Bake.SelfDirectionMapsTexelsAndLookups). Cost: 6 size^2 supersample^2 env calls, each with a
/// face direction and a normalisation.
template <class F>
EnvCubeMap bake_cube_map(int size, F&& env, int supersample = 4, Status* st = nullptr)
{
    detail::reset(st);
    if (size < 1 || size > 65536 || supersample < 1 || supersample > 64) {
        detail::report(st, "raykit::bake_cube_map: size in [1, 65536] and supersample in [1, 64] required");
        return {};
    }
    EnvCubeMap cube;
    cube.size = size;
    const float n = static_cast<float>(size), ss = static_cast<float>(supersample);
    for (int f = 0; f < 6; ++f) {
        EnvImage img(size, size);
        for (int j = 0; j < size; ++j) {
            for (int i = 0; i < size; ++i) {
                vec3 sum(0.0f);
                for (int b = 0; b < supersample; ++b) {
                    for (int a = 0; a < supersample; ++a) {
                        const float u = (static_cast<float>(i) + (static_cast<float>(a) + 0.5f) / ss) / n;
                        const float v = (static_cast<float>(j) + (static_cast<float>(b) + 0.5f) / ss) / n;
                        sum += env(glm::normalize(cube_face_direction(f, 2.0f * u - 1.0f, 2.0f * v - 1.0f)));
                    }
                }
                img.set(i, j, sum / (ss * ss));
            }
        }
        cube.faces[static_cast<std::size_t>(f)] = std::move(img);
    }
    return cube;
}

// ---------------------------------------------------------------------------------------------
// Dual-paraboloid atlas

/// Options of bake_dual_paraboloid.
struct DualParaboloidBakeOptions {
    int half_size = 256;   ///< H: the atlas is 2H x H texels; a multiple of 2^ceil(max_lod)
    float max_lod = 0.0f;  ///< largest LOD lookups will use: sets the guard and ceil(max_lod) + 1 mips
    int supersample = 0;   ///< samples per texel and axis; 0 = automatic (see bake_dual_paraboloid)
    /// The map's frame in the source's (world) space, columns = the map's x, y, z axes (e.g.
    /// rk_paraboloid_frame(N, up, +1) for a window): a texel's world direction is frame * local.
    /// Look up with the local direction world * frame. Identity: the map is in world space.
    mat3 frame = mat3(1.0f);
    /// Seam cross-fade width in level-0 texels (0: none, the thesis's hard seam; a few texels is the
    /// intended range). The guard grows by as much so that both halves can be read across the seam
    /// at every LOD up to max_lod; the map's seam_band is the matching band for
    /// rk_dual_paraboloid_seam_weight and the seamless lookups.
    float seam_fade = 0.0f;
};

/// The guard scale bake_dual_paraboloid uses for these options:
/// rk_dual_paraboloid_guard_scale(H, rk_paraboloid_filter_footprint(max_lod) + seam_fade).
inline float dual_paraboloid_guard_scale(const DualParaboloidBakeOptions& o)
{
    const float fade = o.seam_fade > 0.0f ? std::min(o.seam_fade, 65536.0f) : 0.0f;
    return rk_dual_paraboloid_guard_scale(static_cast<float>(o.half_size), rk_paraboloid_filter_footprint(o.max_lod) + fade);
}

/// Bakes a dual-paraboloid atlas from a function of direction `env(vec3 unit_dir) -> vec3`: every
/// texel of level 0 (guard band included, which receives the continuation directions of
/// rk_dual_paraboloid_dir) is the mean of supersample^2 evaluations spread evenly over its area;
/// then ceil(max_lod) 2x2 box mips. supersample 0 means 4. half_size < 2, above 32768 or not a
/// multiple of 2^ceil(max_lod), max_lod outside [0, 16], supersample outside [0, 64], or a guard
/// that eats the whole map (guard scale < 0.25): an empty map (half_size 0), described in *st.
/// Max error, self-direction content, supersample 1: every texel (guard band included) within
/// 9.4e-8 rad of the float64 direction of its centre from the atlas layout documented in
/// paraboloid.glsl (tests/test_paraboloid.cpp Bake.SelfDirectionMapsTexelsAndLookups; the layout
/// itself is pinned by hand in DualParaboloid.AtlasLayoutPinnedByHand).
/// Cost: 2 H^2 supersample^2 (env + rk_dual_paraboloid_dir + a mat3 product), then the mips
/// (4 reads and adds per texel of each coarser level).
template <class F>
DualParaboloidMap bake_dual_paraboloid_fn(F&& env, const DualParaboloidBakeOptions& o, Status* st = nullptr)
{
    detail::reset(st);
    if (!(o.max_lod >= 0.0f && o.max_lod <= 16.0f) || o.supersample < 0 || o.supersample > 64) {
        detail::report(st, "raykit::bake_dual_paraboloid: max_lod in [0, 16] and supersample in [0, 64] required");
        return {};
    }
    const int extra = static_cast<int>(std::ceil(o.max_lod));
    if (o.half_size < 2 || o.half_size > 32768 || o.half_size % (1 << extra) != 0) {
        detail::report(st, "raykit::bake_dual_paraboloid: half_size must be in [2, 32768] and a multiple of "
                           "2^ceil(max_lod)");
        return {};
    }
    if (dual_paraboloid_guard_scale(o) < 0.25f) {
        detail::report(st, "raykit::bake_dual_paraboloid: the guard band for max_lod leaves less than a quarter of "
                           "the map");
        return {};
    }
    DualParaboloidMap map;
    map.half_size = o.half_size;
    map.max_lod = o.max_lod;
    map.guard_scale = dual_paraboloid_guard_scale(o);
    if (o.seam_fade > 0.0f) {
        // The guard holds seam_fade texels beyond the rim: st radius r = 1 + fade_st. A direction at
        // z = -b reads the other half at radius sqrt((1 + b) / (1 - b)), so the band whose far
        // edge lands exactly at r is b = (r^2 - 1) / (r^2 + 1) (slightly less than fade_st): every
        // tap of the fade then stays inside the guard.
        const double r = 1.0 + 2.0 * std::min(o.seam_fade, 65536.0f) / (static_cast<double>(map.guard_scale) * o.half_size);
        map.seam_band = static_cast<float>((r * r - 1.0) / (r * r + 1.0));
    }
    const int ssi = o.supersample == 0 ? 4 : o.supersample;
    const float ss = static_cast<float>(ssi);
    const int w = 2 * o.half_size, h = o.half_size;
    EnvImage base(w, h);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            vec3 sum(0.0f);
            for (int b = 0; b < ssi; ++b) {
                for (int a = 0; a < ssi; ++a) {
                    const vec2 uv(
                        (static_cast<float>(i) + (static_cast<float>(a) + 0.5f) / ss) / static_cast<float>(w),
                        (static_cast<float>(j) + (static_cast<float>(b) + 0.5f) / ss) / static_cast<float>(h));
                    sum += env(o.frame * rk_dual_paraboloid_dir(uv, map.guard_scale));
                }
            }
            base.set(i, j, sum / (ss * ss));
        }
    }
    map.levels = generate_env_mips(base, extra + 1);
    return map;
}

/// The automatic supersampling of bake_dual_paraboloid for a cube of cube_size texels: enough
/// samples per axis to take about two per cube texel where the atlas's texels are largest (the
/// centre of each half spans 4 / (g H) rad, a cube texel at most 2 / cube_size):
/// ceil(4 cube_size / (g H)), clamped to [2, 16].
inline int dual_paraboloid_auto_supersample(int cube_size, int half_size, float guard_scale)
{
    const float r = 4.0f * static_cast<float>(cube_size) / (guard_scale * static_cast<float>(half_size));
    return std::clamp(static_cast<int>(std::ceil(r)), 2, 16);
}

/// The thesis's step 2: a cube map resampled into a dual-paraboloid atlas (both hemispheres, the
/// guard band filled), each texel the box-filtered mean of supersampled seamless bilinear cube
/// lookups (options.supersample = 0: dual_paraboloid_auto_supersample), plus ceil(max_lod) mips.
/// Fails as bake_dual_paraboloid_fn, and for an empty cube (an empty map, described in *st).
/// Max error, self-direction cube of 64 texels into H = 64 (max_lod 2, automatic supersampling):
/// 1.2e-3 rad = 0.056 of the local texel angle against the float64 direction of every texel
/// centre from the documented layout, guard band included (tests/test_paraboloid.cpp
/// Bake.SelfDirectionCubeConvertsToSelfDirectionParaboloid asserts 0.1 texel). Filtering: from a
/// 128-texel cube of checkers with cells of 0.7 to 2.2 atlas texels (H = 32), every texel within
/// 0.054 (RMS 0.012, contrast 1) of the float64 solid-angle-weighted mean of the content over its
/// footprint (the box filter is uniform in st, not in solid angle: 0.016 of that on the rim; most
/// of the rest is the cube's own resolution); one sample per texel errs by 0.60 (RMS 0.22), 2 x 2
/// by 0.31 (RMS 0.06) (Bake.CubeToDualParaboloidTexelsAreSolidAngleMeans asserts 0.1, RMS 0.02).
/// Cost: 2 H^2 supersample^2 sample_cube_map + rk_dual_paraboloid_dir, then the mips.
inline DualParaboloidMap bake_dual_paraboloid(const EnvCubeMap& cube, DualParaboloidBakeOptions o, Status* st = nullptr)
{
    detail::reset(st);
    if (!env_cube_valid(cube)) {
        detail::report(st, "raykit::bake_dual_paraboloid: empty or inconsistent cube map");
        return {};
    }
    if (o.supersample == 0) {
        o.supersample = dual_paraboloid_auto_supersample(cube.size, o.half_size, dual_paraboloid_guard_scale(o));
    }
    return bake_dual_paraboloid_fn([&cube](vec3 d) { return sample_cube_map(cube, d); }, o, st);
}

/// Lookup of a dual-paraboloid atlas along dir (any non-zero length) at an explicit LOD, clamped
/// to [0, max_lod]: bilinear within a level, linear between levels (GL_LINEAR_MIPMAP_LINEAR with
/// textureLod and GL_CLAMP_TO_EDGE), at rk_dual_paraboloid_uv. The CPU mirror of
/// rk_dual_paraboloid_sample_lod.
/// Domain: any finite dir (zero counts as +z), any lod (clamped to [0, min(max_lod, levels - 1)];
/// NaN reads level 0).
/// Edge cases: an empty map returns (0, 0, 0); on the seam (z = ±0) the +z half is read, and the
/// guard keeps every tap inside the half (DualParaboloid.GuardKeepsEveryTapInItsHalf).
/// Max error, as the angle between the lookup of a self-direction atlas (H = 64, LOD 0, one sample
/// per texel) and the direction: 1.7e-4 rad = 0.0026 texel (4 / (g H)), second order everywhere
/// (5e6 random directions + refinement; Bake.SelfDirectionMapsTexelsAndLookups); baked from a
/// 96-texel cube (max_lod 2), within a texel of the seam (|st| > 1 - h, h = 2^lod 2 / (g H) the
/// LOD's texel in st) 1.6e-4, 6.0e-4 and 2.4e-3 rad at LOD 0, 1, 2, below the band one texel
/// further in (1.7e-4, 6.4e-4, 2.8e-3; the guard band's content is right). Not continuous across
/// the seam: the halves are mirror images, so their bilinear errors across z = 0 have opposite
/// signs and the lookup jumps by up to h^2 / 4 rad (2.7e-4, 1.1e-3, 4.4e-3: twice either side's
/// error, 1.6 times the band's) (Bake.SeamIsContinuous). A map baked with
/// DualParaboloidBakeOptions::seam_fade cross-fades the halves over |z| < map.seam_band (as
/// rk_dual_paraboloid_sample_lod_seamless): with 2 texels (g 0.875 instead of 0.9375 for H = 64,
/// max_lod 2: 7 % fewer texels across the disk) the jump falls to the probes' own spacing (2.3e-6
/// rad at every LOD), and the error inside the band (1.9e-4, 6.8e-4, 2.6e-3 rad at LOD 0, 1, 2)
/// stays below the error beside it (2.0e-4, 7.1e-4, 2.7e-3) (Bake.SeamFadeRemovesTheJump).
/// Cost: rk_dual_paraboloid_uv + 1 bilinear lookup (2 and a vec3 mix at a fractional LOD); twice
/// that inside a fade band.
inline vec3 sample_dual_paraboloid(const DualParaboloidMap& map, vec3 dir, float lod = 0.0f)
{
    if (map.levels.empty()) return vec3(0.0f);
    const float top = static_cast<float>(map.levels.size() - 1);
    const float l = lod > 0.0f ? std::min(lod, std::min(map.max_lod, top)) : 0.0f;  // NaN: 0
    const float l0 = std::floor(l);
    const std::size_t i0 = static_cast<std::size_t>(l0);
    auto at = [&](vec2 uv) {
        const vec3 a = sample_image_bilinear(map.levels[i0], uv);
        return l == l0 ? a : glm::mix(a, sample_image_bilinear(map.levels[i0 + 1], uv), l - l0);
    };
    // With a seam fade (map.seam_band > 0), the two halves are mixed across the seam, as
    // rk_dual_paraboloid_sample_lod_seamless does.
    const float w = rk_dual_paraboloid_seam_weight(dir, map.seam_band);
    if (w >= 1.0f || w <= 0.0f) return at(rk_dual_paraboloid_uv_half(dir, map.guard_scale, w > 0.0f ? 1.0f : -1.0f));
    const vec3 plus = at(rk_dual_paraboloid_uv_half(dir, map.guard_scale, 1.0f));
    const vec3 minus = at(rk_dual_paraboloid_uv_half(dir, map.guard_scale, -1.0f));
    return minus * (1.0f - w) + plus * w;
}

/// A single square paraboloid map (the thesis's per-window map, Fahlén 2005 §3.2.3) of size x size
/// texels for the hemisphere `hemi` (the thesis: -1, d0 = -z) of the local frame `frame` (columns =
/// local axes in world space, e.g. rk_paraboloid_frame(N, up, -1), whose d0 is the window normal
/// N), texels at uv = rk_paraboloid_uv(st, guard_scale), i.e. st = (2 uv - 1) / guard_scale: with
/// guard_scale 1 the rim touches the edges (the thesis's layout), with g < 1 a guard ring of
/// continuation directions surrounds the disk. Each texel is the mean of supersample^2
/// evaluations of env(world_dir) over its area. Look up with rk_paraboloid_sample_biased or
/// sample_paraboloid. size outside [1, 65536], supersample outside [1, 64] or guard_scale outside
/// [RK_PARABOLOID_GUARD_MIN, 1]: an empty image, described in *st (status.hpp).
/// Max error, self-direction content (identity frame, hemi -1, g = 1, 64 texels), against the
/// float64 direction of each texel centre (st = (2 uv - 1) / g, decoded): 4.3e-8 rad with
/// supersample 1, 1.5e-7 rad with 4 (tests/test_paraboloid.cpp
/// Bake.SelfDirectionMapsTexelsAndLookups). Cost: size^2 supersample^2 (rk_paraboloid_decode + a
/// mat3 product + env).
template <class F>
EnvImage bake_paraboloid_fn(F&& env, int size, mat3 frame, float hemi, float guard_scale = 1.0f, int supersample = 4,
                            Status* status = nullptr)
{
    detail::reset(status);
    if (size < 1 || size > 65536 || supersample < 1 || supersample > 64 ||
        !(guard_scale >= RK_PARABOLOID_GUARD_MIN && guard_scale <= 1.0f)) {
        detail::report(status, "raykit::bake_paraboloid: size in [1, 65536], supersample in [1, 64], guard_scale in "
                           "[RK_PARABOLOID_GUARD_MIN, 1] required");
        return {};
    }
    EnvImage img(size, size);
    const float n = static_cast<float>(size), ss = static_cast<float>(supersample);
    for (int j = 0; j < size; ++j) {
        for (int i = 0; i < size; ++i) {
            vec3 sum(0.0f);
            for (int b = 0; b < supersample; ++b) {
                for (int a = 0; a < supersample; ++a) {
                    const float u = (static_cast<float>(i) + (static_cast<float>(a) + 0.5f) / ss) / n;
                    const float v = (static_cast<float>(j) + (static_cast<float>(b) + 0.5f) / ss) / n;
                    const vec2 st((2.0f * u - 1.0f) / guard_scale, (2.0f * v - 1.0f) / guard_scale);
                    sum += env(frame * rk_paraboloid_decode(st, hemi));
                }
            }
            img.set(i, j, sum / (ss * ss));
        }
    }
    return img;
}

/// bake_paraboloid_fn from a cube map (seamless bilinear lookups; supersample 0 chooses about two
/// samples per cube texel where the map's texels are largest, as for the atlas). Fails as
/// bake_paraboloid_fn, and for an empty cube (an empty image, described in *st).
/// Max error: a window-frame map (64 texels) from a self-direction cube of 48 texels looks up
/// within 1.5e-3 rad of the direction over the half-space the window reflects (5e6 random
/// directions + refinement; tests/test_paraboloid.cpp Bake.WindowFrameMapsAndSingleParaboloid
/// asserts 0.01 rad).
/// Cost: size^2 supersample^2 sample_cube_map.
inline EnvImage bake_paraboloid(const EnvCubeMap& cube, int size, mat3 frame, float hemi, float guard_scale = 1.0f,
                                int supersample = 0, Status* st = nullptr)
{
    detail::reset(st);
    if (!env_cube_valid(cube)) {
        detail::report(st, "raykit::bake_paraboloid: empty or inconsistent cube map");
        return {};
    }
    if (supersample == 0) {
        const float r = 4.0f * static_cast<float>(cube.size) /
                        (std::max(guard_scale, RK_PARABOLOID_GUARD_MIN) * static_cast<float>(std::max(size, 1)));
        supersample = std::clamp(static_cast<int>(std::ceil(r)), 2, 16);
    }
    return bake_paraboloid_fn([&cube](vec3 d) { return sample_cube_map(cube, d); }, size, frame, hemi, guard_scale,
                              supersample, st);
}

/// Bilinear lookup of a single paraboloid map along the local direction dir (world * frame),
/// directions behind the map clamped to the rim: the CPU mirror of rk_paraboloid_sample_biased
/// at bias 0 on the base level.
/// Domain: any finite dir (zero counts as d0). Edge cases: directions behind the map (|st| > 1)
/// read the rim point with the same st direction; the exact antipode of d0 has st = (0, 0) and
/// reads the centre.
/// Max error, as the angle between the lookup of a self-direction map (g = 1, 64 texels, one
/// sample per texel) and the direction, over the hemisphere: 1.6e-2 rad = 0.25 of the centre
/// texel (4 / size; 5e6 random directions + refinement), on the rim, where g = 1 puts the rim on
/// the image edge and clamp-to-edge returns the last texel centre (half a rim texel, 1 / size rad):
/// bake with g < 1 for a guard ring. Elsewhere second order (tests/test_paraboloid.cpp
/// Bake.SelfDirectionMapsTexelsAndLookups).
/// Cost: rk_paraboloid_encode, 1 dot (+ 1 sqrt, 1 div behind the map), rk_paraboloid_uv, 1
/// bilinear lookup.
inline vec3 sample_paraboloid(const EnvImage& map, vec3 dir, float hemi, float guard_scale = 1.0f)
{
    vec2 st = rk_paraboloid_encode(dir, hemi);
    // |st| reaches 1e30 near the antipode: normalised by its largest component first, so that the
    // squared length cannot overflow (to inf, which would scale st to the centre).
    const float m = std::max(std::abs(st.x), std::abs(st.y));
    if (m > 0.0f) {
        const vec2 q = st / m;
        const float lq = std::sqrt(glm::dot(q, q));
        if (m * lq > 1.0f) st = q / lq;
    }
    return sample_image_bilinear(map, rk_paraboloid_uv(st, guard_scale));
}

/// The inverse resampling (atlas -> cube), for tests: each cube texel the mean of
/// supersample^2 level-0 lookups (sample_dual_paraboloid) over its area. Fails as bake_cube_map,
/// and for a map without levels (an empty cube, described in *st).
inline EnvCubeMap cube_from_dual_paraboloid(const DualParaboloidMap& map, int size, int supersample = 2,
                                            Status* st = nullptr)
{
    if (map.levels.empty() || map.levels[0].width != 2 * map.half_size || map.levels[0].height != map.half_size ||
        map.half_size < 1) {
        detail::report(st, "raykit::cube_from_dual_paraboloid: empty or inconsistent map");
        return {};
    }
    return bake_cube_map(
        size, [&map](vec3 d) { return sample_dual_paraboloid(map, d, 0.0f); }, supersample, st);
}

// ---------------------------------------------------------------------------------------------
// Octahedral map (C++ only: the comparison of issue 5 item 6)

/// Octahedral encoding of a direction (any non-zero length; zero gives the +z pole) to p in
/// [-1, 1]^2: p = (x, y) / (|x| + |y| + |z|), folded over the diagonals for z < 0.
/// Domain: any finite dir (normalised first, robustly; all-denormal counts as zero). Edge cases:
/// z = -0 is not folded; x = 0 or y = 0 below the equator folds to the + side (Cigolle's
/// signNotZero); -z maps to the corner (1, 1), the same direction as the other three corners.
/// Max error vs float64 (Cigolle et al. 2014's listing): 1.5e-7 in p; dir -> p -> dir through
/// octahedral_decode within 3.3e-7 rad (2e7 random directions + refinement;
/// tests/test_paraboloid.cpp Octahedral.EncodeDecodeAgainstFloat64 asserts 3e-7 and 5e-7).
/// Cost: rk_paraboloid_normalize (1 div, 1 rsqrt) + 2 div + ~8 flops.
inline vec2 octahedral_encode(vec3 dir)
{
    const vec3 d = rk_paraboloid_normalize(dir, vec3(0.0f, 0.0f, 1.0f));
    const float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    vec2 p(d.x / l1, d.y / l1);
    if (d.z < 0.0f) {
        const vec2 s(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
        p = vec2((1.0f - std::abs(p.y)) * s.x, (1.0f - std::abs(p.x)) * s.y);
    }
    return p;
}

/// The unit direction of octahedral coordinates p in [-1, 1]^2 (clamped).
/// Domain: finite p; outside [-1, 1]^2 clamped. Edge cases: the four corners all give -z, (0, 0)
/// gives +z. Max error vs float64: 1.1e-7 rad (2e7 random p + refinement; tests/test_paraboloid.cpp
/// Octahedral.EncodeDecodeAgainstFloat64 asserts 3e-7). Cost: ~8 flops + 1 normalisation
/// (1 sqrt, 1 div).
inline vec3 octahedral_decode(vec2 p_in)
{
    const vec2 p = glm::clamp(p_in, vec2(-1.0f), vec2(1.0f));
    vec3 v(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
    if (v.z < 0.0f) {
        const vec2 s(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f);
        v = vec3((1.0f - std::abs(p.y)) * s.x, (1.0f - std::abs(p.x)) * s.y, v.z);
    }
    return glm::normalize(v);
}

/// Bakes an octahedral map of size x size texels (uv = 0.5 p + 0.5) from a function of direction,
/// supersample^2 evaluations per texel. size outside [2, 65536] or supersample outside [1, 64]: an
/// empty map (size 0), described in *st (status.hpp).
/// Max error, self-direction content, 64 texels, against the float64 decode of each texel centre:
/// 4.2e-8 rad with supersample 1; with 4, 4.9e-3 rad = 0.064 of the largest texel angle (0.0765
/// rad) for texels that straddle a fold, where the mapping has a kink and the box filter's mean
/// leaves the centre direction (tests/test_paraboloid.cpp Bake.SelfDirectionMapsTexelsAndLookups).
/// Cost: size^2 supersample^2 (octahedral_decode + env).
template <class F>
OctahedralMap bake_octahedral_fn(int size, F&& env, int supersample = 4, Status* st = nullptr)
{
    detail::reset(st);
    if (size < 2 || size > 65536 || supersample < 1 || supersample > 64) {
        detail::report(st, "raykit::bake_octahedral: size in [2, 65536] and supersample in [1, 64] required");
        return {};
    }
    OctahedralMap map;
    map.size = size;
    map.image = EnvImage(size, size);
    const float n = static_cast<float>(size), ss = static_cast<float>(supersample);
    for (int j = 0; j < size; ++j) {
        for (int i = 0; i < size; ++i) {
            vec3 sum(0.0f);
            for (int b = 0; b < supersample; ++b) {
                for (int a = 0; a < supersample; ++a) {
                    const float u = (static_cast<float>(i) + (static_cast<float>(a) + 0.5f) / ss) / n;
                    const float v = (static_cast<float>(j) + (static_cast<float>(b) + 0.5f) / ss) / n;
                    sum += env(octahedral_decode(vec2(2.0f * u - 1.0f, 2.0f * v - 1.0f)));
                }
            }
            map.image.set(i, j, sum / (ss * ss));
        }
    }
    return map;
}

/// An octahedral map resampled from a cube map (supersample 0: ceil(5 cube_size / size) clamped to
/// [2, 16], about two samples per cube texel where the octahedral texels are largest). Fails as
/// bake_octahedral_fn, and for an empty cube (an empty map, described in *st). Accuracy against the source cube at the cube's
/// texel budget: tests/test_paraboloid.cpp Accuracy.EqualTexelBudgetsDualParaboloidVsOctahedral
/// (56.2 dB PSNR from a 64-texel cube of a synthetic city, vs 51.8 dB for the dual paraboloid).
/// Cost: size^2 supersample^2 (octahedral_decode + sample_cube_map).
inline OctahedralMap bake_octahedral(const EnvCubeMap& cube, int size, int supersample = 0, Status* st = nullptr)
{
    detail::reset(st);
    if (!env_cube_valid(cube)) {
        detail::report(st, "raykit::bake_octahedral: empty or inconsistent cube map");
        return {};
    }
    if (supersample == 0) {
        supersample = std::clamp(
            static_cast<int>(std::ceil(5.0f * static_cast<float>(cube.size) / static_cast<float>(std::max(size, 1)))),
            2, 16);
    }
    return bake_octahedral_fn(
        size, [&cube](vec3 d) { return sample_cube_map(cube, d); }, supersample, st);
}

/// Bilinear lookup of an octahedral map along dir with the map's fold-over edges (a tap past an
/// edge reads the texel mirrored across the edge's midpoint, as a one-texel gutter would provide).
/// Domain: any finite dir (zero counts as +z); map.size >= 2.
/// Max error, as the angle between the lookup of a self-direction map (64 texels, one sample per
/// texel) and the direction: 2.0e-2 rad = 0.25 of the largest texel angle (0.0765 rad; 5e6 random
/// directions + refinement), next to the folds (p.x = 0, p.y = 0 and the inner diamond's edges),
/// where bilinear interpolation across the mapping's kink errs to first order
/// (tests/test_paraboloid.cpp Bake.SelfDirectionMapsTexelsAndLookups asserts 0.3).
/// Cost: octahedral_encode, 4 texel reads (with the edge mirroring), 2 floor, 3 vec3 mix.
inline vec3 sample_octahedral(const OctahedralMap& map, vec3 dir)
{
    const int n = map.size;
    const vec2 p = octahedral_encode(dir);
    const float x = (0.5f * p.x + 0.5f) * static_cast<float>(n) - 0.5f;
    const float y = (0.5f * p.y + 0.5f) * static_cast<float>(n) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    auto at = [&](int i, int j) {
        if (i < 0) {
            i = -1 - i;
            j = n - 1 - j;
        }
        if (i >= n) {
            i = 2 * n - 1 - i;
            j = n - 1 - j;
        }
        if (j < 0) {
            j = -1 - j;
            i = n - 1 - i;
        }
        if (j >= n) {
            j = 2 * n - 1 - j;
            i = n - 1 - i;
        }
        return map.image.texel(std::clamp(i, 0, n - 1), std::clamp(j, 0, n - 1));
    };
    const vec3 a = glm::mix(at(x0, y0), at(x0 + 1, y0), ax);
    const vec3 b = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), ax);
    return glm::mix(a, b, ay);
}

}  // namespace raykit
