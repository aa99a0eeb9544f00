// raykit — bench/trace/trace_scene.hpp: the scene every tracer of raykit_bench_trace sees: the test
// meshes (tests/reference/svo_meshes.hpp), their bounding box, the root cube a voxel tracer
// voxelises in, and one pinhole camera per mesh giving a frame of primary rays (origin + unit
// direction, float). Depends on glm and the mesh generators only (no Google Benchmark, no peers), so
// a test or a demo can reuse it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "raykit/svo_build.hpp"
#include "raykit/svo_mesh.hpp"
#include "reference/svo_meshes.hpp"

namespace rktrace {

/// A primary ray: origin and unit direction, so a hit distance t is a world-space length.
struct Ray {
    glm::vec3 org{0.0f};
    glm::vec3 dir{0.0f, 0.0f, 1.0f};
};

/// What a tracer returns for a ray that hits nothing.
constexpr float kMiss = std::numeric_limits<float>::infinity();

inline bool is_hit(float t) { return t < kMiss; }

struct Bounds {
    glm::vec3 lo{0.0f};
    glm::vec3 hi{0.0f};
    glm::vec3 centre() const { return 0.5f * (lo + hi); }
    glm::vec3 extent() const { return hi - lo; }
};

/// Bounding box of the vertices that triangles use.
inline Bounds mesh_bounds(const raykit::SvoMeshData& m)
{
    Bounds b;
    b.lo = glm::vec3(std::numeric_limits<float>::max());
    b.hi = glm::vec3(-std::numeric_limits<float>::max());
    for (std::uint32_t i : m.indices) {
        b.lo = glm::min(b.lo, m.positions[i]);
        b.hi = glm::max(b.hi, m.positions[i]);
    }
    return b;
}

/// Total triangle area (for memory estimates of narrow-band grids).
inline double mesh_area(const raykit::SvoMeshData& m)
{
    double a = 0.0;
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        const glm::dvec3 p0(m.positions[m.indices[i]]), p1(m.positions[m.indices[i + 1]]), p2(m.positions[m.indices[i + 2]]);
        a += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    }
    return a;
}

/// The root cube a voxel tracer (raykit's octree, OpenVDB's grid) voxelises in: edge = the bounding
/// box's largest extent padded by `padding` (1%), centred on the box. At depth D a voxel is
/// size / 2^D, voxel (i, j, k) spans min + [i, i+1] * voxel(D) on each axis.
struct Cube {
    glm::vec3 min{0.0f};
    float size = 0.0f;
    double voxel(int depth) const { return static_cast<double>(size) / std::ldexp(1.0, depth); }
    glm::vec3 centre() const { return min + glm::vec3(0.5f * size); }
};

inline Cube bounds_cube(const Bounds& b, float padding = 0.01f)
{
    const glm::vec3 e = b.extent();
    Cube c;
    c.size = std::max(e.x, std::max(e.y, e.z)) * (1.0f + padding);
    c.min = b.centre() - glm::vec3(0.5f * c.size);
    return c;
}

/// Pinhole camera, square pixels, y up in the image. ray(x, y) goes through pixel (x, y)'s centre,
/// row 0 at the top.
struct Camera {
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    glm::vec3 right{1.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float tan_half_fov_y = 0.36397f;  // tan(20 degrees)
    int width = 512;
    int height = 512;

    Ray ray(int x, int y) const
    {
        const float aspect = static_cast<float>(width) / static_cast<float>(height);
        const float u = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f) * tan_half_fov_y * aspect;
        const float v = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height)) * tan_half_fov_y;
        return Ray{eye, glm::normalize(forward + u * right + v * up)};
    }
};

/// Where every camera looks from (relative to the box centre): in front, right of and above it, so
/// a y-up figure is seen three-quarter and axis-aligned faces are oblique (no ray runs along one).
inline glm::vec3 default_view_direction() { return glm::normalize(glm::vec3(0.45f, 0.35f, 1.0f)); }

