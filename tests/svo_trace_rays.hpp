// Ray sets for the octree traversal tests (test_svo_traverse, parity_svo_trace): ordinary random
// rays and the adversarial families the traversal must survive, for a root cube
// [root_min, root_min + root_size]^3 at a given depth. Lattice points (cell corners, edges, faces)
// are exactly representable in float32 when root_min and root_size are dyadic, which the tests use,
// so "origin on a face" and "ray through a corner" are exact, not approximately so.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "raykit/svo_build.hpp"

namespace svotrace {

/// The trees the trace tests cast rays through: `mesh` voxelised at `depth` with `fill`, the
/// colour stream only. False with the builder's message in `why`.
inline bool build_colour_tree(const raykit::SvoMeshData& mesh, int depth, raykit::SvoFill fill, raykit::SvoTree& t,
                              std::string& why)
{
    raykit::SvoBuildOptions opt;
    opt.depth = depth;
    opt.fill = fill;
    opt.attributes = RK_SVO_ATTR_COLOR;
    raykit::SvoStatus st;
    const bool ok = raykit::build_svo(mesh.view(), opt, t, st);
    why = st.message;
    return ok;
}

struct Ray {
    glm::vec3 origin;
    glm::vec3 dir;
    float t_max;
    int family;  ///< index into family_names
};

inline const char* const family_names[] = {
    "random outside",   // 0: origin outside the root, aimed near it
    "random inside",    // 1: origin inside the root
    "axis-parallel",    // 2: one or two components exactly +0 / -0
    "origin on lattice",// 3: origin on a cell face / edge / corner
    "through lattice",  // 4: aimed exactly at a cell corner or edge point
    "in face plane",    // 5: runs inside a cell face plane
    "tiny components",  // 6: components of 1e-30, denormals, 1e-9 next to 1
    "far origin",       // 7: origin 1e3..1e5 root sizes away
    "scaled dir",       // 8: |dir| from 1e-30 to 1e30
    "short t_max",      // 9: t_max ends inside the root
    "aimed at a voxel", // 10: aimed_rays(): through a point inside a listed voxel
};
constexpr int family_count = 10;  // the families make_rays cycles through (aimed_rays is 10)

/// Distance (world units) of p from the surface of the box [lo, lo + cs]^3: how far outside it is,
/// or, inside, how far from the nearest face (0 when `inside_ok`: an origin inside a node). How the
/// traversal tests check that a hit point lies on its node's surface.
inline double surface_distance(glm::dvec3 p, glm::dvec3 lo, double cs, bool inside_ok)
{
    double outside = 0.0, inside = 1e300;
    for (int a = 0; a < 3; ++a) {
        const double below = lo[a] - p[a], above = p[a] - (lo[a] + cs);
        outside = std::fmax(outside, std::fmax(below, above));
        inside = std::fmin(inside, std::fmin(-below, -above));
    }
    if (outside > 0.0) return outside;
    return inside_ok ? 0.0 : inside;
}

/// `n` rays cycling through every family, deterministic in `seed`.
inline std::vector<Ray> make_rays(size_t n, glm::vec3 root_min, float root_size, uint32_t depth, uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    auto rand_dir = [&]() {
        for (;;) {
            glm::vec3 d(2.0f * U(rng) - 1.0f, 2.0f * U(rng) - 1.0f, 2.0f * U(rng) - 1.0f);
            float l = glm::length(d);
            if (l > 0.05f && l <= 1.0f) return d / l;
        }
    };
    const float cell = root_size / float(1u << depth);
    const glm::vec3 centre = root_min + glm::vec3(0.5f * root_size);
    auto in_root = [&]() { return root_min + root_size * glm::vec3(U(rng), U(rng), U(rng)); };
    // A lattice point at the finest level, coordinates 0..2^depth (exact for dyadic roots).
    auto lattice = [&](uint32_t level) {
        const uint32_t side = 1u << level;
        std::uniform_int_distribution<uint32_t> k(0, side);
        const float s = root_size / float(side);
        return root_min + s * glm::vec3(float(k(rng)), float(k(rng)), float(k(rng)));
    };
    auto axis = [&]() { return static_cast<int>(rng() % 3); };
    auto rand_level = [&]() { return std::uniform_int_distribution<uint32_t>(0, depth)(rng); };
    std::vector<Ray> rays;
    rays.reserve(n);
    const float inf = std::numeric_limits<float>::max();
    for (size_t i = 0; i < n; ++i) {
        const int fam = static_cast<int>(i % family_count);
        Ray r{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), inf, fam};
        switch (fam) {
        case 0: {
            glm::vec3 target = in_root();
            r.dir = rand_dir();
            r.origin = target - r.dir * (root_size * (0.6f + 2.0f * U(rng)));
            break;
        }
        case 1: r.origin = in_root(); r.dir = rand_dir(); break;
        case 2: {
            r.origin = U(rng) < 0.5f ? in_root() : centre + (glm::vec3(U(rng), U(rng), U(rng)) - 0.5f) * (3.0f * root_size);
            r.dir = rand_dir();
            const int k = static_cast<int>(rng() % 3);
            r.dir[k] = (rng() & 1) ? -0.0f : 0.0f;
            if (rng() & 1) r.dir[(k + 1) % 3] = (rng() & 1) ? -0.0f : 0.0f;
            if (r.dir == glm::vec3(0.0f)) r.dir[(k + 2) % 3] = 1.0f;
            break;
        }
        case 3: {
            r.origin = lattice(rand_level());
            // Move along 0..2 axes inside the cell: face or edge instead of corner.
            for (int a = 0; a < 3; ++a)
                if (rng() % 3 == 0) r.origin[a] = std::fmin(r.origin[a] + cell * 0.5f, root_min[a] + root_size);
            r.dir = rand_dir();
            if (rng() % 4 == 0) r.dir[axis()] = 0.0f;
            break;
        }
        case 4: {
            glm::vec3 target = lattice(rand_level());
            if (rng() & 1) target[axis()] += cell * 0.25f;  // an edge point instead of a corner
            glm::vec3 from = U(rng) < 0.5f ? in_root() : target + rand_dir() * (root_size * (0.3f + U(rng)));
            r.origin = from;
            r.dir = target - from;
            if (r.dir == glm::vec3(0.0f)) r.dir = glm::vec3(0.0f, 0.0f, -1.0f);
            break;
        }
        case 5: {
            r.origin = lattice(rand_level());
            r.origin += glm::vec3(U(rng), U(rng), U(rng)) * cell;
            const int k = static_cast<int>(rng() % 3);
            r.origin[k] = lattice(rand_level())[k];  // exactly on a face plane
            r.dir = rand_dir();
            r.dir[k] = (rng() & 1) ? -0.0f : 0.0f;
            if (r.dir == glm::vec3(0.0f)) r.dir[(k + 1) % 3] = 1.0f;
            break;
        }
        case 6: {
            r.origin = U(rng) < 0.5f ? in_root() : lattice(rand_level());
            r.dir = rand_dir();
            const float tiny[] = {1e-30f, -1e-30f, 1e-40f, -1e-42f, 1e-9f, -3e-8f, 1e-20f};
            r.dir[axis()] = tiny[rng() % 7];
            if (rng() & 1) r.dir[axis()] = tiny[rng() % 7];
            break;
        }
        case 7: {
            glm::vec3 target = in_root();
            r.dir = rand_dir();
            const float far = root_size * std::pow(10.0f, 3.0f + 2.0f * U(rng));
            r.origin = target - r.dir * far;
            break;
        }
        case 8: {
            glm::vec3 target = in_root();
            glm::vec3 d = rand_dir();
            r.origin = target - d * (root_size * (0.5f + U(rng)));
            r.dir = d * std::pow(10.0f, -30.0f + 60.0f * U(rng));
            break;
        }
        default: {
            r.origin = U(rng) < 0.5f ? in_root() : centre - rand_dir() * root_size;
            r.dir = rand_dir();
            r.t_max = root_size * U(rng);
            break;
        }
        }
        rays.push_back(r);
    }
    return rays;
}

