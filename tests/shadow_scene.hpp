// The analytic scene of the shadow-map proofs (tests/test_shadow_visibility.cpp, directional light;
// tests/test_shadow_omni.cpp, point light): a ground square, spheres and boxes (thin plates and
// walls), intersected exactly in float64, so that every camera pixel can be classified by a ray cast
// to the light and every shadow-map texel made by a ray cast through its centre (what a rasteriser
// stores there); LightMap / render_map make a directional light's map of it (also used by
// bench/bench_shadow.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "raykit/shadow_filter.hpp"

namespace rktest {

using glm::dvec3;

struct Sphere {
    dvec3 c;
    double r;
};
struct Box {
    dvec3 lo, hi;
};

struct Scene {
    std::vector<Sphere> spheres;
    std::vector<Box> boxes;
    double ground_half = 6.0;  // the ground is the square |x|, |z| <= ground_half at y = 0

    /// First hit of origin + t dir, t in (tmin, tmax): t, normal; false when none.
    bool hit(dvec3 o, dvec3 d, double tmin, double& t, dvec3& n) const
    {
        t = 1e300;
        bool any = false;
        if (d.y != 0.0) {
            const double tg = -o.y / d.y;
            const dvec3 p = o + tg * d;
            if (tg > tmin && tg < t && std::abs(p.x) <= ground_half && std::abs(p.z) <= ground_half) {
                t = tg;
                n = dvec3(0, 1, 0);
                any = true;
            }
        }
        for (const Sphere& s : spheres) {
            const dvec3 oc = o - s.c;
            const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - s.r * s.r, disc = b * b - c;
            if (disc < 0.0) continue;
            const double sq = std::sqrt(disc);
            for (double ts : {-b - sq, -b + sq})
                if (ts > tmin && ts < t) {
                    t = ts;
                    n = glm::normalize(o + ts * d - s.c);
                    any = true;
                    break;
                }
        }
        for (const Box& bx : boxes) {
            double t0 = tmin, t1 = 1e300;
            int axis = -1;
            double sgn = 0.0;
            bool ok = true;
            for (int a = 0; a < 3 && ok; ++a) {
                if (d[a] == 0.0) {
                    ok = o[a] >= bx.lo[a] && o[a] <= bx.hi[a];
                    continue;
                }
                double ta = (bx.lo[a] - o[a]) / d[a], tb = (bx.hi[a] - o[a]) / d[a];
                double s = -1.0;
                if (ta > tb) {
                    std::swap(ta, tb);
                    s = 1.0;
                }
                if (ta > t0) {
                    t0 = ta;
                    axis = a;
                    sgn = s;
                }
                t1 = std::min(t1, tb);
                ok = t0 <= t1;
            }
            if (ok && axis >= 0 && t0 < t) {
                t = t0;
                n = dvec3(0.0);
                n[axis] = sgn;
                any = true;
            }
        }
        return any;
    }
};

/// The scene of both proofs: three spheres (one floating), a thin floating plate, a thin wall.
inline Scene test_scene()
{
    Scene s;
    s.spheres = {{dvec3(-2.0, 1.0, -1.0), 1.0}, {dvec3(2.5, 0.6, 1.5), 0.6}, {dvec3(0.5, 2.2, 2.5), 0.4}};
    s.boxes = {{dvec3(-1.0, 1.2, 1.8), dvec3(1.2, 1.25, 3.2)},   // a thin floating plate
               {dvec3(3.0, 0.0, -3.0), dvec3(3.05, 2.0, 0.0)}};  // a thin wall on the ground
    return s;
}

/// for_each_camera_hit: the proofs' camera (eye (0.5, 7, 11) looking at (0, 0.6, 0), a vertical
/// field of view of 0.9 rad) over a w x h image: fn(p, n) for every pixel, in row order, whose ray
/// through the pixel centre hits the scene, p the first hit and n its unit normal turned towards the
/// eye.
template <class Fn>
void for_each_camera_hit(const Scene& sc, int w, int h, Fn fn)
{
    const dvec3 eye(0.5, 7.0, 11.0), at(0.0, 0.6, 0.0);
    const glm::dmat4 view = glm::lookAt(eye, at, dvec3(0, 1, 0)), inv = glm::inverse(glm::perspective(0.9, double(w) / h, 0.1, 100.0) * view);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::dvec4 q = inv * glm::dvec4((x + 0.5) / w * 2 - 1, (y + 0.5) / h * 2 - 1, 0.5, 1.0);
            const dvec3 d = glm::normalize(dvec3(q) / q.w - eye);
            double t;
            dvec3 n;
            if (!sc.hit(eye, d, 0.0, t, n)) continue;
            if (glm::dot(n, d) > 0.0) n = -n;
            fn(eye + t * d, n);
        }
}

