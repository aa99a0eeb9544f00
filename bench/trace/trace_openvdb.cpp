// raykit — bench/trace/trace_openvdb.cpp: OpenVDB's level-set ray intersector on a narrow-band level
// set of the same mesh, the closest voxel peer of raykit's octree. Per depth D: FloatGrid from
// openvdb::tools::meshToLevelSet, voxel size = the scene's cube / 2^D, voxel centres on the cube's
// lattice (min + (i + 1/2) voxel), half-width 3 voxels; build_ms times meshToLevelSet (TBB, every
// core: counter build_threads). Tracing: one tools::LevelSetRayIntersector<FloatGrid> per thread
// (its search state is mutable), world-space math::Ray<double>, intersectsWS(ray, xyz, t).
// (OpenVDB 10's intersectsWS(ray, t) overload reads t before the search: the time where the ray
// enters the grid's bounding box, not the hit; hence the overload with the position.)
// Rows whose narrow band would not fit (estimate: kBytesPerBandVoxel per voxel within the half-width
// of the surface, against min(RAYKIT_BENCH_TRACE_MAX_BYTES or 8 GiB, half of MemAvailable)) are
// skipped with an error saying so. Compiled only when OpenVDB is found (bench/trace/CMakeLists.txt).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>
#include <openvdb/math/Ray.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/RayIntersector.h>
#include <tbb/task_arena.h>

#include "../proc_memory.hpp"
#include "trace_harness.hpp"

namespace rktrace {
namespace {

constexpr float kHalfWidth = 3.0f;
constexpr double kBytesPerBandVoxel = 16.0;  // grid values and topology plus meshToVolume's temporaries

using rkbench_mem::mem_available_bytes;

double memory_limit_bytes()
{
    double limit = 8.0 * 1024 * 1024 * 1024;
    if (const char* e = std::getenv("RAYKIT_BENCH_TRACE_MAX_BYTES")) limit = std::strtod(e, nullptr);
    const std::uint64_t avail = mem_available_bytes();
    if (avail) limit = std::min(limit, 0.5 * static_cast<double>(avail));
    return limit;
}

Prepared prepare(const Scene& s, int depth)
{
    static std::once_flag init;
    std::call_once(init, [] { openvdb::initialize(); });

    const double vox = s.cube.voxel(depth);
    const double est = s.area / (vox * vox) * 2.0 * static_cast<double>(kHalfWidth) * kBytesPerBandVoxel;
    const double limit = memory_limit_bytes();
    Prepared p;
    if (est > limit) {
        char msg[160];
        std::snprintf(msg, sizeof msg, "level set estimated at %.0f MiB, above the limit of %.0f MiB (RAYKIT_BENCH_TRACE_MAX_BYTES,"
                      " half of MemAvailable)", est / (1024.0 * 1024), limit / (1024.0 * 1024));
        p.skip = msg;
        return p;
    }

    std::vector<openvdb::Vec3s> points;
    points.reserve(s.mesh.positions.size());
    for (const glm::vec3& v : s.mesh.positions) points.emplace_back(v.x, v.y, v.z);
    std::vector<openvdb::Vec3I> tris;
    tris.reserve(s.triangles);
    for (std::size_t i = 0; i + 2 < s.mesh.indices.size(); i += 3)
        tris.emplace_back(s.mesh.indices[i], s.mesh.indices[i + 1], s.mesh.indices[i + 2]);
    openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(vox);
    const glm::dvec3 origin = glm::dvec3(s.cube.min) + glm::dvec3(0.5 * vox);
    xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));

    const auto t0 = std::chrono::steady_clock::now();
    openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, tris, kHalfWidth);
    p.build_ms = seconds_since(t0) * 1e3;
    p.counters.emplace_back("build_threads", static_cast<double>(tbb::this_task_arena::max_concurrency()));
    p.counters.emplace_back("grid_MB", static_cast<double>(grid->memUsage()) * 1e-6);
    p.counters.emplace_back("active_voxels", static_cast<double>(grid->activeVoxelCount()));
    p.keep = grid;
    const openvdb::FloatGrid* g = grid.get();
    p.make_thread = [g] {
        auto isect = std::make_shared<openvdb::tools::LevelSetRayIntersector<openvdb::FloatGrid>>(*g);
        return per_ray([isect](const Ray& r) {
            const openvdb::math::Ray<double> ray(openvdb::Vec3d(r.org.x, r.org.y, r.org.z), openvdb::Vec3d(r.dir.x, r.dir.y, r.dir.z));
            openvdb::Vec3d xyz;
            double t = 0.0;
            return isect->intersectsWS(ray, xyz, t) ? static_cast<float>(t) : kMiss;
        });
    };
    return p;
}

const TracerRegistrar reg(TracerSpec{"openvdb", "OpenVDB " OPENVDB_LIBRARY_VERSION_STRING
                                                " LevelSetRayIntersector on meshToLevelSet, half-width 3",
                                     20, true, {}, false, prepare});

}  // namespace
}  // namespace rktrace
