// raykit's level-of-detail rows of raykit_bench_trace: svo_trace_packets in a RK_SVO_TRAVERSE_LOD=1
// build (this unit; the other raykit rows are full detail), each ray stopping at the first
// non-empty node no wider than one pixel of the scene's camera (rk_svo_pixel_cone, scale 1): what a
// renderer that needs no sub-pixel detail traces. A coarser answer than the full-detail rows, so
// its own rows: trace/<mesh>/raykit_packet_lod/d<D>/threads:<n>. Where voxels are wider than a
// pixel (shallow trees) it is the full-detail answer.
#define RK_SVO_TRAVERSE_LOD 1
#include "trace_raykit_prepare.hpp"

namespace rktrace {
namespace {

// Tolerances: the nodes a ray stops at are up to a pixel wide, so silhouettes widen by up to a
// pixel instead of a voxel (more hits) and hits come up to a node early: at depth 12 one pixel is
// about 8-16 voxels of these scenes, hence the loose distance tolerance. Losing hits still fails
// the row (the same -3 % floor as full detail).
const TracerRegistrar reg_packet_lod(TracerSpec{"raykit_packet_lod",
                                                "raykit svo_trace_packets with a 1-pixel level-of-detail footprint (RK_SVO_TRAVERSE_LOD=1), geometry only",
                                                33, true, {8, 9, 10, 11, 12}, false,
                                                [](const Scene& s, int depth) { return prepare(s, depth, 2, 1.0f); }, 50.0, 40.0, -3.0});

}  // namespace
}  // namespace rktrace
