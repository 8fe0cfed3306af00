// The gl backend's streams every integrator shares, for one image size: the rays and the hits
// the accelerator traces them into, each round's surface records, the colour and weight of each
// element's ray, the sample sums, and the camera rays' passes. Stream element (x, y) is pixel
// column x, row y from the top (of the tile). The integrators (integrators/whitted, path) add
// their own streams and passes; kernel tests drive the passes one by one.
#pragma once

#include "raytrace/camera/Camera.h"
#include "raytrace/common/RenderTypes.h"
#include "raytrace/textures/SceneTextures.h"
#include "raytrace/accel/GlAccelerator.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"
#include "stream/GPUMask.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace gpurt {

// The full-size streams only some renders use (llvmpipe zeroes every texture it allocates, about
// 8 ms per 16 MB stream at 1024x1024): the others are 1x1 and their kernels are not set up.
struct StreamNeeds {
    bool emitters = true;   // lightSample: the emitters' sample points
    bool environment = false;  // lightSample: the environment's sample directions (path)
    bool pathState = true;  // pathState: rays that spawn (Whitted's bounce) or the path integrator
    bool sums = true;       // sampleSum: more than one sample, or the viewer's progressive sums
    // The wavefront rounds' streams: surface records, local colours, light samples (false: the
    // integrators are megakernels, which keep them in registers; the colour, weight and ray
    // streams are then the path megakernel's live paths, full size only with `paths`).
    bool stages = true;
    // The primary AOVs (RenderSettings::aovs, the viewer's display modes): without the stages,
    // the hit stream is full size only for them.
    bool aovs = true;
    // Adaptive sampling (RenderSettings::adaptive): the odd samples' sums, the pixels' activity,
    // its mask over the pixel passes, and the convergence pass.
    bool adaptive = false;
    bool variance = false;  // the samples' squares summed (the variance AOV)
    // The denoiser's features (the path integrator): each sample's albedo and shading normal, and
    // their sums (common/path.h featuresOpenAfter).
    bool features = false;
    bool operator==(const StreamNeeds&) const = default;
};

// An RGBA stream's elements as vectors of its first T::length() channels (vec3: the colour
// streams; vec4: the hits).
template <typename T>
std::vector<T> downloadVectors(const GPUFloatArray& stream) {
    const std::vector<float> flat = stream.download();
    std::vector<T> out(flat.size() / 4);
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < T::length(); ++c) out[i][c] = flat[i * 4 + size_t(c)];
    return out;
}

struct GpuPipeline {
    using Needs = StreamNeeds;
    int width, height;
    Needs needs;
    // Ray streams, rewritten for every trace (primary, shadow, mirror), and the hits the
    // accelerator traces them into (glsl/common/scene_layout.h).
    GPUFloatArray rayOrigin, rayDir, hit;
    GlAccelerator& accel;
    // Per-round surface records (surface.frag writes them, the lighting and bounce passes read
    // them) and each element's ray: its colour so far and weight (throughput, alive).
    GPUFloatArray surfacePoint, surfaceNormal, surfaceView, surfaceShading, localColor, color, weight;
    // The sum of the samples so far of each pixel (--spp; the viewer's running mean).
    GPUFloatArray sampleSum;
    GPUFloatArray lightSample;  // the emitter point (or environment direction) each surface point's shadow ray aims at
    // The integrator's state of each element's ray: Whitted's ray tree (depth, stack height, rays)
    // or the path integrator's (pdf of the ray's direction, pixel).
    GPUFloatArray pathState;
    // The pixel-centre AOVs kept for a viewer's display modes while the samples reuse the ray and
    // surface streams: the primary hits, step counts and facing normals (1 x 1 unless
    // `progressive`: streams nobody uses cost their allocation).
    bool progressive;
    GPUFloatArray aovHit, aovCells, aovNormal;
    // The camera rays (raygen.frag): through the sample's point of each pixel, or its centre.
    GPUKernel raygen, raygenCentre;
    // Adaptive sampling (needs.adaptive; 1 x 1 otherwise): the sum of each pixel's odd-numbered
    // samples (common/adaptive.h), its activity (1: still taking samples, 0: stopped), the mask
    // that keeps stopped pixels out of the passes that start samples and sum them (null without
    // adaptive sampling), and the convergence pass (integrators/converge.frag).
    GPUFloatArray oddSum;
    GPUFloatArray squareSum;  // needs.variance: the sum of each pixel's samples' squares (1 x 1 otherwise)
    // needs.features (1 x 1 otherwise): per pixel the albedo and shading normal of its sample (the
    // path integrators write them as images) and their sums over the samples.
    GPUFloatArray pixelAlbedo, pixelNormal, albedoSum, normalSum;
    GPUPingPongArray activity;
    std::unique_ptr<GPUMask> activeMask;
    // The active pixels packed by the last convergence pass (slot k: element (k % width, k /
    // width) holds the pixel's stream index) and their number; none before the first pass.
    GPUFloatArray activePixels, activeCount;
    std::optional<uint64_t> packedActive;
    GPUKernel converge;

    // The accelerator's passes are attached to the ray streams (not without the stages: the
    // megakernels trace inside). paths: the path integrator's per-ray state (pathState) even
    // where `needed` says no ray spawns.
    GpuPipeline(int w, int h, const SceneTextures& textures, GlAccelerator& accelerator, MaskMode mask,
                bool paths = false, bool progressiveAovs = false, Needs needed = {});

    // The contract camera as the uniforms of the kernels that generate primary rays (raygen's
    // through the pixel centres until setSample), and the image row of the streams' row 0
    // (--tile) as the uniform tileRow of `kernels` (scene/pixel.glsl imagePixel) and of the
    // accelerator's.
    void setCamera(const CameraBasis& c, const std::vector<GPUKernel*>& kernels = {});
    // The sample that raygen's rays go through: sample s of n (n = 1: the pixel centre).
    void setSample(uint32_t s, uint32_t n, uint32_t seed);
    // The pass that generates the primary rays of the current sample: the pixel centres' own
    // variant when there is one sample a pixel.
    GPUKernel& primaryRays() { return sampleCount_ == 1 ? raygenCentre : raygen; }
    // Its own kernels (the accelerator's are accel.kernels()).
    std::vector<GPUKernel*> kernels() { return {&raygen, &raygenCentre}; }

    // Adaptive sampling: every pixel active, the sums cleared.
    void beginAdaptive();
    // The convergence pass under --noise-threshold `threshold`: the pixels that stop leave the
    // mask. Returns the pixels still active (the pass's occlusion count).
    uint64_t convergeRound(float threshold);

    // The primary rays' depth, prim and steps AOVs from the hit and step streams (before the
    // shading passes reuse them; primary rays at the step limit count in stats.overflowRays),
    // and the normal AOV after the surface pass.
    // steps: the step counts' stream where the hits were traced elsewhere than by the
    // accelerator's trace kernels (the megakernels), else accel.steps().
    // countOverflow: the primary rays at the step limit count in out.stats (the megakernels count
    // them themselves).
    void readHitAovs(RenderOutput& out, const GPUFloatArray* steps = nullptr, bool countOverflow = true);
    void readNormalAov(RenderOutput& out, const GPUFloatArray* normals = nullptr);

  private:
    uint32_t sampleCount_ = 1;
};

}  // namespace gpurt
