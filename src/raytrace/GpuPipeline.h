// The GL tracer's streams and kernels for one image size (used by GpuTracer; kernel tests drive
// the kernels one by one). Stream element (x, y) is pixel column x, row y from the top.
#pragma once

#include "raytrace/Camera.h"
#include "raytrace/SceneTextures.h"
#include "raytrace/accel/GlAccelerator.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"
#include "stream/GPUMask.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace gpurt {

// The full-size streams only some renders use (llvmpipe zeroes every texture it allocates, about
// 8 ms per 16 MB stream at 1024x1024): the others are 1x1 and their kernels are not set up.
struct StreamNeeds {
    bool emitters = true;   // lightSample: the emitters' sample points
    bool pathState = true;  // pathState: rays that spawn (Whitted's bounce) or the path integrator
    bool sums = true;       // sampleSum: more than one sample, or the viewer's progressive sums
    bool operator==(const StreamNeeds&) const = default;
};

// The streams (one element per pixel, row 0 = top) and the kernels that connect them.
struct GpuPipeline {
    using Needs = StreamNeeds;
    int width, height;
    Needs needs;
    // Ray streams, rewritten for every trace (primary, shadow, mirror), and the hits the
    // accelerator traces them into (glsl/common/scene_layout.h).
    GPUFloatArray rayOrigin, rayDir, hit;
    GlAccelerator& accel;
    // Per-bounce surface records and the per-pixel accumulators of eq. 5.1.
    GPUFloatArray surfacePoint, surfaceNormal, surfaceView, surfaceShading, localColor, color, weight;
    // The sum of the samples so far of each pixel (--spp; the viewer's running mean).
    GPUFloatArray sampleSum;
    GPUFloatArray lightSample;  // the emitter point each surface point's shadow ray aims at
    // The ray tree (bounce.frag): each pixel's depth, stack height and ray count, and its stack
    // of pending rays, `stackSlots` slots of image size one above the other.
    GPUFloatArray pathState;
    // The pixel-centre AOVs kept for a viewer's display modes while the samples reuse the ray and
    // surface streams: the primary hits, cell counts and facing normals (1 x 1 unless
    // `progressive`: streams nobody uses cost their allocation).
    bool progressive;
    GPUFloatArray aovHit, aovCells, aovNormal;
    int stackSlots;  // 0: the stacks are 1 x 1
    GPUFloatArray stackOrigin, stackDir, stackWeight;
    // The path integrator (1 x 1 unless `paths`): the live paths packed for the next round (ray,
    // throughput, path state, colour so far), their counter, each pixel's colour once its path has
    // ended, and the bounce pass's own output (whether the element's path lives on).
    bool paths;
    GPUFloatArray nextOrigin, nextDir, nextWeight, nextState, nextColor, pathCount, pixelColor, pathLives;
    // The box of the elements that have a ray in the next round of the ray tree (bounce.frag).
    GPUFloatArray rayBounds;
    // The path integrator's masks: paths alive at the start of a round (its trace, surface and
    // bounce passes) and paths with a hit in it (the shadow rays' passes).
    GPUMask aliveMask, surfaceMask;
    GPUKernel raygen, raygenCentre, surface, shadowgen, light, bounce, lastBounce, accumulate;
    // shadowgen and light for the emitters (area lights): one emitter point per sample.
    GPUKernel emitterShadowgen, emitterLight;
    // The path integrator's variants (PATH) and its bounce (pathbounce.frag).
    GPUKernel pathSurface, pathShadowgen, pathLight, pathEmitterShadowgen, pathBounce, pathPack, pathDeposit,
        pathAccumulate;

