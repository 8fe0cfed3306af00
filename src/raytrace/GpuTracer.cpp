#include "raytrace/GpuTracer.h"

#include "raytrace/GpuPipeline.h"

#include "stream/GPUKernel.h"
#include "stream/KernelChain.h"
#include "stream/StreamErrors.h"

#include <chrono>

namespace gpurt {

GpuTracer::GpuTracer(const Scene& scene, const UniformGrid& grid, GpuTracerOptions options)
    : scene_(scene), grid_(grid), options_(options), textures_(scene, grid) {}

GpuTracer::~GpuTracer() = default;

GpuPipeline& GpuTracer::pipeline(int width, int height) {
    if (!pipeline_ || pipeline_->width != width || pipeline_->height != height) {
        pipeline_.reset();
        const MaskMode mask = options_.mask == MaskMode::None ? defaultMaskMode() : options_.mask;
        pipeline_ = std::make_unique<GpuPipeline>(width, height, textures_, options_.traverseSteps, mask);
    }
    return *pipeline_;
}

// Voxel precalculation, then traverse and intersect until no ray is ACTIVE or WAITing (both
// counts zero). Every traverser pass moves each active ray at least one cell and every
// intersector pass finishes or advances each waiting ray, so the loop is bounded by the cells a
// ray can cross; reaching the bound throws (never a hang). Load balancing: the wait mask's own
// pass counts the waiting rays, and the intersector is skipped while they are fewer than
// waitThreshold of the live rays. Returns the rays traced.
uint64_t GpuTracer::traceLoop(GpuPipeline& p) {
    const uint64_t rays = p.precalc.execute();
    const glm::ivec3 r = grid_.resolution;
    const int limit = 2 * (r.x + r.y + r.z) + 8;
    const bool balance = options_.waitThreshold > 0.0f;
    p.intersect.setMask(&p.waitMask, !balance);
    whileLoop("trace", limit, [&] {
        const uint64_t active = p.traverse.execute();
        if (balance) {
            const std::optional<uint64_t> waiting = p.waitMask.updateAndCount();
            if (waiting && *waiting == 0) return active;
            if (waiting && active > 0 && double(*waiting) < options_.waitThreshold * double(active + *waiting))
                return active;  // keep traversing: too few rays would share the intersector pass
        }
        return active + p.intersect.execute();
    });
    return rays;
}

namespace {
template <typename T>
std::vector<T> toVectors(const std::vector<float>& flat, int stride) {
    std::vector<T> out(flat.size() / size_t(stride));
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < T::length(); ++c) out[i][c] = flat[i * size_t(stride) + size_t(c)];
    return out;
}
}  // namespace

RenderOutput GpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    GpuPipeline& p = pipeline(camera.width, camera.height);
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.height;
    const size_t pixels = size_t(camera.width) * size_t(camera.height);

    const std::vector<PointLight> lights = lightsOrHeadlight(scene_, camera.eye);
    const int maxBounces = std::max(0, settings.maxBounces);
    p.color.fill(0.0f);
    p.weight.fill(1.0f);  // every pixel starts a path of weight 1
    p.surface.setUniform("background", scene_.background);

    p.setCamera(camera);
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
