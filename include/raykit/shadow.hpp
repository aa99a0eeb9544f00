// raykit — shadow.hpp: the CPU build of shaders/raykit/shadow.glsl and the CPU side of shadow
// mapping (Fahlén, "Illumination for Real-Time Rendering of Large Architectural Environments",
// ch. 5): the shadow matrix (Eq. 5.1) for OpenGL's and Vulkan's depth ranges, cascade split
// distances, an orthographic light fit per cascade whose texel grid stays fixed in world space while
// the camera moves (no shimmering edges), and deterministic PCF sample patterns. Point lights' cube
// and dual-paraboloid maps are read through shadow.glsl's omnidirectional section (which includes
// paraboloid.glsl, so this header brings in raykit/paraboloid.hpp).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_shadow.cpp checks that both builds agree on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/common.hpp"
#include "raykit/paraboloid.hpp"  // shadow.glsl reads dual-paraboloid atlases through paraboloid.glsl

namespace raykit {
#include "raykit/shadow.glsl"

/// shadow_bias_matrix: maps the light's clip space to shadow-map coordinates: x, y from [-1, 1] to
/// [0, 1] (texture u, v), z from [-1, 1] to [0, 1] (OpenGL's default depth) or unchanged
/// (`zero_to_one`: Vulkan, D3D, glClipControl). With the same projection used to render the map and
/// to look it up, Vulkan's downward y needs no flip here: row 0 is NDC y = -1 in both.
inline mat4 shadow_bias_matrix(bool zero_to_one)
{
    mat4 b(1.0f);
    b[0][0] = 0.5f;
    b[1][1] = 0.5f;
    b[3][0] = 0.5f;
    b[3][1] = 0.5f;
    if (!zero_to_one) {
        b[2][2] = 0.5f;
        b[3][2] = 0.5f;
    }
    return b;
}

/// shadow_matrix: Eq. 5.1, S = B · P_light · V_light · V_camera⁻¹, formed in double: it takes a
/// point in the camera's view space to (u, v, depth) in the map (rk_sh_project). Pass the identity
/// as camera_view_inverse to look up world-space points.
inline mat4 shadow_matrix(const mat4& light_projection, const mat4& light_view, const mat4& camera_view_inverse, bool zero_to_one)
{
    const glm::dmat4 s = glm::dmat4(shadow_bias_matrix(zero_to_one)) * glm::dmat4(light_projection) * glm::dmat4(light_view) *
                         glm::dmat4(camera_view_inverse);
    return mat4(s);
}

/// cascade_splits: the far ends of `count` (1..4) cascades between near and far by the practical
/// split scheme (Zhang et al. 2006): split_i = lambda · n (f/n)^(i/N) + (1 - lambda) (n + (f - n) i/N),
/// lambda = 0 uniform, 1 logarithmic. Unused entries repeat `far`. Domain: 0 < near < far, lambda in
/// [0, 1] (clamped). rk_sh_cascade_index reads the result.
inline vec4 cascade_splits(float near_plane, float far_plane, int count, float lambda)
{
    const int n = std::min(std::max(count, 1), 4);
    const double nn = std::max(static_cast<double>(near_plane), 1e-30), ff = std::max(static_cast<double>(far_plane), nn);
    const double l = std::min(std::max(static_cast<double>(lambda), 0.0), 1.0);
    vec4 s(far_plane);
    for (int i = 1; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        s[i - 1] = static_cast<float>(i == n ? ff : l * nn * std::pow(ff / nn, t) + (1.0 - l) * (nn + (ff - nn) * t));
    }
    return s;
}

/// An orthographic light fit for one cascade (see fit_cascade).
struct CascadeFit {
    mat4 view{1.0f};        ///< world -> light space (rotation only: the light space's origin is the world's)
    mat4 projection{1.0f};  ///< the orthographic box, for the chosen depth convention
    double left = 0.0, bottom = 0.0;  ///< the box's light-space x and y minimum (texel grid origin)
    double size = 0.0;      ///< the box's width and height (world units): texel * resolution
    double texel = 0.0;     ///< one texel's width (the snapping unit)
    double near_z = 0.0, far_z = 0.0;  ///< the depth range along the light direction (light-space -z)
};

/// fit_cascade: the light's orthographic box for the part of a perspective camera's frustum between
/// view distances split_near and split_far. The box is a bounding sphere's square (its size does not
/// change when the camera turns), and its corner is snapped to whole texels in a light space that
/// does not move with the camera, so a moving camera never shifts the texel grid in world space:
/// shadow edges do not shimmer. camera_to_world: the camera's inverse view matrix (looking down -z);
/// fov_y in radians, aspect = width / height; light_dir: the direction the light travels (unit);
/// caster_margin: how far towards the light the box extends beyond the slice (casters outside the
/// view that shadow it). Computed in double; zero_to_one picks the projection's depth range.
inline CascadeFit fit_cascade(const mat4& camera_to_world, float fov_y, float aspect, float split_near, float split_far,
                              vec3 light_dir, int resolution, float caster_margin, bool zero_to_one)
{
    CascadeFit fit;
    const glm::dmat4 cw(camera_to_world);
    const double ty = std::tan(0.5 * static_cast<double>(fov_y)), tx = ty * static_cast<double>(aspect);
    glm::dvec3 corners[8];
    int k = 0;
    for (double d : {static_cast<double>(split_near), static_cast<double>(split_far)})
        for (int sy : {-1, 1})
            for (int sx : {-1, 1}) corners[k++] = glm::dvec3(cw * glm::dvec4(sx * tx * d, sy * ty * d, -d, 1.0));
    // Light space: a fixed orthonormal basis (right, up, back = -dir), origin at the world's.
    glm::dvec3 dir = glm::normalize(glm::dvec3(light_dir));
    if (!std::isfinite(dir.x + dir.y + dir.z)) dir = glm::dvec3(0.0, -1.0, 0.0);
    const glm::dvec3 ref = std::abs(dir.y) < 0.99 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 right = glm::normalize(glm::cross(dir, ref)), up = glm::cross(right, dir), back = -dir;
    // The slice's bounding sphere: centre the corners' centroid, radius the farthest corner (a
    // rigid motion of the camera keeps the radius, so the box size and texel size never change).
    glm::dvec3 c(0.0);
    for (const glm::dvec3& p : corners) c += p / 8.0;
    double r = 0.0;
    for (const glm::dvec3& p : corners) r = std::max(r, glm::length(p - c));
    const int res = std::max(resolution, 2);
    // The sphere's square, its side rounded up to a fixed grain (so that the rounding of r under
    // rotation never changes it), plus one texel of slack for the snap: the box is W = d + W / res
    // wide, texel = W / res, and the snapped corner (at most one texel below the square's) keeps the
    // whole square inside.
    const double d = std::ceil(2.0 * r * 1024.0) / 1024.0 + 1e-9;
    fit.texel = d / (res - 1);
    fit.size = fit.texel * res;
    const double lx = glm::dot(c, right) - 0.5 * d, ly = glm::dot(c, up) - 0.5 * d;
    fit.left = std::floor(lx / fit.texel) * fit.texel;
    fit.bottom = std::floor(ly / fit.texel) * fit.texel;
    // Depth: light-space z = dot(p, back); the box spans the slice plus the caster margin.
    double zmin = 1e300, zmax = -1e300;
    for (const glm::dvec3& p : corners) {
        zmin = std::min(zmin, glm::dot(p, back));
        zmax = std::max(zmax, glm::dot(p, back));
    }
    fit.near_z = -(zmax + std::max(static_cast<double>(caster_margin), 0.0));  // distance along dir (view looks down -z)
    fit.far_z = -zmin;
    glm::dmat4 v(1.0);
    for (int i = 0; i < 3; ++i) {
        v[i][0] = right[i];
        v[i][1] = up[i];
        v[i][2] = back[i];
    }
    fit.view = mat4(v);
    const double x1 = fit.left + fit.size, y1 = fit.bottom + fit.size;
    const glm::dmat4 p = zero_to_one ? glm::orthoRH_ZO(fit.left, x1, fit.bottom, y1, fit.near_z, fit.far_z)
                                     : glm::orthoRH_NO(fit.left, x1, fit.bottom, y1, fit.near_z, fit.far_z);
    fit.projection = mat4(p);
    return fit;
}

/// vogel_disk: n samples of rk_sh_vogel_disk (phi = 0), for a constant table. Deterministic.
inline std::vector<vec2> vogel_disk(int n)
{
    std::vector<vec2> v;
    for (int i = 0; i < std::max(n, 0); ++i) v.push_back(rk_sh_vogel_disk(static_cast<uint>(i), static_cast<uint>(n), 0.0f));
    return v;
}

/// concentric_disk: Shirley and Chiu's area-preserving map of [-1, 1]² onto the unit disk (squares to
/// rings), which keeps the strata of a stratified square stratified on the disk.
inline vec2 concentric_disk(vec2 s)
{
    const double a = s.x, b = s.y;
    if (a == 0.0 && b == 0.0) return vec2(0.0f);
    const double pi4 = 0.78539816339744830962;
    double r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = pi4 * (b / a);
    } else {
        r = b;
        phi = 2.0 * pi4 - pi4 * (a / b);
    }
    return vec2(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)));
}

