// raykit — bench/trace/trace_embree.cpp: Embree 3 on the source triangles, the exact reference of
// raykit_bench_trace (other rows' hits are checked against its). One triangle geometry, scene and
// geometry at RTC_BUILD_QUALITY_HIGH, default device (its BVH build uses every core; build_ms times
// geometry upload + rtcCommitScene). Two rows:
//   embree         one rtcIntersect1 per ray (single rays), the reference;
//   embree_coherent  rtcIntersect1M over the span's rays in 4x4 pixel-tile order with
//                  RTC_INTERSECT_CONTEXT_FLAG_COHERENT: Embree's own answer to coherent primary rays
//                  (it forms packets inside), the peer of raykit's packets. The fastest form measured on
//                  an AVX-512 CPU (the 5 meshes' frames, 3 runs of a scratch program timing every form
//                  in one process, interleaved): 2.7-3.9x rtcIntersect1 there (3.1-4.2x in the trace
//                  bench); rtcIntersect16 on 4x4 tiles 0.86-1.05x it, on 8x2 tiles 0.78-1.00x,
//                  rtcIntersect8 on 4x2 tiles 0.77-0.90x; without the coherent flag 16-ray packets
//                  lose half their speed.
// Compiled only when find_package(embree 3 CONFIG) succeeds (bench/trace/CMakeLists.txt).
#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "trace_harness.hpp"

namespace rktrace {
namespace {

struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    EmbreeScene() = default;
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;
    ~EmbreeScene()
    {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

void check(RTCDevice device, const char* what)
{
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("embree: ") + what + " failed (error " + std::to_string(static_cast<int>(e)) + ")");
}

// A ray of the frame as Embree's ray and hit record: t from 0 to kMiss, no hit yet.
void ray_hit(RTCRayHit& rh, const Ray& r)
{
    rh.ray.org_x = r.org.x;
    rh.ray.org_y = r.org.y;
    rh.ray.org_z = r.org.z;
    rh.ray.tnear = 0.0f;
    rh.ray.dir_x = r.dir.x;
    rh.ray.dir_y = r.dir.y;
    rh.ray.dir_z = r.dir.z;
    rh.ray.time = 0.0f;
    rh.ray.tfar = kMiss;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

Prepared prepare(const Scene& s, int /*depth*/)
{
    auto e = std::make_shared<EmbreeScene>();
    e->device = rtcNewDevice(nullptr);
    if (!e->device) throw std::runtime_error("embree: rtcNewDevice failed");

    const auto t0 = std::chrono::steady_clock::now();
    e->scene = rtcNewScene(e->device);
    rtcSetSceneBuildQuality(e->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(e->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          s.mesh.positions.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                               s.triangles));
    check(e->device, "rtcSetNewGeometryBuffer");
    std::memcpy(v, s.mesh.positions.data(), s.mesh.positions.size() * sizeof(glm::vec3));
    std::memcpy(idx, s.mesh.indices.data(), s.triangles * 3 * sizeof(unsigned));
    rtcCommitGeometry(g);
    rtcAttachGeometry(e->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(e->scene);
    check(e->device, "rtcCommitScene");

    Prepared p;
    p.build_ms = seconds_since(t0) * 1e3;
    p.keep = e;
    RTCScene scene = e->scene;
    p.make_thread = [scene] {
        return per_ray([scene](const Ray& r) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            RTCRayHit rh;
            ray_hit(rh, r);
            rtcIntersect1(scene, &ctx, &rh);
            return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : kMiss;
        });
    };
    return p;
}

// Embree's coherent stream over the span's rows (the harness hands out chunks of whole rows of
// `width` rays; a partial last row is traced too): the rays copied in 4x4 pixel-tile order into one RTCRayHit array, one
// rtcIntersect1M, the distances copied back (the copies are timed: an application pays them too).
Prepared prepare_coherent(const Scene& s, int depth)
{
    Prepared p = prepare(s, depth);
    RTCScene scene = std::static_pointer_cast<EmbreeScene>(p.keep)->scene;
    const std::size_t width = static_cast<std::size_t>(s.camera.width);
    p.make_thread = [scene, width] {
        auto buf = std::make_shared<std::vector<RTCRayHit>>();
        auto at = std::make_shared<std::vector<std::size_t>>();
        return SpanTracer([scene, width, buf, at](const Ray* rays, std::size_t n, float* t) {
            const std::size_t rows = (n + width - 1) / width;  // a partial last row too
            buf->resize(n);
            at->resize(n);
            std::size_t c = 0;
            for (std::size_t y0 = 0; y0 < rows; y0 += 4)
                for (std::size_t x0 = 0; x0 < width; x0 += 4)
                    for (std::size_t y = y0; y < std::min(rows, y0 + 4); ++y)
                        for (std::size_t x = x0; x < std::min(width, x0 + 4) && y * width + x < n; ++x) {
                            const std::size_t i = y * width + x;
                            ray_hit((*buf)[c], rays[i]);
                            (*at)[c++] = i;
                        }
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            rtcIntersect1M(scene, &ctx, buf->data(), static_cast<unsigned>(c), sizeof(RTCRayHit));
            for (std::size_t j = 0; j < c; ++j) {
                const RTCRayHit& rh = (*buf)[j];
                t[(*at)[j]] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : kMiss;
            }
        });
    };
    return p;
}

const TracerRegistrar reg(TracerSpec{"embree", "Embree " RTC_VERSION_STRING " rtcIntersect1 on the triangles, BVH quality high", 10,
                                     false, {}, true, prepare});
const TracerRegistrar reg_coherent(TracerSpec{"embree_coherent",
                                              "Embree " RTC_VERSION_STRING " rtcIntersect1M, coherent context, rays in 4x4 pixel tiles, BVH quality high",
                                              11, false, {}, false, prepare_coherent});

}  // namespace
}  // namespace rktrace
