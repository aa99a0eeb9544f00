// The analytic scene of the shadow-map proofs (tests/test_shadow_visibility.cpp, directional light;
// tests/test_shadow_omni.cpp, point light): a ground square, spheres and boxes (thin plates and
// walls), intersected exactly in float64, so that every camera pixel can be classified by a ray cast
// to the light and every shadow-map texel made by a ray cast through its centre (what a rasteriser
// stores there).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

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

}  // namespace rktest
