// Analytic scenes for ambient occlusion (tests/test_ssao.cpp, bench/bench_ssao.cpp): a floor, an
// inner corner of floor and wall, a sphere resting on the floor; each rendered into a reversed-Z
// float depth buffer and a view-space normal buffer by casting one ray per pixel in double, and the
// reference AO of a point: the fraction of 1,024 stratified cosine-weighted rays that hit the scene
// within the AO radius, in double. Independent of ssao.glsl (it uses only gbuffer.hpp's uniforms).
#pragma once

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/gbuffer.hpp"
#include "raykit/ssao.hpp"

namespace aoref {

using glm::dvec3;
using raykit::AoMapCpu;
using raykit::mat4;
using raykit::vec3;
using raykit::vec4;

constexpr int W = 160, H = 120;
constexpr double kNear = 0.1, kFar = 100.0;

struct Scene {
    bool floor = true;
    bool wall = false;     // the plane z = -2, facing +z
    bool sphere = false;   // centre (0, 0.5, -1.5), radius 0.5, on the floor
    /// First hit of o + t d, t > tmin: t and the unit normal facing the ray.
    bool hit(dvec3 o, dvec3 d, double tmin, double tmax, double& t, dvec3& n) const
    {
        t = tmax;
        bool any = false;
        if (floor && d.y != 0.0) {
            const double tf = -o.y / d.y;
            if (tf > tmin && tf < t) {
                t = tf;
                n = dvec3(0, 1, 0);
                any = true;
            }
        }
        if (wall && d.z != 0.0) {
            const double tw = (-2.0 - o.z) / d.z;
            if (tw > tmin && tw < t) {
                t = tw;
                n = dvec3(0, 0, 1);
                any = true;
            }
        }
        if (sphere) {
            const dvec3 c(0.0, 0.5, -1.5), oc = o - c;
            const double b = glm::dot(oc, d), cc = glm::dot(oc, oc) - 0.25, disc = b * b - cc;
            if (disc >= 0.0) {
                const double q = std::sqrt(disc);
                for (double ts : {-b - q, -b + q})
                    if (ts > tmin && ts < t) {
                        t = ts;
                        n = glm::normalize(o + ts * d - c);
                        any = true;
                        break;
                    }
            }
        }
        if (any && glm::dot(n, d) > 0.0) n = -n;
        return any;
    }
};

/// The rendered buffers and everything the AO functions need.
struct Frame {
    AoMapCpu depth;                  // reversed-Z window depth (float)
    std::vector<dvec3> world, nview; // per pixel: world position, view-space normal (NaN: sky)
    std::vector<bool> covered;
    glm::dmat4 view;
    vec3 k;
    vec4 ray, proj;
};

inline Frame render(const Scene& sc)
{
    Frame f;
    const dvec3 eye(0.3, 1.4, 1.8), at(0.0, 0.3, -1.6);
    f.view = glm::lookAt(eye, at, dvec3(0, 1, 0));
    const glm::dmat4 P = glm::perspective(1.0, double(W) / H, kNear, kFar);
    const glm::dmat4 inv = glm::inverse(P * f.view);
    f.k = raykit::gbuffer_depth_params(kNear, kFar, true);
    f.ray = raykit::gbuffer_view_ray(mat4(P));
    f.proj = vec4(float(P[0][0]), float(P[1][1]), float(P[2][0]), float(P[2][1]));
    f.depth.width = W;
    f.depth.height = H;
    f.depth.v.assign(size_t(W) * H, 0.0f);  // reversed-Z far plane
    f.world.assign(size_t(W) * H, dvec3(0.0));
    f.nview.assign(size_t(W) * H, dvec3(0.0));
    f.covered.assign(size_t(W) * H, false);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec4 q = inv * glm::dvec4((x + 0.5) / W * 2 - 1, (y + 0.5) / H * 2 - 1, 0.5, 1.0);
            const dvec3 d = glm::normalize(dvec3(q) / q.w - eye);
            double t;
            dvec3 n;
            if (!sc.hit(eye, d, 0.0, 1e300, t, n)) continue;
            const dvec3 p = eye + t * d;
            const double dist = -(f.view * glm::dvec4(p, 1.0)).z;
            if (dist > kFar) continue;
            const size_t i = size_t(y) * W + size_t(x);
            f.depth.v[i] = float((1.0 / dist - 1.0 / kFar) / (1.0 / kNear - 1.0 / kFar));  // reversed-Z
            f.world[i] = p;
            f.nview[i] = glm::normalize(dvec3(f.view * glm::dvec4(n, 0.0)));
            f.covered[i] = true;
        }
    return f;
}

/// Ray-traced AO at p with normal n: the fraction of 32 x 32 stratified cosine-weighted rays that
/// hit the scene within `radius`.
inline double reference_ao(const Scene& sc, dvec3 p, dvec3 n, double radius)
{
    const dvec3 a = std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 t = glm::normalize(a - n * glm::dot(a, n)), b = glm::cross(n, t);
    int hits = 0;
    for (int i = 0; i < 32; ++i)
        for (int j = 0; j < 32; ++j) {
            const double u1 = (i + 0.5) / 32.0, u2 = (j + 0.5) / 32.0;
            const double r = std::sqrt(u1), phi = 2.0 * 3.14159265358979323846 * u2;
            const dvec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u1)) * n;
            double th;
            dvec3 nh;
            if (sc.hit(p + 1e-9 * n, d, 1e-9, radius, th, nh)) ++hits;
        }
    return hits / 1024.0;
}


inline std::vector<double> references(const Scene& sc, const Frame& f, double radius)
{
    std::vector<double> r(f.covered.size(), 0.0);
    const glm::dmat4 iv = glm::inverse(f.view);
    for (size_t i = 0; i < r.size(); ++i)
        if (f.covered[i]) r[i] = reference_ao(sc, f.world[i], glm::normalize(dvec3(iv * glm::dvec4(f.nview[i], 0.0))), radius);
    return r;
}

}  // namespace aoref
