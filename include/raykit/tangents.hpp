// raykit — tangents.hpp: per-vertex tangents with handedness for normal mapping (Fahlén,
// "Illumination for Real-Time Rendering of Large Architectural Environments", §6.2, after Lengyel):
// each triangle's tangent and bitangent solve Q1 = s1 T + t1 B, Q2 = s2 T + t2 B (the thesis prints
// a minus sign in Eq. 6.4; with it the solved B is wrong whenever t1 != 0), they are summed at its
// vertices, and each vertex's sum is made perpendicular to its normal (Gram–Schmidt), normalised,
// and given the handedness w = ±1 of det(T, B, N), which rk_nm_tbn (normalmap.glsl) uses as
// B = w · N × T (Eq. 6.5). C++ only (a mesh-processing step); the shader side is normalmap.glsl.
//
// Triangles whose uv area is zero (or not finite) contribute nothing; a vertex left without any
// tangent (all its triangles degenerate in uv) gets rk_nm_basis_tangent of its normal and w = +1, so
// every output is a finite unit vector perpendicular to its normal. Not MikkTSpace: vertices are not
// split and contributions are not angle-weighted, so tangents differ from a glTF exporter's where
// uv seams or skewed triangles meet (use the file's tangents when it has them).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raykit/normalmap.hpp"
#include "raykit/status.hpp"

namespace raykit {

/// compute_tangents: one tangent (xyz unit, w = ±1 handedness) per vertex of an indexed triangle
/// mesh: positions and normals as 3 floats per vertex, uvs as 2, `indices` 3 per triangle (nullptr:
/// vertices 3t, 3t+1, 3t+2). Zero or non-finite normals count as +z. Returns false with a message
/// for an index out of range or missing arrays (vertex_count > 0 with a null pointer); an empty mesh
/// gives an empty result. Cost: O(vertices + triangles), one pass each.
inline bool compute_tangents(const float* positions, const float* normals, const float* uvs, size_t vertex_count,
                             const uint32_t* indices, size_t triangle_count, std::vector<vec4>& out, Status& st)
{
    st = Status{};
    out.clear();
    if (vertex_count == 0) return true;
    if (!positions || !normals || !uvs) return st.fail(Error::invalid_argument, "compute_tangents: positions, normals and uvs are required");
    if (!indices && triangle_count * 3 > vertex_count)
        return st.fail(Error::invalid_argument, "compute_tangents: " + std::to_string(triangle_count) + " triangles need " +
                                                    std::to_string(triangle_count * 3) + " vertices without indices");
    std::vector<glm::dvec3> tan(vertex_count, glm::dvec3(0.0)), bit(vertex_count, glm::dvec3(0.0));
    for (size_t t = 0; t < triangle_count; ++t) {
        size_t v[3];
        for (int k = 0; k < 3; ++k) {
            v[k] = indices ? indices[3 * t + static_cast<size_t>(k)] : 3 * t + static_cast<size_t>(k);
            if (v[k] >= vertex_count)
                return st.fail(Error::invalid_argument, "compute_tangents: triangle " + std::to_string(t) + " uses vertex " +
                                                            std::to_string(v[k]) + " of " + std::to_string(vertex_count));
        }
        auto P = [&](size_t i) { return glm::dvec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]); };
        auto U = [&](size_t i) { return glm::dvec2(uvs[2 * i], uvs[2 * i + 1]); };
        const glm::dvec3 q1 = P(v[1]) - P(v[0]), q2 = P(v[2]) - P(v[0]);
        const glm::dvec2 d1 = U(v[1]) - U(v[0]), d2 = U(v[2]) - U(v[0]);
        const double det = d1.x * d2.y - d2.x * d1.y;
        // A zero-area uv triangle (or an overflowing one) has no tangent direction.
        if (!(std::abs(det) > 1e-30) || !std::isfinite(det)) continue;
        const double r = 1.0 / det;
        // Q1 = s1 T + t1 B, Q2 = s2 T + t2 B  =>  T = (t2 Q1 - t1 Q2) / det, B = (s1 Q2 - s2 Q1) / det.
        // Summed unnormalised: each triangle weighs by its size in space relative to uv.
        const glm::dvec3 T = (d2.y * q1 - d1.y * q2) * r, B = (d1.x * q2 - d2.x * q1) * r;
        if (!std::isfinite(T.x + T.y + T.z + B.x + B.y + B.z)) continue;
        for (size_t k : v) {
            tan[k] += T;
            bit[k] += B;
        }
    }
    out.resize(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) {
        glm::dvec3 n(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
        const double nl = glm::length(n);
        n = nl > 1e-30 && std::isfinite(nl) ? n / nl : glm::dvec3(0.0, 0.0, 1.0);
        glm::dvec3 t = tan[i] - n * glm::dot(n, tan[i]);
        const double tl = glm::length(t);
        if (!(tl > 1e-12 * std::max(glm::length(tan[i]), 1e-300)) || !std::isfinite(tl)) {
            out[i] = vec4(rk_nm_basis_tangent(vec3(n)), 1.0f);
            continue;
        }
        t /= tl;
        const double w = glm::dot(glm::cross(n, t), bit[i]) < 0.0 ? -1.0 : 1.0;
        out[i] = vec4(vec3(t), static_cast<float>(w));
    }
    return true;
}

}  // namespace raykit
