// raykit's rows of raykit_bench_trace: the C++ build of svo_traverse.glsl (rk_svo_trace, the same
// text the shaders run) over a tree that raykit::build_svo voxelises from the scene's triangles in
// the shared root cube (so depth D means the same voxels as OpenVDB's rows), geometry only (no
// attribute stream is read, as in a depth or shadow pass). Rows: trace/<mesh>/raykit/d<D>/threads:<n>.
#include "trace_raykit_prepare.hpp"

static_assert(RK_SVO_TRAVERSE_LOD == 0, "full detail");

namespace rktrace {
namespace {

// Tolerances: a surface voxelisation marks every voxel the surface touches, so its shell reaches up
// to a voxel outside the surface: silhouettes widen by up to a voxel (more hits: +14% on the torus
// and +37% on the thin-limbed figure at depth 6 in the 64 x 64 smoke frame, a few % at depth 10 in
// 512 x 512) and hits come up to sqrt(3) voxels early (about -1.0 to -1.5 measured). It never loses
// hits, though: fewer than the reference's minus 3% fails the row, so a traversal that misses
// surfaces cannot pass the smoke test.
const TracerRegistrar reg(TracerSpec{"raykit", "raykit rk_svo_trace (C++ build of svo_traverse.glsl), geometry only", 30, true,
                                     {8, 9, 10, 11, 12}, false,
                                     [](const Scene& s, int depth) { return prepare(s, depth, 0); }, 50.0, 2.0, -3.0});
// The same rays through svo_trace_rays (raykit/svo_trace_simd.hpp): the loop on 8 AVX2 lanes, the
// answers bit for bit rk_svo_trace's (test_svo_trace_simd).
const TracerRegistrar reg_simd(TracerSpec{"raykit_simd", "raykit svo_trace_rays (rk_svo_trace's loop on 8 AVX2 lanes), geometry only",
                                          31, true, {8, 9, 10, 11, 12}, false,
                                          [](const Scene& s, int depth) { return prepare(s, depth, 1); }, 50.0, 2.0, -3.0});

// Coherent rays (8 x 4 pixel tiles on AVX-512, else 4 x 4 on AVX2) sharing one traversal (raykit/svo_trace_packet.hpp):
// the answers are rk_svo_trace's (test_svo_trace_packet).
const TracerRegistrar reg_packet(TracerSpec{"raykit_packet", "raykit svo_trace_packets (8x4 ray packets on AVX-512 lanes, else 4x4 on AVX2), geometry only",
                                            32, true, {8, 9, 10, 11, 12}, false,
                                            [](const Scene& s, int depth) { return prepare(s, depth, 2); }, 50.0, 2.0, -3.0});

}  // namespace
}  // namespace rktrace
