// raykit — light_volume.hpp: the CPU build of shaders/raykit/light_volume.glsl (windowed falloff,
// spot factor, a sphere's screen rectangle and depth range) and the CPU side of deferred light
// volumes (Fahlén, "Illumination for Real-Time Rendering of Large Architectural Environments",
// §2.3): convex volume meshes that contain the lit region, the light radius for a cut-off, and the
// rule that picks the culled faces.
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_light_volume.cpp checks that both builds agree on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/gbuffer.hpp"
#include "raykit/status.hpp"

namespace raykit {
#include "raykit/light_volume.glsl"

/// A light volume's mesh: positions and counter-clockwise triangles seen from outside (front faces
/// face out), convex and closed.
struct LightVolumeMesh {
    std::vector<vec3> positions;
    std::vector<uint32_t> indices;
};

/// point_light_radius: the distance at which the unwindowed inverse-square illuminance I / d²
/// falls to `cutoff`: sqrt(I / cutoff). rk_lv_point_falloff windows the light to exactly 0 there,
/// and the volume of that radius bounds it. Domain: intensity >= 0, cutoff > 0 (else 0).
inline float point_light_radius(float intensity, float cutoff)
{
    if (!(intensity > 0.0f) || !(cutoff > 0.0f) || !std::isfinite(intensity)) return 0.0f;
    return static_cast<float>(std::min(std::sqrt(static_cast<double>(intensity) / cutoff), static_cast<double>(RK_FLT_MAX)));
}

namespace detail {
/// Scales a convex mesh around the origin whose vertices lie on the unit sphere so that every face
/// plane is at least 1 from the origin: the mesh then contains the unit ball.
inline void circumscribe_unit_ball(LightVolumeMesh& m)
{
    double min_d = 1.0;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
        const glm::dvec3 nrm = glm::normalize(glm::cross(b - a, c - a));
        min_d = std::min(min_d, glm::dot(nrm, a));
    }
    // A hair more than 1 / min_d so that float rounding of the scaled vertices never cuts the ball.
    const double s = (1.0 / min_d) * (1.0 + 4e-7);
    for (vec3& p : m.positions) p = vec3(glm::dvec3(p) * s);
}
/// The side count and half-angle light_volume_cone builds with (and light_volume_cull_cone tests
/// against): segments clamped to 3..256, the angle to [1e-4 rad, 80 degrees].
inline int cone_segments(int segments) { return std::min(std::max(segments, 3), 256); }
inline double cone_half_angle(float half_angle)
{
    return std::min(std::max(static_cast<double>(half_angle), 1e-4), 80.0 * 3.14159265358979323846 / 180.0);
}
}  // namespace detail