    // stackSlots: rays a pixel's stack can hold (0 where nothing spawns two rays: a scene without
    // glass). The accelerator's passes are attached to the ray streams.
    GpuPipeline(int w, int h, const SceneTextures& textures, GlAccelerator& accelerator, MaskMode mask,
                int slots = 0, bool pathStreams = false, bool progressiveAovs = false, Needs needed = {})
        : width(w),
          height(h),
          needs(needed),
          rayOrigin(w, h, 4, "rayOrigin"),
          rayDir(w, h, 4, "rayDir"),
          hit(w, h, 4, "hit"),
          accel(accelerator),
          surfacePoint(w, h, 4, "surfacePoint"),
          surfaceNormal(w, h, 4, "surfaceNormal"),
          surfaceView(w, h, 4, "surfaceView"),
          surfaceShading(w, h, 4, "surfaceShading"),
          localColor(w, h, 4, "localColor"),
          color(w, h, 4, "color"),
          weight(w, h, 4, "weight"),
          sampleSum(needs.sums ? w : 1, needs.sums ? h : 1, 4, "sampleSum"),
          lightSample(needs.emitters ? w : 1, needs.emitters ? h : 1, 4, "lightSample"),
          pathState(needs.pathState || pathStreams ? w : 1, needs.pathState || pathStreams ? h : 1, 4, "pathState"),
          progressive(progressiveAovs),
          aovHit(progressive ? w : 1, progressive ? h : 1, 4, "aovHit"),
          aovCells(progressive ? w : 1, progressive ? h : 1, GPUFormat::RGBA32I, "aovCells"),
          aovNormal(progressive ? w : 1, progressive ? h : 1, 4, "aovNormal"),
          stackSlots(slots),
          stackOrigin(slots > 0 ? w : 1, slots > 0 ? h * slots : 1, 4, "stackOrigin"),
          stackDir(slots > 0 ? w : 1, slots > 0 ? h * slots : 1, 4, "stackDir"),
          stackWeight(slots > 0 ? w : 1, slots > 0 ? h * slots : 1, 4, "stackWeight"),
          paths(pathStreams),
          nextOrigin(paths ? w : 1, paths ? h : 1, 4, "nextOrigin"),
          nextDir(paths ? w : 1, paths ? h : 1, 4, "nextDir"),
          nextWeight(paths ? w : 1, paths ? h : 1, 4, "nextWeight"),
          nextState(paths ? w : 1, paths ? h : 1, 4, "nextState"),
          nextColor(paths ? w : 1, paths ? h : 1, 4, "nextColor"),
          pathCount(1, 1, GPUFormat::R32UI, "pathCount"),
          pixelColor(paths ? w : 1, paths ? h : 1, 4, "pixelColor"),
          pathLives(paths ? w : 1, paths ? h : 1, 1, "pathLives"),
          rayBounds(4, 1, GPUFormat::R32UI, "rayBounds"),
          aliveMask("alive", mask, weight, 3, 1.0f, 1.0f),
          surfaceMask("surface", mask, surfacePoint, 3, 0.0f, 1e30f),
          raygen("raygen", "trace/raygen.frag"),
          raygenCentre("raygen", "trace/raygen.frag", {"PIXEL_CENTRE"}),  // a variant: the same pass in --stats
          surface("surface", "trace/surface.frag"),
          shadowgen("shadowgen", "trace/shadowgen.frag"),
          light("light", "trace/light.frag"),
          bounce("bounce", "trace/bounce.frag"),
          lastBounce("lastBounce", "trace/bounce.frag", {"LAST_ROUND"}),
          accumulate("accumulate", "trace/accumulate.frag"),
          emitterShadowgen("emitterShadowgen", "trace/shadowgen.frag", {"EMITTER"}),
          emitterLight("emitterLight", "trace/light.frag", {"EMITTER"}),
          pathSurface("pathSurface", "trace/surface.frag", {"PATH"}),
          pathShadowgen("pathShadowgen", "trace/shadowgen.frag", {"PATH"}),
          pathLight("pathLight", "trace/light.frag", {"PATH"}),
          pathEmitterShadowgen("pathEmitterShadowgen", "trace/shadowgen.frag", {"EMITTER", "PATH"}),
          pathBounce("pathBounce", "trace/pathbounce.frag"),
          pathPack("pathPack", "trace/pathbounce.frag", {"PACK"}),
          pathDeposit("pathDeposit", "trace/pathdeposit.frag"),
          pathAccumulate("pathAccumulate", "trace/accumulate.frag") {
        accel.attach(GlRayStreams{&rayOrigin, &rayDir, &hit}, mask);
        for (GPUKernel* k : ownKernels()) textures.bind(*k);
        raygen.addOutput(rayOrigin).addOutput(rayDir);
        raygenCentre.addOutput(rayOrigin).addOutput(rayDir);
        for (GPUKernel* k : {&surface, &pathSurface}) {
            k->addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir").addInput(hit, "hitState");
            k->addInput(weight, "weight").addInOut(color, "colorState");
            k->addOutput(surfacePoint).addOutput(surfaceNormal).addOutput(surfaceView).addOutput(localColor);
            k->addOutput(surfaceShading);
        }
        pathSurface.addInput(pathState, "pathState");
        for (GPUKernel* k : {&shadowgen, &pathShadowgen}) {
            k->addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
            k->addOutput(rayOrigin).addOutput(rayDir);
        }
        for (GPUKernel* k : {&light, &pathLight}) {
            k->addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
            k->addInput(surfaceView, "surfaceView").addInput(hit, "hitState").addInOut(localColor, "localState");
            k->addInput(surfaceShading, "surfaceShading");
        }
        bounce.addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
        bounce.addInput(surfaceView, "surfaceView").addInput(localColor, "localColor");
        bounce.addInput(surfaceShading, "surfaceShading");
        bounce.addInOut(color, "colorState").addInOut(weight, "weightState");
        bounce.addOutput(rayOrigin).addOutput(rayDir);
        if (needs.pathState) bounce.addInOut(pathState, "pathStateIn");
        bounce.addImage(stackOrigin, "stackOrigin").addImage(stackDir, "stackDir").addImage(stackWeight, "stackWeight");
        bounce.setUniform("stackSlots", slots);
        bounce.addImage(rayBounds, "rayBounds");
        lastBounce.addInput(surfacePoint, "surfacePoint").addInput(weight, "weightState");
        lastBounce.addInput(localColor, "localColor").addInOut(color, "colorState");
        if (needs.sums) accumulate.addInput(color, "colorState").addInOut(sampleSum, "sumState");
        for (GPUKernel* k : {&emitterShadowgen, &pathEmitterShadowgen}) {
            k->addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
            k->addOutput(rayOrigin).addOutput(rayDir);
            if (needs.emitters) k->addOutput(lightSample);
        }
        emitterLight.addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
        emitterLight.addInput(surfaceView, "surfaceView").addInput(hit, "hitState");
        emitterLight.addInput(lightSample, "lightSample").addInOut(localColor, "localState");
        emitterLight.addInput(surfaceShading, "surfaceShading");
        pathEmitterShadowgen.addInput(pathState, "pathState");
        for (GPUKernel* k : {&pathShadowgen, &pathEmitterShadowgen})  // the lobes at the hit's texture coordinates
            k->addInput(surfaceView, "surfaceView").addInput(surfaceShading, "surfaceShading");
        for (GPUKernel* k : {&pathBounce, &pathPack}) {
            k->addInput(surfacePoint, "surfacePoint").addInput(surfaceNormal, "surfaceNormal");
            k->addInput(surfaceView, "surfaceView").addInput(surfaceShading, "surfaceShading");
            k->addInput(localColor, "localColor").addInput(hit, "hitState").addInput(lightSample, "lightSample");
            k->addImage(pixelColor, "pixelColor");
        }
        pathBounce.addInOut(color, "colorState").addInOut(weight, "weightState").addOutput(rayOrigin).addOutput(rayDir);
        if (paths) pathBounce.addInOut(pathState, "pathStateIn");
        pathPack.addInput(color, "colorState").addInput(weight, "weightState").addInput(pathState, "pathStateIn");
        pathPack.addImage(nextOrigin, "nextOrigin").addImage(nextDir, "nextDir").addImage(nextWeight, "nextWeight");
        pathPack.addImage(nextState, "nextState").addImage(nextColor, "nextColor").addImage(pathCount, "pathCount");
        pathPack.addOutput(pathLives);
        pathDeposit.addInput(color, "colorState").addInput(weight, "weightState").addInput(pathState, "pathStateIn");
        pathDeposit.addImage(pixelColor, "pixelColor").addOutput(pathLives);
        if (needs.sums) pathAccumulate.addInput(pixelColor, "colorState").addInOut(sampleSum, "sumState");
    }