/// A directional light's orthographic shadow map: light space (right, up, back = -dir), the box
/// [x0, x0 + size]^2 across, depth = (distance from the plane at back = z_top) / range.
struct LightMap {
    dvec3 dir, right, up, back;
    double x0 = 0, y0 = 0, size = 0, z_top = 0, range = 0;
    raykit::ShadowMapCpu map;
    double texel() const { return size / map.width; }
    raykit::vec3 project(dvec3 p) const
    {
        const double u = (glm::dot(p, right) - x0) / size, v = (glm::dot(p, up) - y0) / size;
        const double d = (z_top - glm::dot(p, back)) / range;
        return raykit::vec3(float(u), float(v), float(map.reversed ? 1.0 - d : d));
    }
};

/// render_map: the orthographic map of a light travelling along dir over the scene region |x|, |z|
/// <= half_extent, 0 <= y <= 3, res x res texels, each the depth of the first hit along the ray
/// through its centre (1: nothing), reversed-Z when asked.
inline LightMap render_map(const Scene& sc, dvec3 dir, int res, double half_extent, bool reversed)
{
    LightMap lm;
    lm.dir = glm::normalize(dir);
    const dvec3 ref = std::abs(lm.dir.y) < 0.99 ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
    lm.right = glm::normalize(glm::cross(lm.dir, ref));
    lm.up = glm::cross(lm.right, lm.dir);
    lm.back = -lm.dir;
    // The box around the scene region |x|, |z| <= half_extent, 0 <= y <= 3.
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300, zmin = 1e300, zmax = -1e300;
    for (int i = 0; i < 8; ++i) {
        const dvec3 p((i & 1) ? half_extent : -half_extent, (i & 2) ? 3.0 : 0.0, (i & 4) ? half_extent : -half_extent);
        xmin = std::min(xmin, glm::dot(p, lm.right));
        xmax = std::max(xmax, glm::dot(p, lm.right));
        ymin = std::min(ymin, glm::dot(p, lm.up));
        ymax = std::max(ymax, glm::dot(p, lm.up));
        zmin = std::min(zmin, glm::dot(p, lm.back));
        zmax = std::max(zmax, glm::dot(p, lm.back));
    }
    lm.size = std::max(xmax - xmin, ymax - ymin);
    lm.x0 = xmin;
    lm.y0 = ymin;
    lm.z_top = zmax + 0.5;
    lm.range = lm.z_top - zmin + 0.5;
    lm.map.width = lm.map.height = res;
    lm.map.reversed = reversed;
    lm.map.depth.resize(size_t(res) * size_t(res));
    for (int j = 0; j < res; ++j)
        for (int i = 0; i < res; ++i) {
            const double x = lm.x0 + (i + 0.5) * lm.size / res, y = lm.y0 + (j + 0.5) * lm.size / res;
            const dvec3 o = x * lm.right + y * lm.up + lm.z_top * lm.back;
            double t;
            dvec3 n;
            double d = 1.0;
            if (sc.hit(o, lm.dir, 0.0, t, n)) d = std::min(t / lm.range, 1.0);
            // The float a depth buffer stores.
            lm.map.depth[size_t(j) * size_t(res) + size_t(i)] = float(reversed ? 1.0 - d : d);
        }
    return lm;
}

}  // namespace rktest