/// pcf_jittered_grid: the thesis's PCF pattern: a rows x cols stratified grid on the square, one
/// jittered sample per cell (deterministic for `seed`), mapped to the unit disk by concentric_disk.
/// The thesis used 8 taps (rows 2, cols 4), each a hardware 2x2 compare. rows, cols in 1..64.
inline std::vector<vec2> pcf_jittered_grid(int rows, int cols, uint32_t seed)
{
    const int nr = std::min(std::max(rows, 1), 64), nc = std::min(std::max(cols, 1), 64);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<vec2> v;
    for (int j = 0; j < nr; ++j)
        for (int i = 0; i < nc; ++i) {
            const double x = -1.0 + 2.0 * (i + u(rng)) / nc, y = -1.0 + 2.0 * (j + u(rng)) / nr;
            v.push_back(concentric_disk(vec2(static_cast<float>(x), static_cast<float>(y))));
        }
    return v;
}

/// poisson_disk: n points in the unit disk by best-candidate sampling (Mitchell 1991): each new point
/// is, of `candidates` random ones (30 if <= 0), the farthest from the points so far. Deterministic
/// for `seed`; the closest pair is at least 0.6 / sqrt(n) apart for n in 4..256 (tested).
inline std::vector<vec2> poisson_disk(int n, uint32_t seed, int candidates = 30)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int k = candidates > 0 ? candidates : 30;
    std::vector<glm::dvec2> pts;
    for (int i = 0; i < std::max(n, 0); ++i) {
        glm::dvec2 best(0.0);
        double best_d = -1.0;
        for (int c = 0; c < k; ++c) {
            glm::dvec2 p;
            do {
                p = glm::dvec2(u(rng), u(rng));
            } while (glm::dot(p, p) > 1.0);
            double d = 1e300;
            for (const glm::dvec2& q : pts) d = std::min(d, glm::length(p - q));
            if (d > best_d) {
                best_d = d;
                best = p;
            }
        }
        pts.push_back(best);
    }
    std::vector<vec2> out;
    for (const glm::dvec2& p : pts) out.push_back(vec2(p));
    return out;
}

}  // namespace raykit