    // The integrators' kernels (the accelerator's are accel.kernels()).
    std::array<GPUKernel*, 18> ownKernels() {
        return {&raygen, &raygenCentre, &surface, &shadowgen, &light, &bounce, &lastBounce, &accumulate,
                &emitterShadowgen, &emitterLight, &pathSurface, &pathShadowgen, &pathLight, &pathEmitterShadowgen,
                &pathBounce, &pathPack, &pathDeposit, &pathAccumulate};
    }
    // Every kernel of a render: the integrators' and the accelerator's.
    std::vector<GPUKernel*> allKernels() {
        const std::array<GPUKernel*, 18> own = ownKernels();
        std::vector<GPUKernel*> all(own.begin(), own.end());
        for (GPUKernel* k : accel.kernels()) all.push_back(k);
        return all;
    }

    // The path rounds' passes over the first `rows` rows only, where the live paths are packed
    // (std::nullopt: all rows again).
    void setPathRows(std::optional<int> rows) {
        const std::optional<StreamRect> rect =
            rows ? std::optional<StreamRect>(StreamRect{0, 0, width, *rows}) : std::nullopt;
        for (GPUKernel* k : {&pathSurface, &pathShadowgen, &pathLight, &pathEmitterShadowgen, &pathBounce, &pathPack,
                             &pathDeposit})
            k->setRect(rect);
        accel.setRect(rect);
    }

