// Test meshes for the octree builder (raykit/svo_build.hpp), shared by its tests, benchmarks and
// demos: header-only generators returning raykit::SvoMeshData. Deterministic (a local splitmix64,
// no <random> distributions), so the same call gives the same floats on every platform.
//
// Closed meshes (uv_sphere, icosphere, torus, box, thin_wall, menger_sponge) share vertices by
// index and are wound counter-clockwise seen from outside (outward normals, positive signed
// volume); every undirected edge is used as often a->b as b->a. The rest are open sheets or soups.
// The *_triangles() helpers give triangle counts without building, so a benchmark can pick sizes
// (~1k: icosphere(3) = 1280, uv_sphere(32, 17) = 1024; ~70k: uv_sphere(256, 137) = 69632,
// torus(192, 180) = 69120; menger_sponge(2, 3, 4) = 2112, 36096, 672768; icosphere(6) = 81920).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "raykit/svo_mesh.hpp"

namespace rkmesh {

using raykit::SvoMeshData;

constexpr double kPi = 3.14159265358979323846;

/// splitmix64: the generator behind every random mesh here (Steele, Lea & Flood 2014).
struct Rng {
    std::uint64_t s;
    explicit Rng(std::uint64_t seed) : s(seed) {}
    std::uint64_t next()
    {
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1) with 53 bits.
    double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

inline glm::vec3 to_vec3(double x, double y, double z)
{
    return glm::vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
}

inline std::uint32_t push_vertex(SvoMeshData& m, glm::vec3 p)
{
    m.positions.push_back(p);
    return static_cast<std::uint32_t>(m.positions.size() - 1);
}

inline void push_tri(SvoMeshData& m, std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
    m.indices.push_back(a);
    m.indices.push_back(b);
    m.indices.push_back(c);
}

inline std::size_t triangle_count(const SvoMeshData& m) { return m.indices.size() / 3; }

// ---- closed meshes ---------------------------------------------------------------------------

/// UV sphere: `segments` (>= 3) around z, `rings` (>= 2) from pole to pole; one vertex per pole,
/// the seam shared. Vertices lie on the sphere; faces are within radius*(1-cos(pi/min(segments,
/// rings))) inside it.
inline std::size_t uv_sphere_triangles(int segments, int rings) { return static_cast<std::size_t>(2 * segments * (rings - 1)); }

inline SvoMeshData uv_sphere(int segments, int rings, double radius = 1.0, glm::dvec3 centre = glm::dvec3(0.0))
{
    SvoMeshData m;
    auto at = [&](double theta, double phi) {
        return to_vec3(centre.x + radius * std::sin(theta) * std::cos(phi), centre.y + radius * std::sin(theta) * std::sin(phi),
                       centre.z + radius * std::cos(theta));
    };
    const std::uint32_t north = push_vertex(m, to_vec3(centre.x, centre.y, centre.z + radius));
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s) push_vertex(m, at(kPi * r / rings, 2.0 * kPi * s / segments));
    const std::uint32_t south = push_vertex(m, to_vec3(centre.x, centre.y, centre.z - radius));
    auto ring = [&](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + (s % segments)); };
    for (int s = 0; s < segments; ++s) push_tri(m, north, ring(1, s), ring(1, s + 1));
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            push_tri(m, ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
            push_tri(m, ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
        }
    for (int s = 0; s < segments; ++s) push_tri(m, ring(rings - 1, s), south, ring(rings - 1, s + 1));
    return m;
}

/// Icosphere: an icosahedron subdivided `level` times (each triangle into 4, midpoints pushed to
/// the sphere, shared between neighbours). 20 * 4^level triangles.
inline std::size_t icosphere_triangles(int level) { return static_cast<std::size_t>(20) << (2 * level); }

inline SvoMeshData icosphere(int level, double radius = 1.0, glm::dvec3 centre = glm::dvec3(0.0))
{
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& v : p) v = glm::normalize(v);
    std::vector<std::uint32_t> tri = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6,
                                      7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (int l = 0; l < level; ++l) {
        std::unordered_map<std::uint64_t, std::uint32_t> mid;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const std::uint64_t key = a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back(glm::normalize(p[a] + p[b]));
            const auto idx = static_cast<std::uint32_t>(p.size() - 1);
            mid.emplace(key, idx);
            return idx;
        };
        std::vector<std::uint32_t> next;
        next.reserve(tri.size() * 4);
        for (std::size_t i = 0; i < tri.size(); i += 3) {
            const std::uint32_t a = tri[i], b = tri[i + 1], c = tri[i + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            for (std::uint32_t v : {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}) next.push_back(v);
        }
        tri.swap(next);
    }
    SvoMeshData m;
    for (const auto& v : p) m.positions.push_back(to_vec3(centre.x + radius * v.x, centre.y + radius * v.y, centre.z + radius * v.z));
    m.indices = tri;
    return m;
}

