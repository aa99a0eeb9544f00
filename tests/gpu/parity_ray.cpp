// GPU parity for shaders/raykit/ray.glsl (see parity.hpp): the plane, sphere, ellipsoid and box
// intervals with their normals, and the impostor helpers (hit point, normal, window depth in the
// usual and reversed-Z conventions), on the driver against the C++ build, over random rays and the
// harness's adversarial values (±0, denormals, 1e±20, 1e±30, ±FLT_MAX) in every argument.
//
// Where a ray is within rounding of tangency (a graze), the two builds may disagree on hit or miss
// and on t by the square root of a rounding: the contract (ray.glsl) leaves that band open. Those
// rows count as equivalent (ties) when both builds return a well-formed interval and the long
// double half-chord of the ray is inside the band the unit test uses (tests/test_ray.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/ray.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {

parity::Domain coord() { return {-8.0f, 8.0f, false, {0.0f, 1.0f, -1.0f, 2.0f}}; }
parity::Domain dir() { return {-1.0f, 1.0f, false, {0.0f, 1.0f, -1.0f}}; }
parity::Domain radius() { return {0.05f, 4.0f, false, {0.0f, 1.0f, 2.0f}}; }

/// Both rows well-formed intervals (a miss is exactly (FLT_MAX, -FLT_MAX)) whose outputs are
/// finite: the minimum for a row to count as a tie.
bool well_formed(const float* g, const float* c)
{
    for (int k = 0; k < 2; ++k)
        if (!std::isfinite(g[k]) || !std::isfinite(c[k])) return false;
    auto ok = [](const float* t) { return (t[0] == RK_FLT_MAX && t[1] == -RK_FLT_MAX) || t[0] <= t[1]; };
    return ok(g) && ok(c);
}

/// The squared half-chord of the ray o + t d against the ball (w = o - c, radius r) relative to
/// the rounding band (|w| + r) r of tests/test_ray.cpp, in long double.
long double graze(const float* o, const float* d, const float* c, long double r)
{
    const long double w[3] = {(long double)o[0] - c[0], (long double)o[1] - c[1], (long double)o[2] - c[2]};
    const long double dd[3] = {d[0], d[1], d[2]};
    const long double a = dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2];
    if (!(a > 0)) return 1e30L;
    const long double tc = -(w[0] * dd[0] + w[1] * dd[1] + w[2] * dd[2]) / a;
    long double f2 = 0, wl = 0;
    for (int k = 0; k < 3; ++k) {
        const long double f = w[k] + tc * dd[k];
        f2 += f * f;
        wl += w[k] * w[k];
    }
    const long double band = (std::sqrt(wl) + r) * r;
    return band > 0 ? std::abs(r * r - f2) / band : 1e30L;
}

/// A tie: within 1e-3 of tangency relative to the band (far above the 4 ε the unit test allows for
/// hit/miss flips: the driver's sqrt, length and division may round differently).
bool sphere_tie(const float* in, const float* g, const float* c)
{
    return well_formed(g, c) && graze(in, in + 3, in + 6, std::abs((long double)in[9])) < 1e-3L;
}

/// A row with an input of extreme magnitude (>= 1e15, or nonzero and <= 1e-15: the harness's
/// adversarial values): through a matrix, such rays overflow or cancel, and the driver's fused
/// multiply-adds round them differently; the contract there is a finite, well-formed result only.
bool extreme_row(const float* in, int n)
{
    for (int k = 0; k < n; ++k) {
        const float x = std::abs(in[k]);
        if (x >= 1e15f || (x > 0.0f && x <= 1e-15f)) return true;
    }
    return false;
}

/// The plane's t within twice its documented bound (ray.glsl: 2.4 ε (|p0 - o| + |t| |d|) / |n̂·d|)
/// of the long double crossing, for both builds: a near-parallel ray's t is that ill-conditioned.
bool plane_tie(const float* in, const float* g, const float* c)
{
    if (!well_formed(g, c)) return false;
    long double w[3], num = 0, den = 0, nl = 0, wl = 0, dl = 0;
    for (int k = 0; k < 3; ++k) {
        w[k] = (long double)in[6 + k] - in[k];
        num += (long double)in[9 + k] * w[k];
        den += (long double)in[9 + k] * in[3 + k];
        nl += (long double)in[9 + k] * in[9 + k];
        wl += w[k] * w[k];
        dl += (long double)in[3 + k] * in[3 + k];
    }
    if (!(den != 0) || !(nl > 0)) return false;
    const long double t = num / den, cosd = std::abs(den) / std::sqrt(nl);
    const long double bound = 2 * 2.4L * 5.9604644775390625e-8L * (std::sqrt(wl) + std::abs(t) * std::sqrt(dl)) / cosd;
    const float gt = g[2], ct = c[2];
    return std::abs(gt - t) <= bound && std::abs(ct - t) <= bound;
}

}  // namespace