/// light_volume_sphere: a convex mesh containing the unit ball, for point lights (scale it by the
/// light's radius): an icosahedron subdivided `subdivisions` times (0..5, clamped), its vertices
/// pushed out so that every face plane is at least 1 from the centre. Vertex radius (how far it
/// over-covers): 1.26 (0 subdivisions, 20 faces), 1.07 (1, 80), 1.02 (2, 320).
inline LightVolumeMesh light_volume_sphere(int subdivisions = 1)
{
    LightVolumeMesh m;
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                             {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const auto& p : v) m.positions.push_back(vec3(glm::normalize(glm::dvec3(p[0], p[1], p[2]))));
    m.indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    const int sub = std::min(std::max(subdivisions, 0), 5);
    for (int s = 0; s < sub; ++s) {
        std::vector<uint32_t> next;
        std::vector<std::pair<uint64_t, uint32_t>> mids;
        auto mid = [&](uint32_t a, uint32_t b) {
            const uint64_t key = a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
            for (const auto& e : mids)
                if (e.first == key) return e.second;
            m.positions.push_back(vec3(glm::normalize(glm::dvec3(m.positions[a]) + glm::dvec3(m.positions[b]))));
            const uint32_t i = static_cast<uint32_t>(m.positions.size() - 1);
            mids.push_back({key, i});
            return i;
        };
        for (size_t k = 0; k < m.indices.size(); k += 3) {
            const uint32_t a = m.indices[k], b = m.indices[k + 1], c = m.indices[k + 2];
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        m.indices.swap(next);
    }
    detail::circumscribe_unit_ball(m);
    return m;
}

/// light_volume_cone: a convex mesh containing the spherical sector of radius 1 and half-angle
/// `half_angle` around -z with its apex at the origin (a spot light of range 1 pointing down -z;
/// scale by the range, rotate -z onto the spot's direction): a pyramid with `segments` sides
/// (3..256, clamped) whose base, at z = -1, circumscribes the circle of radius tan(half_angle).
/// The sector's cap bulges to z = -1 on the axis and is inside because the base is at -1. Domain:
/// half_angle in (0, 80 degrees] (clamped; wider spots: use light_volume_sphere). Returns the
/// apex as vertex 0, the base ring, then the base centre.
inline LightVolumeMesh light_volume_cone(int segments, float half_angle)
{
    LightVolumeMesh m;
    const int n = detail::cone_segments(segments);
    const double pi = 3.14159265358979323846;
    const double a = detail::cone_half_angle(half_angle);
    const double R = std::tan(a) / std::cos(pi / n) * (1.0 + 4e-7);
    m.positions.push_back(vec3(0.0f));
    for (int i = 0; i < n; ++i) {
        const double phi = 2.0 * pi * i / n;
        m.positions.push_back(vec3(static_cast<float>(R * std::cos(phi)), static_cast<float>(R * std::sin(phi)), -1.0f - 4e-7f));
    }
    m.positions.push_back(vec3(0.0f, 0.0f, -1.0f - 4e-7f));
    const uint32_t centre = static_cast<uint32_t>(n + 1);
    for (int i = 0; i < n; ++i) {
        const uint32_t b0 = static_cast<uint32_t>(1 + i), b1 = static_cast<uint32_t>(1 + (i + 1) % n);
        m.indices.insert(m.indices.end(), {0u, b0, b1});      // side: outward, counter-clockwise
        m.indices.insert(m.indices.end(), {centre, b1, b0});  // base, facing -z
    }
    return m;
}

/// Which faces a light volume is drawn with (the thesis's rule).
enum class LightVolumeCull {
    back,   ///< the camera is outside: draw front faces (depth test LESS / GREATER reversed)
    front,  ///< the camera, or a part of its near plane, is inside: draw back faces (depth test
            ///< GEQUAL, or none), so the near plane never clips the volume away
};

/// near_plane_reach: how far from the eye the near plane's rectangle extends: the distance to its
/// corners, near * sqrt(1 + tan²(fov_x / 2) + tan²(fov_y / 2)), from a projection's P[0][0] and
/// P[1][1] (symmetric frusta; for an off-centre one pass the largest corner distance yourself).
inline float near_plane_reach(float near_plane, float p00, float p11)
{
    const double tx = p00 != 0.0f ? 1.0 / p00 : 0.0, ty = p11 != 0.0f ? 1.0 / p11 : 0.0;
    return static_cast<float>(near_plane * std::sqrt(1.0 + tx * tx + ty * ty));
}

/// light_volume_cull_sphere: the faces to cull for a volume mesh around a sphere of radius r at
/// `centre` (world or view space, the same as `eye`), drawn as light_volume_sphere scaled by r.
/// Front faces are culled when the eye is within r_mesh + reach of the centre, where r_mesh is the
/// mesh's vertex radius (`mesh_radius` times r: it over-covers the sphere) and reach =
/// near_plane_reach(): then some of the near plane's rectangle may be inside the mesh and its front
/// faces clipped. Conservative: "back" is returned only when no point of the near-plane rectangle
/// can be inside the mesh. Domain: r >= 0, mesh_radius >= 1.
inline LightVolumeCull light_volume_cull_sphere(vec3 centre, float r, float mesh_radius, vec3 eye, float reach)
{
    const double d = glm::length(glm::dvec3(centre) - glm::dvec3(eye));
    const double lim = static_cast<double>(std::max(r, 0.0f)) * std::max(static_cast<double>(mesh_radius), 1.0) +
                       std::max(static_cast<double>(reach), 0.0);
    return d <= lim * (1.0 + 1e-6) ? LightVolumeCull::front : LightVolumeCull::back;
}

/// light_volume_cull_cone: as light_volume_cull_sphere for a cone mesh (light_volume_cone with
/// `segments` sides and `half_angle`, scaled by the range and turned to `axis`, a unit vector, apex
/// at `apex`): front faces are culled when the eye is within `reach` of the smooth cone that
/// circumscribes the mesh (base radius range * tan(half_angle) / cos(pi / segments)).
inline LightVolumeCull light_volume_cull_cone(vec3 apex, vec3 axis, float range, float half_angle, int segments, vec3 eye,
                                              float reach)
{
    const double pi = 3.14159265358979323846;
    const int n = detail::cone_segments(segments);
    const double a = detail::cone_half_angle(half_angle);
    const double h = std::max(static_cast<double>(range), 0.0) * (1.0 + 1e-6);
    const double R = h * std::tan(a) / std::cos(pi / n) * (1.0 + 1e-6);
    const glm::dvec3 u = glm::normalize(glm::dvec3(axis)), p = glm::dvec3(eye) - glm::dvec3(apex);
    const double t = glm::dot(p, u), rho = glm::length(p - t * u);
    // Distance from (t, rho) to the triangle (0, 0), (h, R), (h, 0) of the half-plane rho >= 0.
    double dist;
    if (t >= 0.0 && t <= h && rho * h <= t * R) {
        dist = 0.0;
    } else {
        auto seg = [](double px, double py, double ax, double ay, double bx, double by) {
            const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
            const double s = l2 > 0.0 ? std::min(std::max(((px - ax) * dx + (py - ay) * dy) / l2, 0.0), 1.0) : 0.0;
            return std::hypot(px - ax - s * dx, py - ay - s * dy);
        };
        dist = std::min(seg(t, rho, 0.0, 0.0, h, R), seg(t, rho, h, 0.0, h, R));
    }
    return dist <= std::max(static_cast<double>(reach), 0.0) * (1.0 + 1e-6) + 1e-9 * h ? LightVolumeCull::front : LightVolumeCull::back;
}

/// lv_projection_params: the `proj` of rk_lv_sphere_ndc_rect for the column-major projection P:
/// (P[0][0], P[1][1], P[2][0], P[2][1]).
inline vec4 lv_projection_params(const mat4& P) { return vec4(P[0][0], P[1][1], P[2][0], P[2][1]); }

}  // namespace raykit