/// Torus around the z axis: `major` segments around z, `minor` around the tube; tube-centre
/// radius R, tube radius r (< R). 2 * major * minor triangles, vertices on the torus.
inline std::size_t torus_triangles(int major, int minor) { return static_cast<std::size_t>(2 * major * minor); }

inline SvoMeshData torus(int major, int minor, double R = 1.0, double r = 0.35, glm::dvec3 centre = glm::dvec3(0.0))
{
    SvoMeshData m;
    for (int i = 0; i < major; ++i)
        for (int j = 0; j < minor; ++j) {
            const double u = 2.0 * kPi * i / major, v = 2.0 * kPi * j / minor;
            const double rr = R + r * std::cos(v);
            push_vertex(m, to_vec3(centre.x + rr * std::cos(u), centre.y + rr * std::sin(u), centre.z + r * std::sin(v)));
        }
    auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % major) * minor + (j % minor)); };
    for (int i = 0; i < major; ++i)
        for (int j = 0; j < minor; ++j) {
            push_tri(m, id(i, j), id(i + 1, j), id(i + 1, j + 1));
            push_tri(m, id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    return m;
}

/// A closed tube (cylinder with flat caps) from a to b: segments x rings quads plus two fans.
inline void append_tube(SvoMeshData& m, glm::dvec3 a, glm::dvec3 b, double radius, int segments, int rings)
{
    const glm::dvec3 axis = glm::normalize(b - a);
    const glm::dvec3 t = std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(axis, t)), e2 = glm::cross(axis, e1);
    const std::uint32_t base = static_cast<std::uint32_t>(m.positions.size());
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double ang = 2.0 * kPi * s / segments;
            const glm::dvec3 p = a + (b - a) * (static_cast<double>(r) / rings) + radius * (std::cos(ang) * e1 + std::sin(ang) * e2);
            push_vertex(m, to_vec3(p.x, p.y, p.z));
        }
    auto id = [&](int r, int s) { return base + static_cast<std::uint32_t>(r * segments + (s % segments)); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            push_tri(m, id(r, s), id(r, s + 1), id(r + 1, s + 1));
            push_tri(m, id(r, s), id(r + 1, s + 1), id(r + 1, s));
        }
    const std::uint32_t ca = static_cast<std::uint32_t>(m.positions.size());
    push_vertex(m, to_vec3(a.x, a.y, a.z));
    const std::uint32_t cb = ca + 1;
    push_vertex(m, to_vec3(b.x, b.y, b.z));
    for (int s = 0; s < segments; ++s) {
        push_tri(m, ca, id(0, s + 1), id(0, s));
        push_tri(m, cb, id(rings, s), id(rings, s + 1));
    }
}

/// A standing figure of 1,024 triangles, 1.8 units tall (torso, head, arms, legs as closed tubes
/// and an icosphere): a stand-in for the ~1k-triangle character of Gritzner's thesis, whose
/// bounding cube, unlike a sphere's, is mostly empty. Parts overlap (not one closed surface).
inline SvoMeshData figure()
{
    SvoMeshData m = icosphere(2, 0.12, glm::dvec3(0.0, 1.62, 0.0));     // head: 320
    append_tube(m, {0.0, 0.85, 0.0}, {0.0, 1.45, 0.0}, 0.17, 16, 6);    // torso: 224
    append_tube(m, {-0.1, 0.0, 0.0}, {-0.1, 0.85, 0.0}, 0.07, 12, 4);   // legs: 2 x 120
    append_tube(m, {0.1, 0.0, 0.0}, {0.1, 0.85, 0.02}, 0.07, 12, 4);
    append_tube(m, {-0.2, 1.42, 0.0}, {-0.42, 0.9, 0.08}, 0.05, 12, 4); // arms: 2 x 120
    append_tube(m, {0.2, 1.42, 0.0}, {0.45, 1.0, -0.1}, 0.05, 12, 4);
    return m;
}