/// A camera looking at the box centre from `from_dir`, `fov_y_degrees` vertical field of view,
/// placed so that all 8 box corners project within `fill` of the image's half-width and
/// half-height: the box fills most of the frame, the mesh less (rays past it miss).
inline Camera fit_camera(const Bounds& b, int width, int height, glm::vec3 from_dir = default_view_direction(),
                         float fov_y_degrees = 40.0f, float fill = 0.95f)
{
    Camera c;
    c.width = width;
    c.height = height;
    c.tan_half_fov_y = std::tan(0.5f * glm::radians(fov_y_degrees));
    c.forward = -glm::normalize(from_dir);
    const glm::vec3 world_up = std::fabs(c.forward.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    c.right = glm::normalize(glm::cross(c.forward, world_up));
    c.up = glm::cross(c.right, c.forward);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float kx = c.tan_half_fov_y * aspect * fill, ky = c.tan_half_fov_y * fill;
    // Corner p at distance d from the centre along -forward: view depth z = d + dot(p - centre, forward);
    // in frame when |dot(p - centre, right)| <= kx z and the same with up and ky.
    const glm::vec3 centre = b.centre();
    float d = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 p((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
        const glm::vec3 q = p - centre;
        const float along = glm::dot(q, c.forward);
        d = std::max(d, std::fabs(glm::dot(q, c.right)) / kx - along);
        d = std::max(d, std::fabs(glm::dot(q, c.up)) / ky - along);
    }
    c.eye = centre - d * c.forward;
    return c;
}

/// The camera's rays, row-major (index y * width + x).
inline std::vector<Ray> primary_rays(const Camera& c)
{
    std::vector<Ray> rays;
    rays.reserve(static_cast<std::size_t>(c.width) * static_cast<std::size_t>(c.height));
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) rays.push_back(c.ray(x, y));
    return rays;
}

/// One benchmark scene: a mesh, its bounds, root cube, camera and frame of primary rays.
struct Scene {
    std::string key;    // trace/<key>/...
    std::string title;  // for reports
    raykit::SvoMeshData mesh;
    std::size_t triangles = 0;
    double area = 0.0;
    Bounds bounds;
    Cube cube;
    Camera camera;
    std::vector<Ray> rays;
    /// Deepest depth voxel tracers run at by default (RAYKIT_BENCH_TRACE_FULL=1 lifts it): meshes
    /// with much surface per cube volume make level sets of gigabytes and minutes sooner.
    int default_max_depth = 10;
};

/// The octree build of a scene for raykit's tracers: geometry only (no attribute stream), at `depth`
/// in the scene's shared root cube, so that depth D means the same voxels as OpenVDB's rows.
inline raykit::SvoBuildOptions svo_options(const Scene& s, int depth)
{
    raykit::SvoBuildOptions opt;
    opt.depth = depth;
    opt.attributes = 0;
    opt.fixed_bounds = true;
    opt.bounds_min = s.cube.min;
    opt.bounds_size = s.cube.size;
    return opt;
}

inline Scene make_scene(std::string key, std::string title, raykit::SvoMeshData mesh, int image_size, int default_max_depth = 10)
{
    Scene s;
    s.default_max_depth = default_max_depth;
    s.key = std::move(key);
    s.title = std::move(title);
    s.mesh = std::move(mesh);
    s.triangles = rkmesh::triangle_count(s.mesh);
    s.area = mesh_area(s.mesh);
    s.bounds = mesh_bounds(s.mesh);
    s.cube = bounds_cube(s.bounds);
    s.camera = fit_camera(s.bounds, image_size, image_size);
    s.rays = primary_rays(s.camera);
    return s;
}

/// The benchmark's meshes, in run order: the thesis's ~1k-triangle character stand-in, the two
/// spheres of the reference Embree measurement (5,856 and ~70k triangles), a dense non-convex torus
/// (seen 30 degrees off its axis: rays through the hole, the near side hiding the far one) and a
/// Menger sponge (through-holes, many silhouettes, axis-aligned faces on voxel boundaries; its
/// surface per cube volume is 4x the sphere's, so voxel tracers stop at depth 9 by default: depth 10
/// is a 1 GB level set).
inline std::vector<Scene> make_scenes(int image_size)
{
    std::vector<Scene> s;
    s.push_back(make_scene("figure", "figure(): standing figure, 1,024 triangles", rkmesh::figure(), image_size));
    s.push_back(make_scene("uv_sphere_5856", "uv_sphere(48, 62): 5,856 triangles", rkmesh::uv_sphere(48, 62), image_size));
    s.push_back(make_scene("uv_sphere_69632", "uv_sphere(256, 137): 69,632 triangles", rkmesh::uv_sphere(256, 137), image_size));
    s.push_back(make_scene("torus_69120", "torus(192, 180): 69,120 triangles, non-convex", rkmesh::torus(192, 180), image_size));
    s.push_back(make_scene("menger_2", "menger_sponge(2): 2,112 triangles, non-convex, axis-aligned", rkmesh::menger_sponge(2),
                           image_size, 9));
    return s;
}

}  // namespace rktrace
