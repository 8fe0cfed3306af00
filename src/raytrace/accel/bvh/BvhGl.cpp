#include "raytrace/accel/bvh/BvhGl.h"
#include "raytrace/accel/GlRegistry.h"
#include "raytrace/accel/bvh/BvhAccelerator.h"

#include <string>

#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/bvh/BvhTexels.h"
#include "raytrace/textures/SceneTextures.h"

namespace gpurt {

namespace {
using namespace glm;
#include "../../../../glsl/common/scene_layout.h"

GPUFloatArray makeNodes(const Bvh& bvh) {
    checkFitsBuffer("BVH node", 2 * GPURT_BVH_NODES_PER_ROW, textureRowsFor(bvh.nodes.size(), GPURT_BVH_NODES_PER_ROW));
    return uploadTexels(bvhNodeTexels(bvh), GPUFormat::RGBA32UI, GPUStorage::Buffer);
}

GPUFloatArray makeTriangles(const Scene& scene, const Bvh& bvh) {
    checkFitsBuffer("BVH triangle", 3 * GPURT_REFS_PER_ROW, textureRowsFor(bvh.triangles.size(), GPURT_REFS_PER_ROW));
    return uploadTexels(bvhTriangleTexels(scene, bvh), GPUFormat::RGBA32F, GPUStorage::Buffer);
}
}  // namespace

// The trace kernel's variants over ray streams of one size, and their steps stream.
struct BvhGl::Passes {
    GPUFloatArray steps;
    GPUKernel trace, traceAny, traceMasked, traceAnyMasked, traceCamera;

    Passes(const BvhGl& bvh, const GlRayStreams& rays)
        : steps(rays.origin->width(), rays.origin->height(), GPUFormat::RGBA32I, "bvhSteps"),
          trace("trace", "accel/bvh/trace.frag"),
          traceAny("traceAny", "accel/bvh/trace.frag", {"ANY_HIT"}),
          traceMasked("traceMasked", "accel/bvh/trace.frag"),
          traceAnyMasked("traceAnyMasked", "accel/bvh/trace.frag", {"ANY_HIT"}),
          traceCamera("traceCamera", "accel/bvh/trace.frag", {"CAMERA"}) {
        for (GPUKernel* k : all()) {
            bvh.bind(*k);
            if (k != &traceCamera) k->addInput(*rays.origin, "rayOrigin").addInput(*rays.dir, "rayDir");
            k->addOutput(steps).addOutput(*rays.hit);
        }
    }
    std::vector<GPUKernel*> all() { return {&trace, &traceAny, &traceMasked, &traceAnyMasked, &traceCamera}; }
};

BvhGl::BvhGl(const Scene& scene, const Bvh& bvh, const GpuTracerOptions& options)
    : bvh_(bvh), options_(options), nodes_(makeNodes(bvh)), triangles_(makeTriangles(scene, bvh)) {}

BvhGl::~BvhGl() = default;

void BvhGl::bind(GPUKernel& kernel) const {
    glm::vec3 boxMin, boxStep;
    bvh_.quantisation(boxMin, boxStep);
    kernel.addInput(nodes_, "bvhNodes")
        .setUniform("bvhBoxMin", boxMin)
        .setUniform("bvhBoxStep", boxStep)
        .addInput(triangles_, "bvhTriangles")
        .setUniform("maxNodeSteps", stepLimit());
}

void BvhGl::bindTrace(GPUKernel& kernel) const {
    kernel.addDefine("ACCEL_BVH");
    bind(kernel);
}

void BvhGl::attach(const GlRayStreams& rays, MaskMode) { passes_ = std::make_unique<Passes>(*this, rays); }

uint64_t BvhGl::trace(bool anyHit, GPUMask* mask) {
    if (!mask) return (anyHit ? passes_->traceAny : passes_->trace).execute();
    GPUKernel& k = anyHit ? passes_->traceAnyMasked : passes_->traceMasked;
    return k.setMask(mask, false).execute();
}

std::optional<uint64_t> BvhGl::traceCamera() { return passes_->traceCamera.execute(); }

void BvhGl::setRect(std::optional<StreamRect> rect) {
    for (GPUKernel* k : {&passes_->trace, &passes_->traceAny, &passes_->traceMasked, &passes_->traceAnyMasked})
        k->setRect(rect);
}

const GPUFloatArray& BvhGl::steps() const { return passes_->steps; }

int BvhGl::stepLimit() const { return options_.maxCellSteps > 0 ? options_.maxCellSteps : bvh_.maxNodeSteps(); }

size_t BvhGl::bytes() const {
    auto size = [](const GPUFloatArray& a) { return a.elements() * size_t(a.channels()) * 4; };
    return size(nodes_) + size(triangles_);
}

std::vector<GPUKernel*> BvhGl::kernels() {
    if (!passes_) return {};
    return passes_->all();
}

std::unique_ptr<GlAccelerator> makeBvhGl(const Scene& scene, const AccelStructure& structure,
                                         const GpuTracerOptions& options) {
    return std::make_unique<BvhGl>(scene, *bvhOf(&structure), options);
}

}  // namespace gpurt