    // The ray tree's round passes over `rect` only (the box of the elements with rays), or all.
    void setRoundRect(std::optional<StreamRect> rect) {
        for (GPUKernel* k : {&surface, &shadowgen, &light, &emitterShadowgen, &emitterLight, &bounce, &lastBounce})
            k->setRect(rect);
        accel.setRect(rect);
    }

    // The path rounds' shading passes under the masks (GpuTracerOptions::maskPaths), or not.
    void maskPaths(bool on) {
        // The bounce pass ends the paths that missed: it runs for all paths alive in the round.
        pathSurface.setMask(on ? &aliveMask : nullptr, false);
        pathBounce.setMask(on ? &aliveMask : nullptr, false);
        pathPack.setMask(on ? &aliveMask : nullptr, false);
        for (GPUKernel* k : {&pathShadowgen, &pathLight, &pathEmitterShadowgen})
            k->setMask(on ? &surfaceMask : nullptr, false);
    }

    // The contract camera as the uniforms of the kernels that generate primary rays (raygen's
    // through the pixel centres until setSample).
    void setCamera(const CameraBasis& c) {
        setSample(0, 1, 0);
        // The image row of the streams' row 0 (--tile): the kernels that key samples by pixel or
        // aim the camera add it (scene.glsl imagePixel).
        for (GPUKernel* k : allKernels()) k->setUniform("tileRow", c.rowBegin);
        std::vector<GPUKernel*> cameras = accel.kernels();  // the accelerator's camera trace
        cameras.insert(cameras.end(), {&raygen, &raygenCentre});
        for (GPUKernel* k : cameras)
            k->setUniform("eye", c.eye)
                .setUniform("forward", c.forward)
                .setUniform("right", c.right)
                .setUniform("upOrtho", c.upOrtho)
                .setUniform("tanHalf", c.tanHalf)
                .setUniform("aspect", c.aspect)
                .setUniform("imageSize", glm::vec2(float(c.width), float(c.height)));
    }

    // The sample that raygen's rays go through: sample s of n (n = 1: the pixel centre).
    void setSample(uint32_t s, uint32_t n, uint32_t seed) {
        sampleCount_ = n;
        for (GPUKernel* k : {&raygen, &emitterShadowgen, &pathEmitterShadowgen, &pathBounce, &pathPack})
            k->setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
    }

    // The pass that generates the primary rays of the current sample: the pixel centres' own
    // variant when there is one sample a pixel.
    GPUKernel& primaryRays() { return sampleCount_ == 1 ? raygenCentre : raygen; }

  private:
    uint32_t sampleCount_ = 1;
};

}  // namespace gpurt
