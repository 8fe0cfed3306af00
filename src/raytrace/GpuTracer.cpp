#include "raytrace/GpuTracer.h"

#include "stream/GPUKernel.h"
#include "stream/KernelChain.h"
#include "stream/StreamErrors.h"

#include <chrono>

namespace gpurt {

// The streams (one element per pixel, row 0 = top) and the kernels that connect them.
struct GpuTracer::Pipeline {
    int width, height;
    // Ray streams, rewritten for every trace (primary, shadow, mirror).
    GPUFloatArray rayOrigin, rayDir, dda, voxel, hit;
    // Per-bounce surface records and the per-pixel accumulators of eq. 5.1.
    GPUFloatArray surfacePoint, surfaceNormal, surfaceView, localColor, color, weight;
    GPUMask activeMask, waitMask;
    GPUKernel raygen, precalc, traverse, intersect, surface, shadowgen, light, bounce;

    Pipeline(int w, int h, const SceneTextures& textures, const GpuTracerOptions& options, MaskMode mask)
        : width(w),
          height(h),
          rayOrigin(w, h, 4, "rayOrigin"),
          rayDir(w, h, 4, "rayDir"),
          dda(w, h, 4, "dda"),
          voxel(w, h, GPUFormat::RGBA32I, "voxel"),
          hit(w, h, 4, "hit"),
          surfacePoint(w, h, 4, "surfacePoint"),
          surfaceNormal(w, h, 4, "surfaceNormal"),
          surfaceView(w, h, 4, "surfaceView"),
          localColor(w, h, 4, "localColor"),
          color(w, h, 4, "color"),
          weight(w, h, 4, "weight"),
          activeMask("active", mask, dda, 3, float(RAY_ACTIVE_VALUE), float(RAY_ACTIVE_VALUE)),
          waitMask("wait", mask, dda, 3, float(RAY_WAIT_VALUE), float(RAY_WAIT_VALUE)),
          raygen("raygen", "trace/raygen.frag"),
          precalc("precalc", "trace/precalc.frag"),
          traverse("traverse", "trace/traverse.frag",
                   {"TRAVERSE_STEPS " + std::to_string(std::max(1, options.traverseSteps))}),
          intersect("intersect", "trace/intersect.frag"),
          surface("surface", "trace/surface.frag"),
          shadowgen("shadowgen", "trace/shadowgen.frag"),
          light("light", "trace/light.frag"),
          bounce("bounce", "trace/bounce.frag") {
        for (GPUKernel* k : {&raygen, &precalc, &traverse, &intersect, &surface, &shadowgen, &light, &bounce})
            textures.bind(*k);
        raygen.addOutput(rayOrigin).addOutput(rayDir);
        precalc.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
        precalc.addOutput(dda).addOutput(voxel).addOutput(hit);
        traverse.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
        traverse.addInOut(dda, "ddaState").addInOut(voxel, "voxel").setMask(&activeMask);
        intersect.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
        intersect.addInOut(dda, "ddaState").addInOut(voxel, "voxel").addInOut(hit, "hitState");
        intersect.setMask(&waitMask);
        surface.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir").addInput(hit, "hitState");
        surface.addInput(weight, "weight").addInOut(color, "colorState");
        surface.addOutput(surfacePoint).addOutput(surfaceNormal).addOutput(surfaceView).addOutput(localColor);
        shadowgen.addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
        shadowgen.addOutput(rayOrigin).addOutput(rayDir);
        light.addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
        light.addInput(surfaceView, "surfaceView").addInput(hit, "hitState").addInOut(localColor, "localState");
        bounce.addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
        bounce.addInput(surfaceView, "surfaceView").addInput(localColor, "localColor");
        bounce.addInOut(color, "colorState").addInOut(weight, "weightState");
        bounce.addOutput(rayOrigin).addOutput(rayDir);
    }