TEST(GpuParity, Ray)
{
    const char* L = "raykit/ray.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_ray_sphere_normals", L,
                  (coord(), coord(), coord(), dir(), dir(), dir(), coord(), coord(), coord(), radius()), 8,
                  vec3 ne; vec3 nx;
                  vec2 t = rk_ray_sphere_normals(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), vec3(a[6], a[7], a[8]), a[9], ne, nx);
                  o[0] = t.x; o[1] = t.y; o[2] = ne.x; o[3] = ne.y; o[4] = ne.z; o[5] = nx.x; o[6] = nx.y; o[7] = nx.z;),
        RK_PARITY("rk_ray_ellipsoid_normals", L,
                  (coord(), coord(), coord(), dir(), dir(), dir(), coord(), coord(), coord(), radius(), radius(), radius()), 8,
                  vec3 ne; vec3 nx;
                  vec2 t = rk_ray_ellipsoid_normals(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), vec3(a[6], a[7], a[8]),
                                                    vec3(a[9], a[10], a[11]), ne, nx);
                  o[0] = t.x; o[1] = t.y; o[2] = ne.x; o[3] = ne.y; o[4] = ne.z; o[5] = nx.x; o[6] = nx.y; o[7] = nx.z;),
        RK_PARITY("rk_ray_ellipsoid_m_normals", L,
                  (coord(), coord(), coord(), dir(), dir(), dir(), dom::range(0.2f, 1.0f), dir(), dir(), dir(),
                   dom::range(0.2f, 1.0f), dir(), dir(), dir(), dom::range(0.2f, 1.0f)), 8,
                  vec3 ne; vec3 nx;
                  // A diagonally dominant map (well-conditioned for the random rows).
                  mat3 m = mat3(vec3(a[6] + 1.0f, 0.2f * a[7], 0.2f * a[8]), vec3(0.2f * a[9], a[10] + 1.0f, 0.2f * a[11]),
                                vec3(0.2f * a[12], 0.2f * a[13], a[14] + 1.0f));
                  vec2 t = rk_ray_ellipsoid_m_normals(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), vec3(0.0f), m, ne, nx);
                  o[0] = t.x; o[1] = t.y; o[2] = ne.x; o[3] = ne.y; o[4] = ne.z; o[5] = nx.x; o[6] = nx.y; o[7] = nx.z;),
        RK_PARITY("rk_ray_box_normals", L,
                  (coord(), coord(), coord(), dir(), dir(), dir(), coord(), coord(), coord(), coord(), coord(), coord()), 8,
                  vec3 ne; vec3 nx;
                  vec2 t = rk_ray_box_normals(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), vec3(a[6], a[7], a[8]),
                                              vec3(a[9], a[10], a[11]), ne, nx);
                  o[0] = t.x; o[1] = t.y; o[2] = ne.x; o[3] = ne.y; o[4] = ne.z; o[5] = nx.x; o[6] = nx.y; o[7] = nx.z;),
        RK_PARITY("rk_ray_plane / rk_ray_plane_t", L,
                  (coord(), coord(), coord(), dir(), dir(), dir(), coord(), coord(), coord(), dir(), dir(), dir()), 3,
                  vec2 t = rk_ray_plane(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), vec3(a[6], a[7], a[8]), vec3(a[9], a[10], a[11]));
                  o[0] = t.x; o[1] = t.y;
                  o[2] = rk_ray_plane_t(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), vec3(a[6], a[7], a[8]), vec3(a[9], a[10], a[11]));),
        // A perspective fragment's view ray (o = 0) against a view-space sphere in front of the camera.
        RK_PARITY("rk_ray_impostor_sphere", L,
                  (dom::range(-0.6f, 0.6f), dom::range(-0.6f, 0.6f), dom::range(-1.0f, -0.5f), dom::range(-2.0f, 2.0f),
                   dom::range(-2.0f, 2.0f), dom::range(-20.0f, -2.0f), radius(), dom::unit()), 8,
                  vec3 k = rk_gb_depth_params(0.1f, a[7] > 0.5f ? 0.0f : 100.0f, a[7] > 0.5f);
                  vec3 p; vec3 n; float depth;
                  bool hit = rk_ray_impostor_sphere(vec3(0.0f), vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), a[6], k, p, n, depth);
                  o[0] = hit ? 1.0f : 0.0f; o[1] = p.x; o[2] = p.y; o[3] = p.z; o[4] = n.x; o[5] = n.y; o[6] = n.z; o[7] = depth;),
        RK_PARITY("rk_ray_impostor_box", L,
                  (dom::range(-0.6f, 0.6f), dom::range(-0.6f, 0.6f), dom::range(-1.0f, -0.5f), dom::range(-2.0f, 2.0f),
                   dom::range(-2.0f, 2.0f), dom::range(-20.0f, -2.0f), radius(), radius(), radius(), dir(), dir(), dom::unit()), 8,
                  vec3 k = rk_gb_depth_params(0.1f, a[11] > 0.5f ? 0.0f : 100.0f, a[11] > 0.5f);
                  // A rotation from the unit quaternion through (a[9], a[10], 0.5) (no trigonometry).
                  vec3 qv = vec3(a[9], a[10], 0.5f);
                  float ql = max(length(qv), 1e-6f);
                  float qx = qv.x / ql; float qy = qv.y / ql; float qz = qv.z / ql; float qw = 0.6f; float s = 1.0f / (1.0f + qw * qw);
                  qx *= sqrt(s); qy *= sqrt(s); qz *= sqrt(s); qw *= sqrt(s);
                  mat3 rot = mat3(vec3(1.0f - 2.0f * (qy * qy + qz * qz), 2.0f * (qx * qy + qz * qw), 2.0f * (qx * qz - qy * qw)),
                                  vec3(2.0f * (qx * qy - qz * qw), 1.0f - 2.0f * (qx * qx + qz * qz), 2.0f * (qy * qz + qx * qw)),
                                  vec3(2.0f * (qx * qz + qy * qw), 2.0f * (qy * qz - qx * qw), 1.0f - 2.0f * (qx * qx + qy * qy)));
                  vec3 p; vec3 n; float depth;
                  bool hit = rk_ray_impostor_box(vec3(0.0f), vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), rot, vec3(a[6], a[7], a[8]),
                                                 k, p, n, depth);
                  o[0] = hit ? 1.0f : 0.0f; o[1] = p.x; o[2] = p.y; o[3] = p.z; o[4] = n.x; o[5] = n.y; o[6] = n.z; o[7] = depth;),
    };
    for (parity::Case& c : cases) {
        if (c.name == "rk_ray_sphere_normals") c.tie = sphere_tie;
        if (c.name == "rk_ray_ellipsoid_normals") {
            // The graze test in the scaled space: (o - c) / radii, d / radii against the unit ball.
            c.tie = [](const float* in, const float* g, const float* cp) {
                float o[3], d[3], z[3] = {0.0f, 0.0f, 0.0f};
                for (int k = 0; k < 3; ++k) {
                    const float r = std::max(std::abs(in[9 + k]), RK_FLT_MIN);
                    o[k] = (in[k] - in[6 + k]) / r;
                    d[k] = in[3 + k] / r;
                }
                if (well_formed(g, cp) && graze(o, d, z, 1.0L) < 1e-3L) return true;
                // A semi-axis below 2^-60 (a disc) may be missed by a driver that flushes denormals:
                // its scaled radius is subnormal there (ray.glsl's contract). Hardware drivers only.
                const float rmin = std::min(std::min(std::abs(in[9]), std::abs(in[10])), std::abs(in[11]));
                const bool miss = g[0] == RK_FLT_MAX && g[1] == -RK_FLT_MAX &&
                                  std::all_of(g + 2, g + 8, [](float v) { return v == 0.0f; });
                return parity::hardware_allowances() && rmin < 8.67361738e-19f && miss;
            };
        }
        if (c.name == "rk_ray_ellipsoid_m_normals")
            c.tie = [](const float* in, const float* g, const float* cp) { return well_formed(g, cp) && extreme_row(in, 15); };
        if (c.name == "rk_ray_plane / rk_ray_plane_t") c.tie = plane_tie;
        if (c.name == "rk_ray_impostor_box") {
            c.tie = [](const float* in, const float* g, const float* cp) {
                return extreme_row(in, 11) && g[7] >= 0.0f && g[7] <= 1.0f && cp[7] >= 0.0f && cp[7] <= 1.0f;
            };
        }
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}
