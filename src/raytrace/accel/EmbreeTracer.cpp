#include "raytrace/accel/EmbreeTracer.h"

#include "base/Parallel.h"
#include "raytrace/common/RenderTypes.h"
#include "stream/StreamErrors.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>

namespace gpurt {

struct EmbreeTracer::Handles {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Handles() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

EmbreeTracer::EmbreeTracer(const Scene& scene, int threads)
    : handles_(std::make_unique<Handles>()), threads_(std::max(1, threads)) {
    const std::string config = "threads=" + std::to_string(threads_);
    handles_->device = rtcNewDevice(config.c_str());
    if (!handles_->device) throw EnvironmentError("Embree: cannot create a device (" + config + ")");
    handles_->scene = rtcNewScene(handles_->device);
    rtcSetSceneBuildQuality(handles_->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t n = scene.triangles.size();
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    if (n > 0 && (!vertices || !indices)) {
        rtcReleaseGeometry(geometry);
        throw EnvironmentError("Embree: cannot allocate the geometry of " + std::to_string(n) + " triangles");
    }
    for (size_t k = 0; k < n; ++k) {
        const Triangle& t = scene.triangles[k];
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (size_t c = 0; c < 3; ++c) {
            for (size_t a = 0; a < 3; ++a) vertices[9 * k + 3 * c + a] = v[c][int(a)];
            indices[3 * k + c] = unsigned(3 * k + c);
        }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(handles_->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(handles_->scene);
}

EmbreeTracer::~EmbreeTracer() = default;

std::string EmbreeTracer::version() { return RTC_VERSION_STRING; }

namespace {

constexpr float kNoHit = -1.0f;

void setRay(RTCRay& r, glm::vec3 o, glm::vec3 d, float tLimit) {
    r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
    r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
    r.tnear = 0.0f;
    r.tfar = tLimit;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
}

// Rays [begin, end) one at a time.
void traceSingle(RTCScene scene, const RayStream& rays, bool anyHit, size_t begin, size_t end,
                 std::vector<glm::vec4>& hits) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = begin; i < end; ++i) {
        if (rays.tLimit[i] < 0.0f) continue;
        if (anyHit) {
            RTCRay r;
            setRay(r, rays.origin[i], rays.direction[i], rays.tLimit[i]);
            rtcOccluded1(scene, &context, &r);
            hits[i] = glm::vec4(0.0f, 0.0f, 0.0f, r.tfar < 0.0f ? 0.0f : kNoHit);  // tfar = -inf: blocked
            continue;
        }
        RTCRayHit rh;
        setRay(rh.ray, rays.origin[i], rays.direction[i], rays.tLimit[i]);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        hits[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                      ? glm::vec4(std::numeric_limits<float>::infinity(), 0.0f, 0.0f, kNoHit)
                      : glm::vec4(rh.ray.tfar, rh.hit.u, rh.hit.v, float(rh.hit.primID));
    }
}

// Embree's 8- and 16-wide packet calls, chosen by the packet type.
void intersectPacket(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit8* p) {
    rtcIntersect8(valid, scene, context, p);
}
void intersectPacket(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit16* p) {
    rtcIntersect16(valid, scene, context, p);
}
void occludedPacket(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRay8* p) {
    rtcOccluded8(valid, scene, context, p);
}
void occludedPacket(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRay16* p) {
    rtcOccluded16(valid, scene, context, p);
}

// Rays [begin, end) in packets of N consecutive elements (RTCRayHit8 or RTCRayHit16).
template <size_t N, typename Packet>
void tracePackets(RTCScene scene, const RayStream& rays, bool anyHit, size_t begin, size_t end,
                  std::vector<glm::vec4>& hits) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) Packet packet;
    alignas(64) int valid[N];
    for (size_t first = begin; first < end; first += N) {
        const size_t count = std::min<size_t>(N, end - first);
        auto& r = packet.ray;
        for (size_t k = 0; k < N; ++k) {
            const size_t i = first + k;
            valid[k] = k < count && rays.tLimit[i] >= 0.0f ? -1 : 0;
            const glm::vec3 o = valid[k] ? rays.origin[i] : glm::vec3(0.0f);
            const glm::vec3 d = valid[k] ? rays.direction[i] : glm::vec3(0.0f, 0.0f, 1.0f);
            r.org_x[k] = o.x, r.org_y[k] = o.y, r.org_z[k] = o.z;
            r.dir_x[k] = d.x, r.dir_y[k] = d.y, r.dir_z[k] = d.z;
            r.tnear[k] = 0.0f;
            r.tfar[k] = valid[k] ? rays.tLimit[i] : 0.0f;
            r.time[k] = 0.0f;
            r.mask[k] = 0xFFFFFFFFu;
            r.id[k] = unsigned(k);
            r.flags[k] = 0;
            packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        if (anyHit) occludedPacket(valid, scene, &context, &r);
        else intersectPacket(valid, scene, &context, &packet);
        for (size_t k = 0; k < count; ++k) {
            if (!valid[k]) continue;
            glm::vec4& h = hits[first + k];
            if (anyHit) h = glm::vec4(0.0f, 0.0f, 0.0f, r.tfar[k] < 0.0f ? 0.0f : kNoHit);
            else if (packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID)
                h = glm::vec4(std::numeric_limits<float>::infinity(), 0.0f, 0.0f, kNoHit);
            else h = glm::vec4(r.tfar[k], packet.hit.u[k], packet.hit.v[k], float(packet.hit.primID[k]));
        }
    }
}

}  // namespace

uint64_t EmbreeTracer::trace(const RayStream& rays, bool anyHit, EmbreeMode mode, std::vector<glm::vec4>& hits) const {
    const size_t n = rays.tLimit.size();
    hits.assign(n, glm::vec4(std::numeric_limits<float>::infinity(), 0.0f, 0.0f, kNoHit));
    // Chunks of one stream row (an image row for primary rays: coherent), handed out dynamically.
    parallelChunks(n, std::max<size_t>(8, size_t(rays.width)), threads_, [&](size_t begin, size_t end, size_t) {
        if (mode == EmbreeMode::Packet8) tracePackets<8, RTCRayHit8>(handles_->scene, rays, anyHit, begin, end, hits);
        else if (mode == EmbreeMode::Packet16)
            tracePackets<16, RTCRayHit16>(handles_->scene, rays, anyHit, begin, end, hits);
        else traceSingle(handles_->scene, rays, anyHit, begin, end, hits);
    });
    return rays.rays();
}

}  // namespace gpurt