    // The ray states as mask values (glsl/common/raymath.h).
    static constexpr int RAY_ACTIVE_VALUE = 1;
    static constexpr int RAY_WAIT_VALUE = 2;
};

GpuTracer::GpuTracer(const Scene& scene, const UniformGrid& grid, GpuTracerOptions options)
    : scene_(scene), grid_(grid), options_(options), textures_(scene, grid) {}

GpuTracer::~GpuTracer() = default;

GpuTracer::Pipeline& GpuTracer::pipeline(int width, int height) {
    if (!pipeline_ || pipeline_->width != width || pipeline_->height != height) {
        pipeline_.reset();
        const MaskMode mask = options_.mask == MaskMode::None ? defaultMaskMode() : options_.mask;
        pipeline_ = std::make_unique<Pipeline>(width, height, textures_, options_, mask);
    }
    return *pipeline_;
}

// Voxel precalculation, then traverse and intersect until no ray is ACTIVE or WAITing (both
// counts zero). Every iteration moves each live ray at least one cell, so the loop is bounded by
// the cells a ray can cross; reaching the bound throws (never a hang). Returns the rays traced.
uint64_t GpuTracer::traceLoop(Pipeline& p) {
    const uint64_t rays = p.precalc.execute();
    const glm::ivec3 r = grid_.resolution;
    const int limit = r.x + r.y + r.z + 8;
    whileLoop("trace", limit, [&] {
        const uint64_t active = p.traverse.execute();
        const uint64_t waiting = p.intersect.execute();
        return active + waiting;
    });
    return rays;
}

namespace {
void setCamera(GPUKernel& raygen, const CameraBasis& c) {
    raygen.setUniform("eye", c.eye)
        .setUniform("forward", c.forward)
        .setUniform("right", c.right)
        .setUniform("upOrtho", c.upOrtho)
        .setUniform("tanHalf", c.tanHalf)
        .setUniform("aspect", c.aspect)
        .setUniform("imageSize", glm::vec2(float(c.width), float(c.height)));
}

template <typename T>
std::vector<T> toVectors(const std::vector<float>& flat, int stride) {
    std::vector<T> out(flat.size() / size_t(stride));
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < T::length(); ++c) out[i][c] = flat[i * size_t(stride) + size_t(c)];
    return out;
}
}  // namespace

uint64_t GpuTracer::tracePrimary(const CameraBasis& camera) {
    Pipeline& p = pipeline(camera.width, camera.height);
    setCamera(p.raygen, camera);
    p.raygen.dispatch();
    return traceLoop(p);
}

uint64_t GpuTracer::traceShadows(glm::vec3 lightPosition) {
    if (!pipeline_) throw UsageError("traceShadows needs a tracePrimary first");
    Pipeline& p = *pipeline_;
    p.weight.fill(1.0f);
    p.color.fill(0.0f);
    p.surface.setUniform("background", scene_.background).dispatch();
    p.shadowgen.setUniform("lightPosition", lightPosition).dispatch();
    return traceLoop(p);
}

std::vector<glm::vec4> GpuTracer::primaryHits() {
    if (!pipeline_) return {};
    return toVectors<glm::vec4>(pipeline_->hit.download(), 4);
}

RenderOutput GpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    Pipeline& p = pipeline(camera.width, camera.height);
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.height;
    const size_t pixels = size_t(camera.width) * size_t(camera.height);

    const std::vector<PointLight> lights = lightsOrHeadlight(scene_, camera.eye);
    const int maxBounces = std::max(0, settings.maxBounces);
    p.color.fill(0.0f);
    p.weight.fill(1.0f);  // every pixel starts a path of weight 1
    p.surface.setUniform("background", scene_.background);

    setCamera(p.raygen, camera);
    p.raygen.dispatch();
    for (int b = 0; b <= maxBounces; ++b) {
        const uint64_t rays = traceLoop(p);
        (b == 0 ? out.stats.primaryRays : out.stats.secondaryRays) += rays;
        if (b == 0) {
            // The primary AOVs, before shadow rays reuse the ray streams.
            const auto hits = p.hit.download();
            const auto cells = p.voxel.downloadInt();
            out.depth.resize(pixels);
            out.prim.resize(pixels);
            out.steps.resize(pixels);
            for (size_t i = 0; i < pixels; ++i) {
                const bool isHit = hits[i * 4 + 3] >= 0.0f;
                out.depth[i] = isHit ? hits[i * 4] : std::numeric_limits<float>::infinity();
                out.prim[i] = isHit ? hits[i * 4 + 3] : -1.0f;
                out.steps[i] = float(cells[i * 4 + 3]);
            }
        }
        p.surface.dispatch();
        if (b == 0) out.normal = toVectors<glm::vec3>(p.surfaceNormal.download(), 4);
        for (const PointLight& l : lights) {
            p.shadowgen.setUniform("lightPosition", l.position).dispatch();
            out.stats.shadowRays += traceLoop(p);
            p.light.setUniform("lightPosition", l.position)
                .setUniform("lightColor", l.color)
                .setUniform("lightIntensity", l.intensity)
                .dispatch();
        }
        p.bounce.setUniform("lastBounce", b == maxBounces ? 1 : 0).dispatch();
        if (b == maxBounces) break;
    }
    for (size_t i = 0; i < pixels; ++i)
        if (out.prim[i] < 0.0f) out.normal[i] = glm::vec3(0.0f);
    out.color = toVectors<glm::vec3>(p.color.download(), 4);
    for (GPUKernel* k : {&p.raygen, &p.precalc, &p.traverse, &p.intersect, &p.surface, &p.shadowgen, &p.light, &p.bounce})
        k->flushStats();
    out.stats.totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace gpurt
