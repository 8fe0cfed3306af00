// The CPU backend: the integrators' per-sample code (Whitted's ray tree, the path integrator) over
// a CpuAccelerator, with the shared shading, material and path code of glsl/common.
#include "raytrace/CpuTracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "raytrace/MaterialRecord.h"
#include "raytrace/accel/grid/GridCpu.h"
#include "raytrace/Parallel.h"
#include "raytrace/RayMath.h"

namespace gpurt {

using namespace raymath;

CpuTracer::CpuTracer(const Scene& scene, const UniformGrid& grid)
    : scene_(scene),
      accel_(std::make_unique<GridCpu>(scene, grid)),
      rayOffset_(grid.rayOffset()),
      emitters_(buildEmitterTable(scene)) {
    triangles_.reserve(scene.triangles.size());
    for (const Triangle& t : scene.triangles)
        triangles_.push_back({t.v0, t.v1 - t.v0, t.v2 - t.v0});
}

TraceHit CpuTracer::trace(glm::vec3 o, glm::vec3 d, float tLimit) const { return accel_->closestHit(o, d, tLimit); }

TraceHit CpuTracer::traceAny(glm::vec3 o, glm::vec3 d, float tLimit) const { return accel_->anyHit(o, d, tLimit); }

uint64_t CpuTracer::traceStream(const RayStream& rays, bool anyHit, int threads,
                               std::vector<glm::vec4>& hits) const {
    const size_t n = rays.tLimit.size();
    hits.assign(n, glm::vec4(std::numeric_limits<float>::infinity(), 0.0f, 0.0f, -1.0f));
    parallelChunks(n, std::max<size_t>(8, size_t(rays.width)), threads, [&](size_t begin, size_t end, size_t) {
        for (size_t i = begin; i < end; ++i) {
            if (rays.tLimit[i] < 0.0f) continue;
            const TraceHit h = anyHit ? traceAny(rays.origin[i], rays.direction[i], rays.tLimit[i])
                                      : trace(rays.origin[i], rays.direction[i], rays.tLimit[i]);
            if (h.prim >= 0) hits[i] = glm::vec4(h.t, h.u, h.v, float(h.prim));
        }
    });
    return rays.rays();
}

bool CpuTracer::unblocked(glm::vec3 origin, glm::vec3 dir, float limit, RenderStats& stats) const {
    const TraceHit blocker = traceAny(origin, dir, limit);
    ++stats.shadowRays;
    if (blocker.state == RAY_OVERFLOW) ++stats.overflowRays;
    return blocker.prim < 0;
}

bool CpuTracer::lightVisible(glm::vec3 p, glm::vec3 n, glm::vec3 lightPos, RenderStats& stats) const {
    if (!lightInFront(p, n, lightPos)) return false;
    glm::vec3 origin, dir;
    float limit;
    shadowRay(p, n, rayOffset_, lightPos, origin, dir, limit);
    return unblocked(origin, dir, limit, stats);
}

bool CpuTracer::emitterVisible(int i, int j, uint32_t sample, uint32_t samples, uint32_t seed, int depth,
                               glm::vec3 p, glm::vec3 n, RenderStats& stats, glm::vec3& q, uint32_t& id) const {
    if (emitters_.empty()) return false;
    const vec2 u = cmjSample(sample, samples, samplePattern(uint32_t(i), uint32_t(j), seed, GPURT_DIM_EMITTER + uint32_t(depth)));
    const size_t k = emitters_.pick(u.x);
    id = emitters_.triangles[k];
    const PreparedTriangle& e = triangles_[id];
    q = emitterPoint(e.v0, e.e1, e.e2, vec2(remapToUnit(u.x, emitters_.lower(k), emitters_.cdf[k]), u.y));
    if (!lightInFront(p, n, q)) return false;
    glm::vec3 origin, dir;
    float limit;
    emitterShadowRay(p, n, rayOffset_, q, origin, dir, limit);
    return unblocked(origin, dir, limit, stats);
}

// Round b of GpuTracer::tracePath is iteration b here, in the same order of operations: the hit's
// emission (weighed against next-event estimation), then below the last depth the point lights
// and one emitter point, each with a shadow ray, then the next direction and Russian roulette.
glm::vec3 CpuTracer::pathSample(int i, int j, uint32_t sample, uint32_t samples, glm::vec3 eye, glm::vec3 d,
                                const RenderSettings& settings, const std::vector<PointLight>& lights,
                                RenderOutput* aovs, size_t pixel, RenderStats& stats) const {
    const int maxDepth = std::max(0, settings.maxBounces);
    glm::vec3 o = eye, color(0.0f), weight(1.0f);
    float prevPdf = 0.0f;  // the camera ray: its emission counts in full
    for (int b = 0;; ++b) {
        const TraceHit hit = trace(o, d, GPURT_FAR);
        stats.addLivePaths(size_t(b), 1);
        ++(b == 0 ? stats.primaryRays : stats.secondaryRays);
        if (hit.state == RAY_OVERFLOW) ++stats.overflowRays;
        if (b == 0 && aovs) aovs->steps[pixel] = static_cast<float>(hit.steps);
        if (hit.prim < 0) {
            color += weight * scene_.background;
            break;
        }
        const PreparedTriangle& tri = triangles_[size_t(hit.prim)];
        const MaterialRecord m = materialRecord(scene_, uint32_t(hit.prim), hit.u, hit.v);
        const glm::vec3 p = o + hit.t * d;
        const glm::vec3 n = facingNormal(tri.e1, tri.e2, d);
        glm::vec3 ns = n;
        if (!scene_.normals.empty()) {
            const TriangleNormals& vn = scene_.normals[size_t(hit.prim)];
            ns = shadingNormal(vn.n0, vn.n1, vn.n2, hit.u, hit.v, n);
        }
        if (b == 0 && aovs) {
            aovs->depth[pixel] = hit.t;
            aovs->prim[pixel] = static_cast<float>(hit.prim);
            aovs->normal[pixel] = n;
        }
        color += weight * (materialEmitted(m, ns) * emissionWeight(prevPdf, hit.t, n, d, emitters_.totalArea));
        if (b == maxDepth) break;

        if (materialLit(m)) {  // next-event estimation (shadowgen.frag, light.frag PATH)
            glm::vec3 local(0.0f);
            for (const PointLight& light : lights)
                if (lightVisible(p, n, light.position, stats))
                    local += pathLightContribution(m, p, ns, d, light.position, light.color, light.intensity);
            vec3 q;
            uint32_t id;
            if (emitterVisible(i, j, sample, samples, settings.seed, b, p, n, stats, q, id)) {
                const PreparedTriangle& e = triangles_[id];
                local += pathLightContribution(m, p, ns, d, q, scene_.materials[scene_.materialIds[id]].emission,
                                               emitterIntensity(p, q, e.e1, e.e2, emitters_.totalArea)) *
                         emitterSampleWeight(m, p, q, e.e1, e.e2, emitters_.totalArea, ns, d);
            }
            color += weight * local;
        }

        // The next direction (pathbounce.frag).
        const uint32_t dim = GPURT_DIM_SCATTER + 2u * uint32_t(b);
        const vec2 u = cmjSample(sample, samples, samplePattern(uint32_t(i), uint32_t(j), settings.seed, dim));
        const vec2 choice = randomPair(sample, samplePattern(uint32_t(i), uint32_t(j), settings.seed, dim + 1u));
        vec3 dir, factor;
        float pdf, side;
        if (!materialSample(m, d, n, ns, frontFace(tri.e1, tri.e2, d), u, choice.x, dir, factor, pdf, side))
            break;
        weight *= factor;
        const float q = survival(b, weight, choice.y);
        if (q == 0.0f) break;
        weight /= q;
        prevPdf = pdf;
        o = offsetOrigin(p, side * n, rayOffset_);
        d = dir;
    }
    return color;
}

RenderOutput CpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) const {
    const auto start = std::chrono::steady_clock::now();
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.rows();  // image rows camera.rowBegin on (pixel (i, j) of the camera is
                                 // element (i, j - rowBegin) of the output)
    const size_t pixels = size_t(camera.width) * size_t(out.height);
    out.color.assign(pixels, glm::vec3(0.0f));
    out.depth.assign(pixels, std::numeric_limits<float>::infinity());
    out.prim.assign(pixels, -1.0f);
    out.normal.assign(pixels, glm::vec3(0.0f));
    out.steps.assign(pixels, 0.0f);

    const bool path = settings.integrator == Integrator::Path;
    const std::vector<PointLight> lights = lightsOrHeadlight(scene_, camera.eye, path);

    // One sample of a pixel: the ray tree of the primary ray d (< 0: the primary hit only, for
    // the AOVs), depth first with a stack of pending rays exactly as the GL rounds take it
    // (bounce.frag), so that the colour sums in the same order; every hit is shaded
    // with a shadow ray per light in front of it and one to the emitters. With readAovs, writes
    // the pixel's AOVs. GpuTracer::traceSample is this as passes.
    const int stackSlots = std::min(std::max(0, settings.maxBounces), GPURT_STACK_SLOTS);
    auto shadeSample = [&](int i, int j, uint32_t sample, uint32_t samples, glm::vec3 d,
                           int maxBounces, bool readAovs, RenderStats& stats) {
        const size_t pixel = size_t(j - camera.rowBegin) * size_t(camera.width) + size_t(i);
        glm::vec3 o = camera.eye;
        glm::vec3 color(0.0f);
        glm::vec3 weight(1.0f);
        struct Pending {
            glm::vec3 o, d, weight;
            int depth;
        };
        Pending stack[GPURT_STACK_SLOTS];
        int height = 0, depth = 0, rays = 1;
        for (int bounce = 0;; ++bounce) {  // the ray's place in the tree's order: its GL round
            const TraceHit hit = trace(o, d, GPURT_FAR);
            if (bounce == 0) {
                ++stats.primaryRays;
                if (readAovs) out.steps[pixel] = static_cast<float>(hit.steps);
            } else {
                ++stats.secondaryRays;
            }
            if (hit.state == RAY_OVERFLOW) ++stats.overflowRays;
            int children = 0;
            if (hit.prim < 0) {
                color += weight * scene_.background;
            } else {
            const PreparedTriangle& tri = triangles_[size_t(hit.prim)];
            const MaterialRecord material = materialRecord(scene_, uint32_t(hit.prim), hit.u, hit.v);
            const glm::vec3 p = o + hit.t * d;
            const glm::vec3 n = facingNormal(tri.e1, tri.e2, d);
            glm::vec3 ns = n;  // the shading normal (surface.frag)
            if (!scene_.normals.empty()) {
                const TriangleNormals& vn = scene_.normals[size_t(hit.prim)];
                ns = shadingNormal(vn.n0, vn.n1, vn.n2, hit.u, hit.v, n);
            }
            color += weight * materialEmitted(material, ns);
            if (bounce == 0 && readAovs) {
                out.depth[pixel] = hit.t;
                out.prim[pixel] = static_cast<float>(hit.prim);
                out.normal[pixel] = n;
            }
            if (maxBounces < 0) break;

            glm::vec3 local = materialAmbient(material);
            for (const PointLight& light : lights)
                if (lightVisible(p, n, light.position, stats))
                    local += materialLight(material, p, ns, d, light.position, light.color, light.intensity);
            vec3 q;  // the sample's point of the emitters (shadowgen.frag EMITTER, light.frag EMITTER)
            uint32_t id;
            if (emitterVisible(i, j, sample, samples, settings.seed, bounce, p, n, stats, q, id)) {
                const PreparedTriangle& e = triangles_[id];
                local += materialLight(material, p, ns, d, q, scene_.materials[scene_.materialIds[id]].emission,
                                       emitterIntensity(p, q, e.e1, e.e2, emitters_.totalArea));
            }
            color += weight * local;

            if (depth < maxBounces && rays < GPURT_TREE_RAYS) {
                vec3 dirA, weightA, dirB, weightB;
                float sideA;
                children = materialChildren(material, d, n, ns, frontFace(tri.e1, tri.e2, d), weight, dirA,
                                            weightA, sideA, dirB, weightB);
                if (children > 0) {
                    const vec3 next = offsetOrigin(p, sideA * n, rayOffset_);
                    depth += 1;
                    rays += 1;
                    if (children == 2 && rays < GPURT_TREE_RAYS && height < stackSlots) {
                        stack[height++] = {offsetOrigin(p, n, rayOffset_), dirB, weightB, depth};
                        rays += 1;
                    }
                    o = next;
                    d = dirA;
                    weight = weightA;
                }
            }
            }
            if (children == 0) {  // the pending ray on top of the stack, or the tree is done
                if (height == 0) break;
                const Pending& top = stack[--height];
                o = top.o;
                d = top.d;
                weight = top.weight;
                depth = top.depth;
            }
        }
        return color;
    };

    // One pixel: the pixel-centre ray for the AOVs when there are several samples, then the
    // samples, summed in order and divided by their number (as the GL accumulate pass sums).
    const uint32_t samples = std::max(1u, settings.samples);
    auto shadePixel = [&](int i, int j, RenderStats& stats) {
        if (samples > 1) shadeSample(i, j, 0, 1, primaryDirection(camera, i, j), -1, true, stats);
        glm::vec3 sum(0.0f);
        const size_t pixel = size_t(j - camera.rowBegin) * size_t(camera.width) + size_t(i);
        for (uint32_t s = 0; s < samples && path; ++s)
            sum += pathSample(i, j, s, samples, camera.eye, sampleDirection(camera, i, j, s, samples, settings.seed),
                              settings, lights, samples == 1 ? &out : nullptr, pixel, stats);
        for (uint32_t s = 0; s < samples && !path; ++s)
            sum += shadeSample(i, j, s, samples, sampleDirection(camera, i, j, s, samples, settings.seed),
                               std::max(0, settings.maxBounces), samples == 1, stats);
        out.color[pixel] = sum / float(samples);
    };

    // Rows are handed out one at a time: cost varies strongly across the image.
    const int threads = std::min(resolveThreads(settings.threads), std::max(1, out.height));
    std::vector<RenderStats> threadStats(static_cast<size_t>(threads));
    parallelChunks(size_t(out.height), 1, threads, [&](size_t row, size_t, size_t worker) {
        for (int i = 0; i < camera.width; ++i) shadePixel(i, camera.rowBegin + int(row), threadStats[worker]);
    });
    for (const RenderStats& s : threadStats) {
        out.stats.primaryRays += s.primaryRays;
        out.stats.shadowRays += s.shadowRays;
        out.stats.secondaryRays += s.secondaryRays;
        out.stats.overflowRays += s.overflowRays;
        for (size_t b = 0; b < s.livePaths.size(); ++b) out.stats.addLivePaths(b, s.livePaths[b]);
    }
    out.stats.samples = uint64_t(pixels) * samples;
    out.stats.totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace gpurt