/// `n` rays aimed at random points inside voxels of `cells` (leaf cells of a depth-`depth` tree
/// in the root [root_min, root_min + root_size]^3): a random ray through a sparse deep tree almost
/// never hits, these mostly do. Every fifth runs along z (axis-parallel); a third start three
/// voxels before their target, the rest up to a root size before it. Family 10.
inline std::vector<Ray> aimed_rays(const std::vector<glm::ivec3>& cells, glm::vec3 root_min, float root_size,
                                   uint32_t depth, size_t n, uint64_t seed)
{
    std::vector<Ray> rays;
    if (cells.empty()) return rays;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f), S(-1.0f, 1.0f);
    const float cs = root_size / float(1u << depth);
    for (size_t i = 0; i < n; ++i) {
        const glm::ivec3 c = cells[rng() % cells.size()];
        const glm::vec3 target = root_min + cs * (glm::vec3(c) + glm::vec3(U(rng), U(rng), U(rng)));
        glm::vec3 dir = glm::normalize(glm::vec3(S(rng), S(rng), S(rng)) + glm::vec3(1e-3f));
        if (i % 5 == 0) dir = glm::vec3(0.0f, 0.0f, (i & 1) ? 1.0f : -1.0f);
        const float back = (i % 3 == 0) ? cs * 3.0f : root_size * U(rng);
        rays.push_back({target - dir * back, dir, std::numeric_limits<float>::max(), 10});
    }
    return rays;
}

}  // namespace svotrace