/// Box [lo, hi], rotated about its centre by `euler` radians (x, then y, then z); 12 triangles.
inline SvoMeshData box(glm::dvec3 lo, glm::dvec3 hi, glm::dvec3 euler = glm::dvec3(0.0))
{
    const glm::dvec3 c = 0.5 * (lo + hi);
    auto rot = [&](glm::dvec3 p) {
        p -= c;
        const double cx = std::cos(euler.x), sx = std::sin(euler.x), cy = std::cos(euler.y), sy = std::sin(euler.y),
                     cz = std::cos(euler.z), sz = std::sin(euler.z);
        p = glm::dvec3(p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z);
        p = glm::dvec3(cy * p.x + sy * p.z, p.y, -sy * p.x + cy * p.z);
        p = glm::dvec3(cz * p.x - sz * p.y, sz * p.x + cz * p.y, p.z);
        return p + c;
    };
    SvoMeshData m;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 q((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
        const glm::dvec3 p = euler == glm::dvec3(0.0) ? q : rot(q);
        push_vertex(m, to_vec3(p.x, p.y, p.z));
    }
    // Corner i = x | y<<1 | z<<2. Each face counter-clockwise seen from outside.
    const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces) {
        push_tri(m, f[0], f[1], f[2]);
        push_tri(m, f[0], f[2], f[3]);
    }
    return m;
}

/// Thin wall: a closed slab `size` x `size` wide and `thickness` thick along `axis` (0..2), centred
/// on `centre` (two parallel quads `thickness` apart plus their four sides). 12 triangles.
inline SvoMeshData thin_wall(double size, double thickness, int axis, glm::dvec3 centre = glm::dvec3(0.0))
{
    glm::dvec3 half(0.5 * size);
    half[axis] = 0.5 * thickness;
    return box(centre - half, centre + half);
}

/// Whether cell (x, y, z) of the 3^level grid is filled in the Menger sponge of that level: no base-3
/// digit position has two or more of the three digits equal to 1.
inline bool menger_filled(int level, int x, int y, int z)
{
    for (int l = 0; l < level; ++l) {
        if ((x % 3 == 1) + (y % 3 == 1) + (z % 3 == 1) >= 2) return false;
        x /= 3, y /= 3, z /= 3;
    }
    return true;
}

/// Menger sponge of `level` (0..4) filling the cube [lo, lo + size]^3: every unit face between a
/// filled and an empty (or outside) cell of the 3^level grid, as 2 triangles wound outward, grid
/// vertices shared. Closed (possibly non-manifold along edges where filled cells meet diagonally).
inline std::size_t menger_triangles(int level)
{
    const int n = static_cast<int>(std::lround(std::pow(3.0, level)));
    auto filled = [&](int x, int y, int z) {
        return x >= 0 && y >= 0 && z >= 0 && x < n && y < n && z < n && menger_filled(level, x, y, z);
    };
    std::size_t faces = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                if (!filled(x, y, z)) continue;
                faces += !filled(x - 1, y, z) + !filled(x + 1, y, z) + !filled(x, y - 1, z) + !filled(x, y + 1, z) +
                         !filled(x, y, z - 1) + !filled(x, y, z + 1);
            }
    return 2 * faces;
}

