#include "raytrace/integrators/CpuScene.h"

#include "raytrace/materials/MaterialRecord.h"
#include "raytrace/materials/SurfaceTexture.h"

namespace gpurt {

using namespace raymath;

CpuScene::CpuScene(const Scene& scene, std::unique_ptr<CpuAccelerator> accel, float rayOffset)
    : scene_(scene), accel_(std::move(accel)), rayOffset_(rayOffset), emitters_(buildEmitterTable(scene)),
      environment_(buildEnvironmentTable(scene)) {
    triangles_.reserve(scene.triangles.size());
    for (const Triangle& t : scene.triangles)
        triangles_.push_back({t.v0, t.v1 - t.v0, t.v2 - t.v0});
}

TraceHit CpuScene::trace(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const {
    return accel_->closestHit(o, d, tLimit, coverageKey);
}

TraceHit CpuScene::traceAny(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const {
    return accel_->anyHit(o, d, tLimit, coverageKey);
}

bool CpuScene::unblocked(glm::vec3 origin, glm::vec3 dir, float limit, uint32_t coverageKey, RenderStats& stats) const {
    const TraceHit blocker = traceAny(origin, dir, limit, coverageKey);
    ++stats.shadowRays;
    if (blocker.state == RAY_OVERFLOW) ++stats.overflowRays;
    return blocker.prim < 0;
}

SurfaceHit CpuScene::surfaceAt(const TraceHit& hit, glm::vec3 o, glm::vec3 d) const {
    const PreparedTriangle& tri = triangles_[size_t(hit.prim)];
    SurfaceHit s;
    s.front = frontFace(tri.e1, tri.e2, d);
    s.m = materialFacing(materialRecord(scene_, uint32_t(hit.prim), hit.u, hit.v), s.front);
    s.p = o + hit.t * d;
    s.n = facingNormal(tri.e1, tri.e2, d);
    s.ns = s.n;  // the shading normal (surface.frag)
    if (!scene_.normals.empty()) {
        const TriangleNormals& vn = scene_.normals[size_t(hit.prim)];
        s.ns = shadingNormal(vn.n0, vn.n1, vn.n2, hit.u, hit.v, s.n);
    }
    const Material& m = scene_.materials[scene_.materialIds[size_t(hit.prim)]];
    if (s.m.coat > 0.0f)  // shading.glsl fetchMaterialRecord: not the base's normal map
        s.m.coatNormal = normalMappedAt(hit, d, s.n, s.ns, m.clearcoatNormalTexture, m.clearcoatNormalScale);
    s.ns = normalMappedAt(hit, d, s.n, s.ns, m.normalTexture, m.normalScale);
    return s;
}

// The shading normal ns at the hit bent by normal map `map` (-1: none) of scale `scale`
// (shading.glsl fetchNormalMapped).
glm::vec3 CpuScene::normalMappedAt(const TraceHit& hit, glm::vec3 d, glm::vec3 ng, glm::vec3 ns, int map,
                                   float scale) const {
    if (map < 0 || scene_.texcoords.empty()) return ns;
    const PreparedTriangle& tri = triangles_[size_t(hit.prim)];
    const uint32_t prim = uint32_t(hit.prim);
    const glm::vec3 texel = sampleLinear(scene_.textures[size_t(map)], texcoordAt(scene_, prim, hit.u, hit.v));
    glm::vec2 dt1, dt2;
    texcoordEdgesAt(scene_, prim, dt1, dt2);
    if (!scene_.tangents.empty())  // SCENE_VERTEX_TANGENTS
        return normalMappedTangent(ns, ng, d, vertexTangentAt(scene_, prim, hit.u, hit.v), tri.e1, tri.e2, dt1, dt2,
                                   texel, scale);
    return normalMapped(ns, ng, d, tri.e1, tri.e2, dt1, dt2, texel, scale);
}

}  // namespace gpurt
