// The GL tracer's streams and kernels for one image size (used by GpuTracer; kernel tests drive
// the kernels one by one). Stream element (x, y) is pixel column x, row y from the top.
#pragma once

#include "raytrace/Camera.h"
#include "raytrace/SceneTextures.h"
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
    bool rayStates = true;  // dda: the trace loop in more than one pass (precalc, traverse, ...)
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
    // Ray streams, rewritten for every trace (primary, shadow, mirror).
    GPUFloatArray rayOrigin, rayDir, dda, voxel, hit;
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
    GPUMask activeMask, waitMask;
    // The path integrator's masks: paths alive at the start of a round (its trace, surface and
    // bounce passes) and paths with a hit in it (the shadow rays' passes).
    GPUMask aliveMask, surfaceMask;
    GPUKernel raygen, raygenCentre, precalc, traverse, intersect, surface, shadowgen, light, bounce, lastBounce, accumulate;
    // shadowgen and light for the emitters (area lights): one emitter point per sample.
    GPUKernel emitterShadowgen, emitterLight;
    // The path integrator's variants (PATH) and its bounce (pathbounce.frag).
    GPUKernel pathSurface, pathShadowgen, pathLight, pathEmitterShadowgen, pathBounce, pathPack, pathDeposit,
        pathAccumulate;
    // The one-pass trace kernels for the masked path rounds.
    GPUKernel pathTrace, pathTraceAny;
    // The fused traverser-intersector (trace.frag), closest hit and any hit (shadow rays), and
    // the whole primary trace in one pass, generating its own rays (no ray streams; hits only).
    GPUKernel trace, traceAny, traceCamera;

    // traverseSteps: cells per traverse pass of the split pair; fusedSteps: cells per pass of the
    // fused kernels, 0 for the whole traversal in one pass. stackSlots: rays a pixel's stack can
    // hold (0 where nothing spawns two rays: a scene without glass).
    GpuPipeline(int w, int h, const SceneTextures& textures, int traverseSteps, MaskMode mask,
                int fusedSteps = 0, int slots = 0, bool pathStreams = false, bool progressiveAovs = false,
                Needs needed = {})
        : width(w),
          height(h),
          needs(needed),
          rayOrigin(w, h, 4, "rayOrigin"),
          rayDir(w, h, 4, "rayDir"),
          dda(needs.rayStates ? w : 1, needs.rayStates ? h : 1, 4, "dda"),
          voxel(w, h, GPUFormat::RGBA32I, "voxel"),
          hit(w, h, 4, "hit"),
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
          activeMask("active", mask, dda, 3, float(RAY_ACTIVE_VALUE), float(RAY_ACTIVE_VALUE)),
          waitMask("wait", mask, dda, 3, float(RAY_WAIT_VALUE), float(RAY_WAIT_VALUE)),
          aliveMask("alive", mask, weight, 3, 1.0f, 1.0f),
          surfaceMask("surface", mask, surfacePoint, 3, 0.0f, 1e30f),
          raygen("raygen", "trace/raygen.frag"),
          raygenCentre("raygen", "trace/raygen.frag", {"PIXEL_CENTRE"}),  // a variant: the same pass in --stats
          precalc("precalc", "trace/precalc.frag"),
          traverse("traverse", "trace/traverse.frag",
                   {"TRAVERSE_STEPS " + std::to_string(std::max(1, traverseSteps))}),
          intersect("intersect", "trace/intersect.frag"),
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
          pathAccumulate("pathAccumulate", "trace/accumulate.frag"),
          pathTrace("pathTrace", "trace/trace.frag", traceDefines(0, false)),
          pathTraceAny("pathTraceAny", "trace/trace.frag", traceDefines(0, true)),
          trace("trace", "trace/trace.frag", traceDefines(fusedSteps, false)),
          traceAny("traceAny", "trace/trace.frag", traceDefines(fusedSteps, true)),
          traceCamera("traceCamera", "trace/trace.frag", cameraTraceDefines()) {
        for (GPUKernel* k : allKernels()) textures.bind(*k);
        raygen.addOutput(rayOrigin).addOutput(rayDir);
        raygenCentre.addOutput(rayOrigin).addOutput(rayDir);
        if (needs.rayStates) {
            precalc.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
            precalc.addOutput(dda).addOutput(voxel).addOutput(hit);
            traverse.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
            traverse.addInOut(dda, "ddaState").addInOut(voxel, "voxel").setMask(&activeMask);
            intersect.addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
            intersect.addInOut(dda, "ddaState").addInOut(voxel, "voxel").addInOut(hit, "hitState");
            intersect.setMask(&waitMask);
        }
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
        for (GPUKernel* k : {&pathTrace, &pathTraceAny})
            k->addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir").addOutput(voxel).addOutput(hit);
        pathTrace.setMask(&aliveMask, false);
        pathTraceAny.setMask(&surfaceMask, false);
        for (GPUKernel* k : {&trace, &traceAny}) {
            k->addInput(rayOrigin, "rayOrigin").addInput(rayDir, "rayDir");
            if (fusedSteps > 0) {  // needs.rayStates
                k->addInOut(dda, "ddaState").addInOut(voxel, "voxel").addOutput(hit);
                k->setMask(&activeMask, false);  // the trace loop updates the mask and counts with it
            } else {
                k->addOutput(voxel).addOutput(hit);  // from the start: no mask, no ray state out
            }
        }
        traceCamera.addOutput(voxel).addOutput(hit);
    }

    std::array<GPUKernel*, 26> allKernels() {
        return {&raygen, &raygenCentre, &precalc, &traverse, &intersect, &surface, &shadowgen, &light, &bounce, &lastBounce,
                &accumulate, &emitterShadowgen, &emitterLight, &pathSurface, &pathShadowgen, &pathLight,
                &pathEmitterShadowgen, &pathBounce, &pathPack, &pathDeposit, &pathAccumulate, &pathTrace, &pathTraceAny, &trace, &traceAny,
                &traceCamera};
    }

    // fusedSteps 0: the fused kernels start from the ray streams (FROM_START, no precalc pass) and
    // take the whole traversal in one pass: the per-ray cell limit ends the kernel's loop.
    static std::vector<std::string> traceDefines(int fusedSteps, bool anyHit) {
        std::vector<std::string> defines;
        if (fusedSteps > 0) defines.push_back("TRACE_STEPS " + std::to_string(fusedSteps));
        else defines.insert(defines.end(), {"FROM_START", "TRACE_STEPS (1 << 30)"});
        if (anyHit) defines.push_back("ANY_HIT");
        return defines;
    }

    // The one-pass trace (traceDefines with no step limit) that generates its own primary rays.
    static std::vector<std::string> cameraTraceDefines() {
        std::vector<std::string> defines = traceDefines(0, false);
        defines.push_back("CAMERA");
        return defines;
    }

    // The path rounds' passes over the first `rows` rows only, where the live paths are packed
    // (std::nullopt: all rows again).
    void setPathRows(std::optional<int> rows) {
        const std::optional<StreamRect> rect =
            rows ? std::optional<StreamRect>(StreamRect{0, 0, width, *rows}) : std::nullopt;
        for (GPUKernel* k : {&trace, &traceAny, &pathTrace, &pathTraceAny, &pathSurface, &pathShadowgen, &pathLight,
                             &pathEmitterShadowgen, &pathBounce, &pathPack, &pathDeposit})
            k->setRect(rect);
    }

    // The ray tree's round passes over `rect` only (the box of the elements with rays), or all.
    void setRoundRect(std::optional<StreamRect> rect) {
        for (GPUKernel* k : {&trace, &traceAny, &surface, &shadowgen, &light, &emitterShadowgen, &emitterLight, &bounce,
                             &lastBounce})
            k->setRect(rect);
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
        for (GPUKernel* k : {&raygen, &raygenCentre, &traceCamera})
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

    // The ray states as mask values (glsl/common/raymath.h).
    static constexpr int RAY_ACTIVE_VALUE = 1;
    static constexpr int RAY_WAIT_VALUE = 2;

  private:
    uint32_t sampleCount_ = 1;
};

}  // namespace gpurt