inline SvoMeshData menger_sponge(int level, glm::dvec3 lo = glm::dvec3(0.0), double size = 1.0)
{
    const int n = static_cast<int>(std::lround(std::pow(3.0, level)));
    auto filled = [&](int x, int y, int z) {
        return x >= 0 && y >= 0 && z >= 0 && x < n && y < n && z < n && menger_filled(level, x, y, z);
    };
    SvoMeshData m;
    std::unordered_map<std::uint64_t, std::uint32_t> vid;
    auto vertex = [&](int x, int y, int z) {
        const std::uint64_t key = (std::uint64_t(x) << 42) | (std::uint64_t(y) << 21) | std::uint64_t(z);
        auto it = vid.find(key);
        if (it != vid.end()) return it->second;
        const double h = size / n;
        const std::uint32_t i = push_vertex(m, to_vec3(lo.x + h * x, lo.y + h * y, lo.z + h * z));
        vid.emplace(key, i);
        return i;
    };
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                if (!filled(x, y, z)) continue;
                for (int axis = 0; axis < 3; ++axis)
                    for (int side = 0; side < 2; ++side) {
                        int c[3] = {x, y, z};
                        c[axis] += side ? 1 : -1;
                        if (filled(c[0], c[1], c[2])) continue;
                        // Face at coordinate c[axis] + side on `axis`, spanning the other two axes u, v.
                        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                        int q[4][3];
                        for (int k = 0; k < 4; ++k) {
                            q[k][0] = x, q[k][1] = y, q[k][2] = z;
                            q[k][axis] += side;
                        }
                        // (u, v) = (0,0), (1,0), (1,1), (0,1): counter-clockwise around +axis.
                        q[1][u] += 1;
                        q[2][u] += 1, q[2][v] += 1;
                        q[3][v] += 1;
                        std::uint32_t id[4];
                        for (int k = 0; k < 4; ++k) id[k] = vertex(q[k][0], q[k][1], q[k][2]);
                        if (side) {
                            push_tri(m, id[0], id[1], id[2]);
                            push_tri(m, id[0], id[2], id[3]);
                        } else {
                            push_tri(m, id[0], id[2], id[1]);
                            push_tri(m, id[0], id[3], id[2]);
                        }
                    }
            }
    return m;
}

// ---- open meshes and soups -------------------------------------------------------------------

/// Axis-aligned quad (2 triangles) on the plane `axis` = `coord`, spanning [lo.x, hi.x] on axis
/// (axis+1)%3 and [lo.y, hi.y] on axis (axis+2)%3. Wound so its normal is +axis.
inline SvoMeshData axis_quad(int axis, double coord, glm::dvec2 lo, glm::dvec2 hi)
{
    SvoMeshData m;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double uv[4][2] = {{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}};
    for (const auto& c : uv) {
        double p[3];
        p[axis] = coord, p[u] = c[0], p[v] = c[1];
        push_vertex(m, to_vec3(p[0], p[1], p[2]));
    }
    push_tri(m, 0, 1, 2);
    push_tri(m, 0, 2, 3);
    return m;
}

/// Slivers in the unit cube: `count` needle triangles (two vertices 1e-8..1e-3 apart, the third
/// up to 0.8 away) and `count` near-collinear ones (the third vertex 1e-6..1e-3 off the
/// line through the other two, possibly between them). After snapping some become collinear.
inline SvoMeshData slivers(int count, std::uint64_t seed = 7)
{
    Rng rng(seed);
    SvoMeshData m;
    auto rnd = [&](double lo, double hi) { return glm::dvec3(rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi)); };
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 a = rnd(0.1, 0.9);
        const glm::dvec3 b = a + std::pow(10.0, rng.uniform(-8.0, -3.0)) * rnd(-1.0, 1.0);
        const glm::dvec3 c = glm::clamp(a + rnd(-0.8, 0.8), glm::dvec3(0.0), glm::dvec3(1.0));
        for (const auto& p : {a, b, c}) push_vertex(m, to_vec3(p.x, p.y, p.z));
        const auto base = static_cast<std::uint32_t>(m.positions.size() - 3);
        push_tri(m, base, base + 1, base + 2);
    }
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 a = rnd(0.05, 0.95), b = rnd(0.05, 0.95);
        const double t = rng.uniform(-0.5, 1.5);
        const double off = std::pow(10.0, rng.uniform(-6.0, -3.0));
        const glm::dvec3 c = glm::clamp(a + t * (b - a) + off * glm::normalize(rnd(-1.0, 1.0)), glm::dvec3(0.0), glm::dvec3(1.0));
        for (const auto& p : {a, b, c}) push_vertex(m, to_vec3(p.x, p.y, p.z));
        const auto base = static_cast<std::uint32_t>(m.positions.size() - 3);
        push_tri(m, base, base + 1, base + 2);
    }
    return m;
}

