// Test harness shared by the interior-mapping tests: float helpers, grids, and random test rays
// on box buildings (ordinary and adversarial kinds) for the float64 brute-force tracer of
// reference/interior_ref.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "raykit/interior_mapping.hpp"
#include "reference/interior_ref.hpp"

namespace imtest {

using raykit::rk_im_grid;
using raykit::rk_im_hit;

inline double dd(float x) { return static_cast<double>(x); }

inline bool finite_hit(const rk_im_hit& h)
{
    const float v[] = {h.t, h.depth, h.uv.x, h.uv.y, h.uv_dx.x, h.uv_dx.y, h.uv_dy.x, h.uv_dy.y, h.pos.x, h.pos.y, h.pos.z};
    for (float x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

inline rk_im_grid make_grid(glm::vec3 room, glm::vec3 origin)
{
    rk_im_grid g;
    g.room_size = room;
    g.origin = origin;
    return g;
}

inline ref_im::Grid ref_grid(const rk_im_grid& g)
{
    ref_im::Grid r;
    for (int a = 0; a < 3; ++a) {
        r.room[a] = dd(g.room_size[a]);
        r.origin[a] = dd(g.origin[a]);
    }
    return r;
}

/// One test ray: a box building [lo, hi] (float, object space), the facade (axis, sign) that p
/// lies on, the camera, the grid.
struct Ray {
    rk_im_grid g;
    glm::vec3 lo, hi, p, cam;
    int axis, sign;
};

enum class Kind { random, on_grid, on_grid_jitter, axis_parallel, grazing, close_camera, huge, denormal };

/// A random building, facade point and camera of the given kind.
inline Ray make_ray(std::mt19937& rng, Kind kind)
{
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    auto uni = [&](float a, float b) { return a + (b - a) * U(rng); };
    Ray r;
    const float base = kind == Kind::huge ? uni(1e4f, 1e5f) : 0.0f;
    r.g = make_grid(glm::vec3(uni(0.7f, 5.0f), uni(2.5f, 4.0f), uni(0.7f, 5.0f)),
                    glm::vec3(base + uni(-10.0f, 10.0f), uni(-10.0f, 10.0f), base + uni(-10.0f, 10.0f)));
    if (kind == Kind::denormal) r.g.origin = glm::vec3(uni(-10.0f, -1.0f), uni(-10.0f, -1.0f), uni(-10.0f, -1.0f));
    const bool grid_faces = kind == Kind::on_grid || kind == Kind::on_grid_jitter;
    for (int a = 0; a < 3; ++a) {
        const float rs = r.g.room_size[a];
        const int k0 = static_cast<int>(std::floor(U(rng) * 6.0f)) - 3;
        const int nk = 1 + static_cast<int>(std::floor(U(rng) * 8.0f));
        if (grid_faces) {
            r.lo[a] = r.g.origin[a] + static_cast<float>(k0) * rs;
            r.hi[a] = r.g.origin[a] + static_cast<float>(k0 + nk) * rs;
        } else {
            // Faces off the grid, at least 4 nudges away from any plane (no facade ambiguity).
            auto off_grid = [&](float x) {
                for (int it = 0; it < 100; ++it) {
                    const double qd = (dd(x) - dd(r.g.origin[a])) / dd(rs);
                    if (std::abs(qd - std::round(qd)) > 4.0 * 0.0009765625 + 1e-4 * (1.0 + std::abs(qd))) break;
                    x += 0.01f * rs;
                }
                return x;
            };
            r.lo[a] = off_grid(r.g.origin[a] + (static_cast<float>(k0) + uni(0.0f, 1.0f)) * rs);
            r.hi[a] = off_grid(r.lo[a] + (static_cast<float>(nk) + uni(0.0f, 1.0f)) * rs);
        }
    }
    if (kind == Kind::denormal) {
        for (int a = 0; a < 3; ++a) {
            r.lo[a] = std::min(r.lo[a], -1.0f);
            r.hi[a] = std::max(r.hi[a], 1.0f);
        }
    }
    // Facade: x or z sides (both signs) or the roof.
    const int pick = static_cast<int>(std::floor(U(rng) * 5.0f)) % 5;
    r.axis = pick < 2 ? 0 : (pick < 4 ? 2 : 1);
    r.sign = (pick == 1 || pick == 3) ? -1 : 1;
    for (int a = 0; a < 3; ++a) r.p[a] = uni(r.lo[a], r.hi[a]);
    r.p[r.axis] = r.sign > 0 ? r.hi[r.axis] : r.lo[r.axis];
    if (kind == Kind::on_grid_jitter) {
        const int ulps = static_cast<int>(std::floor(U(rng) * 17.0f)) - 8;
        float v = r.p[r.axis];
        for (int i = 0; i < std::abs(ulps); ++i) v = std::nextafter(v, ulps > 0 ? 1e30f : -1e30f);
        r.p[r.axis] = v;
    }
    // Camera: outward hemisphere direction, log-uniform distance.
    glm::vec3 dirv;
    for (;;) {
        dirv = glm::vec3(uni(-1.0f, 1.0f), uni(-1.0f, 1.0f), uni(-1.0f, 1.0f));
        const float l2 = glm::dot(dirv, dirv);
        if (l2 > 1e-4f && l2 <= 1.0f) break;
    }
    dirv = glm::normalize(dirv);
    dirv[r.axis] = std::abs(dirv[r.axis]) * static_cast<float>(r.sign);
    if (kind == Kind::grazing) {
        dirv[r.axis] = static_cast<float>(r.sign) * std::pow(10.0f, uni(-7.0f, -3.0f));
    }
    float dist = std::pow(10.0f, uni(-2.0f, 2.5f));
    if (kind == Kind::close_camera) dist = std::pow(10.0f, uni(-6.0f, -3.0f));
    r.cam = r.p + dist * dirv;
    if (kind == Kind::axis_parallel) {
        // One or two tangent components shared with p: the ray is parallel to those families.
        const int t1 = r.axis == 0 ? 1 : 0, t2 = r.axis == 2 ? 1 : 2;
        const int mode = static_cast<int>(std::floor(U(rng) * 3.0f));
        if (mode != 1) r.cam[t1] = r.p[t1];
        if (mode != 0) r.cam[t2] = r.p[t2];
        if (U(rng) < 0.5f) {  // and p exactly on a wall plane of a parallel family
            const float w = r.g.origin[t1] + std::round((r.p[t1] - r.g.origin[t1]) / r.g.room_size[t1]) * r.g.room_size[t1];
            if (w > r.lo[t1] && w < r.hi[t1] && mode != 1) r.p[t1] = r.cam[t1] = w;
        }
    }
    if (kind == Kind::denormal) {
        // p on the plane 0 of a tangent axis, the camera a denormal away: direction components
        // of 1e-45 .. 1e-39 (and exactly zero).
        const int t1 = r.axis == 0 ? 1 : 0;
        const float dn[] = {1e-45f, -1e-45f, 1e-40f, -1e-40f, 1e-39f, -3e-39f, 0.0f, -0.0f};
        r.p[t1] = 0.0f;
        r.cam[t1] = dn[static_cast<size_t>(std::floor(U(rng) * 8.0f)) % 8];
    }
    return r;
}

/// The float64 brute-force hit of a test ray (reference/interior_ref.hpp) with the library's wall
/// model: the regular grid, or walls displaced by rk_im_wall_offset(axis, k, jitter, seed).
inline ref_im::Hit reference_hit(const Ray& r, bool varying, glm::vec3 jitter, std::uint32_t seed)
{
    double p[3], cam[3], lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        p[a] = dd(r.p[a]);
        cam[a] = dd(r.cam[a]);
        lo[a] = dd(r.lo[a]);
        hi[a] = dd(r.hi[a]);
    }
    ref_im::WallOffset off;
    if (varying) {
        off = [&](int axis, long k) { return dd(raykit::rk_im_wall_offset(axis, static_cast<int>(k), jitter[axis], seed)); };
    }
    return ref_im::trace(p, cam, r.axis, r.sign, lo, hi, ref_grid(r.g), off, 0.0009765625);
}

}  // namespace imtest
