// raykit — bench/trace/trace_embree.cpp: Embree 3 on the source triangles, the exact reference of
// raykit_bench_trace (other rows' hits are checked against its). One triangle geometry, scene and
// geometry at RTC_BUILD_QUALITY_HIGH, one rtcIntersect1 per ray (single rays, no packets or streams),
// default device (its BVH build uses every core; build_ms times geometry upload + rtcCommitScene).
// Compiled only when find_package(embree 3 CONFIG) succeeds (bench/trace/CMakeLists.txt).
#include <chrono>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

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
            rtcIntersect1(scene, &ctx, &rh);
            return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : kMiss;
        });
    };
    return p;
}

const TracerRegistrar reg(TracerSpec{"embree", "Embree " RTC_VERSION_STRING " rtcIntersect1 on the triangles, BVH quality high", 10,
                                     false, {}, true, prepare});

}  // namespace
}  // namespace rktrace