/// Random soup: `count` independent triangles with vertices within `max_edge` of a random point
/// of the unit cube (clamped to it). Unwound, unconnected, overlapping.
inline SvoMeshData random_soup(int count, std::uint64_t seed = 1, double max_edge = 0.3)
{
    Rng rng(seed);
    SvoMeshData m;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 c(rng.uniform(), rng.uniform(), rng.uniform());
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = glm::clamp(c + glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) * max_edge,
                                            glm::dvec3(0.0), glm::dvec3(1.0));
            m.indices.push_back(push_vertex(m, to_vec3(p.x, p.y, p.z)));
        }
    }
    return m;
}

/// Textured quad [0,1]^2 at z = 0 with uvs (u = x, v = 1 - y), +z normals, one material whose
/// base colour texture is a `cells` x `cells` checker of texels `a` / `b` (RGBA8, sRGB, repeat).
inline SvoMeshData textured_quad(int cells = 8, glm::u8vec4 a = {255, 32, 32, 255}, glm::u8vec4 b = {32, 32, 255, 255})
{
    SvoMeshData m = axis_quad(2, 0.0, {0.0, 0.0}, {1.0, 1.0});
    for (const auto& p : m.positions) {
        m.uvs.emplace_back(p.x, 1.0f - p.y);
        m.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
    std::vector<std::uint8_t> img(static_cast<std::size_t>(cells * cells * 4));
    for (int y = 0; y < cells; ++y)
        for (int x = 0; x < cells; ++x) {
            const glm::u8vec4 c = ((x + y) & 1) ? b : a;
            for (int k = 0; k < 4; ++k) img[static_cast<std::size_t>((y * cells + x) * 4 + k)] = c[k];
        }
    m.images.push_back(std::move(img));
    raykit::SvoImageView tex;
    tex.pixels = m.images.back().data();
    tex.width = tex.height = cells;
    tex.channels = 4;
    m.textures.push_back(tex);
    raykit::SvoMeshMaterial mat;
    mat.base_color_texture = 0;
    m.materials.push_back(mat);
    m.material_ids.assign(2, 0);
    return m;
}

// ---- helpers ---------------------------------------------------------------------------------

/// A copy with every position p -> p * scale + offset (in double, then rounded to float): e.g.
/// transformed(icosphere(3), 1.0, {1e5, 0, 0}) for a mesh far from the origin. Normals, uvs,
/// materials and textures are kept (texture views re-pointed at the copy's images).
inline SvoMeshData transformed(const SvoMeshData& in, double scale, glm::dvec3 offset)
{
    SvoMeshData m = in;
    for (auto& p : m.positions)
        p = to_vec3(p.x * scale + offset.x, p.y * scale + offset.y, p.z * scale + offset.z);
    for (std::size_t i = 0; i < m.textures.size() && i < m.images.size(); ++i) m.textures[i].pixels = m.images[i].data();
    return m;
}

/// Appends b's triangles to a (positions, indices; normals/uvs/material ids only if both have them).
inline void append(SvoMeshData& a, const SvoMeshData& b)
{
    const auto base = static_cast<std::uint32_t>(a.positions.size());
    const bool normals = a.normals.size() == a.positions.size() && b.normals.size() == b.positions.size();
    const bool uvs = a.uvs.size() == a.positions.size() && b.uvs.size() == b.positions.size();
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    if (normals) a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end()); else a.normals.clear();
    if (uvs) a.uvs.insert(a.uvs.end(), b.uvs.begin(), b.uvs.end()); else a.uvs.clear();
    for (std::uint32_t i : b.indices) a.indices.push_back(base + i);
    a.material_ids.clear();
}

/// Signed volume (divergence theorem, in double): positive for a closed outward-wound mesh.
inline double signed_volume(const SvoMeshData& m)
{
    double v = 0.0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

/// Whether every undirected edge is used as often a->b as b->a (closed, consistently wound).
inline bool edges_paired(const SvoMeshData& m)
{
    std::unordered_map<std::uint64_t, long> count;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = m.indices[t + k], b = m.indices[t + (k + 1) % 3];
            if (a == b) return false;
            const std::uint64_t key = a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
            count[key] += a < b ? 1 : -1;
        }
    for (const auto& kv : count)
        if (kv.second != 0) return false;
    return true;
}

}  // namespace rkmesh
