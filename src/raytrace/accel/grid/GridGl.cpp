#include "raytrace/accel/grid/GridGl.h"
#include "raytrace/accel/GlRegistry.h"
#include "raytrace/accel/grid/GridAccelerator.h"

#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/grid/GridTexels.h"
#include "raytrace/textures/SceneTextures.h"
#include "stream/KernelChain.h"

#include <algorithm>
#include <string>

namespace gpurt {

namespace {
using namespace glm;
#include "../../../../glsl/common/raymath.h"
#include "../../../../glsl/common/scene_layout.h"

// The ray states as mask values (glsl/common/raymath.h).
constexpr float kActive = float(RAY_ACTIVE);
constexpr float kWait = float(RAY_WAIT);

// The trace kernel's variants (trace.frag's defines).
enum TraceFlags : unsigned {
    kFromStart = 1,  // the voxel precalculation in the kernel and the whole traversal in one pass
    kAnyHit = 2,     // shadow rays: the first hit ends the ray
    kCamera = 4,     // the camera's primary rays generated in the kernel (with kFromStart)
};

// steps: cells per pass without kFromStart.
std::vector<std::string> traceDefines(unsigned flags, int steps) {
    std::vector<std::string> defines;
    if (flags & kFromStart) defines.insert(defines.end(), {"FROM_START", "TRACE_STEPS (1 << 30)"});
    else defines.push_back("TRACE_STEPS " + std::to_string(steps));
    if (flags & kAnyHit) defines.push_back("ANY_HIT");
    if (flags & kCamera) defines.push_back("CAMERA");
    return defines;
}

GPUFloatArray makeVoxelIndex(const UniformGrid& grid) {
    checkFitsBuffer("voxel index", GPURT_INDEX_WIDTH, textureRowsFor(grid.cells(), GPURT_INDEX_WIDTH));
    return uploadTexels(voxelIndexTexels(grid), GPUFormat::RG32UI, GPUStorage::Buffer);
}

GPUFloatArray makeCellTriangles(const Scene& scene, const UniformGrid& grid) {
    checkFitsBuffer("cell triangle", 3 * GPURT_REFS_PER_ROW,
                    textureRowsFor(grid.cellTriangles.size(), GPURT_REFS_PER_ROW));
    return uploadTexels(cellTriangleTexels(scene, grid), GPUFormat::RGBA32F, GPUStorage::Buffer);
}
}  // namespace

GridGl::GridGl(const Scene& scene, const UniformGrid& grid, const GpuTracerOptions& options)
    : grid_(grid),
      options_(options),
      voxelIndex_(makeVoxelIndex(grid)),
      cellTriangles_(makeCellTriangles(scene, grid)) {}

GridGl::~GridGl() = default;

void GridGl::bind(GPUKernel& kernel) const {
    kernel.addInput(voxelIndex_, "voxelIndex")
        .addInput(cellTriangles_, "cellTriangles")
        .setUniform("gridMin", grid_.min)
        .setUniform("gridMax", grid_.max)
        .setUniform("cellSize", grid_.cellSize)
        .setUniform("gridRes", grid_.resolution)
        .setUniform("cellTolerance", grid_.hitTolerance())
        .setUniform("maxCellSteps", stepLimit());
}

void GridGl::bindTrace(GPUKernel& kernel) const {
    kernel.addDefine("ACCEL_GRID");
    bind(kernel);
}

bool GridGl::onePass() const { return options_.kernel == TraceKernel::Fused && options_.traverseSteps <= 0; }

int GridGl::stepLimit() const { return options_.maxCellSteps > 0 ? options_.maxCellSteps : grid_.maxCellSteps(); }

GridGl::Passes::Passes(const GridGl& grid, const GlRayStreams& rays, MaskMode mask, bool rayStates, int traverseSteps,
                       int fusedSteps)
    : dda(rayStates ? rays.origin->width() : 1, rayStates ? rays.origin->height() : 1, 4, "dda"),
      voxel(rays.origin->width(), rays.origin->height(), GPUFormat::RGBA32I, "voxel"),
      activeMask("active", mask, dda, 3, kActive, kActive),
      waitMask("wait", mask, dda, 3, kWait, kWait),
      precalc("precalc", "accel/grid/precalc.frag"),
      traverse("traverse", "accel/grid/traverse.frag", {"TRAVERSE_STEPS " + std::to_string(std::max(1, traverseSteps))}),
      intersect("intersect", "accel/grid/intersect.frag"),
      trace("trace", "accel/grid/trace.frag", traceDefines(fusedSteps > 0 ? 0u : unsigned(kFromStart), fusedSteps)),
      traceAny("traceAny", "accel/grid/trace.frag", traceDefines((fusedSteps > 0 ? 0u : unsigned(kFromStart)) | unsigned(kAnyHit), fusedSteps)),
      traceMasked("traceMasked", "accel/grid/trace.frag", traceDefines(kFromStart, 0)),
      traceAnyMasked("traceAnyMasked", "accel/grid/trace.frag", traceDefines(kFromStart | kAnyHit, 0)),
      traceCamera("traceCamera", "accel/grid/trace.frag", traceDefines(kFromStart | kCamera, 0)) {
    for (GPUKernel* k : all()) grid.bind(*k);
    if (rayStates) {
        precalc.addInput(*rays.origin, "rayOrigin").addInput(*rays.dir, "rayDir");
        precalc.addOutput(dda).addOutput(voxel).addOutput(*rays.hit);
        traverse.addInput(*rays.origin, "rayOrigin").addInput(*rays.dir, "rayDir");
        traverse.addInOut(dda, "ddaState").addInOut(voxel, "voxel").setMask(&activeMask);
        intersect.addInput(*rays.origin, "rayOrigin").addInput(*rays.dir, "rayDir");
        intersect.addInOut(dda, "ddaState").addInOut(voxel, "voxel").addInOut(*rays.hit, "hitState");
        intersect.setMask(&waitMask);
    }
    for (GPUKernel* k : {&traceMasked, &traceAnyMasked})
        k->addInput(*rays.origin, "rayOrigin").addInput(*rays.dir, "rayDir").addOutput(voxel).addOutput(*rays.hit);
    for (GPUKernel* k : {&trace, &traceAny}) {
        k->addInput(*rays.origin, "rayOrigin").addInput(*rays.dir, "rayDir");
        if (fusedSteps > 0) {  // rayStates
            k->addInOut(dda, "ddaState").addInOut(voxel, "voxel").addOutput(*rays.hit);
            k->setMask(&activeMask, false);  // the trace loop updates the mask and counts with it
        } else {
            k->addOutput(voxel).addOutput(*rays.hit);  // from the start: no mask, no ray state out
        }
    }
    traceCamera.addOutput(voxel).addOutput(*rays.hit);
}

void GridGl::attach(const GlRayStreams& rays, MaskMode mask) {
    passes_.reset();
    // The split pair's cells a traverser pass; the fused kernel's a pass (0: from the start, in one).
    const int steps = options_.traverseSteps;
    const int fusedSteps = options_.kernel == TraceKernel::Fused ? steps : 0;
    passes_ = std::make_unique<Passes>(*this, rays, mask, !onePass(), steps > 0 ? steps : 16, fusedSteps);
}

// Voxel precalculation, then the trace loop.
//
// Fused with traverseSteps 0: one pass of the kernel that starts from the ray streams and takes
// the whole traversal (no ray can still be ACTIVE after it: the per-ray cell limit ends the
// kernel's loop first). Its count is the number of rays. Fused with N cells a pass: precalc,
// then trace passes until the active mask counts no ray.
//
// Split: traverse and intersect until no ray is ACTIVE or WAITing (both counts zero). Every
// traverser pass moves each active ray at least one cell and every intersector pass finishes or
// advances each waiting ray, so the loop is bounded by the cells a ray can cross; reaching the
// bound throws (never a hang). Load balancing: the wait mask's own pass counts the waiting rays,
// and the intersector is skipped while they are fewer than waitThreshold of the live rays.
// Returns the rays traced.
uint64_t GridGl::traceLoop(bool anyHit) {
    Passes& p = *passes_;
    const int maxCells = stepLimit();
    if (options_.kernel == TraceKernel::Fused) {
        GPUKernel& trace = anyHit ? p.traceAny : p.trace;
        if (onePass()) return trace.execute();  // from the start, whole traversal: one pass
        const int steps = options_.traverseSteps;
        const uint64_t rays = p.precalc.execute();
        whileLoop("trace", maxCells / steps + 2, [&] {
            if (const std::optional<uint64_t> active = p.activeMask.updateAndCount()) {
                if (*active > 0) trace.dispatch();
                return *active;
            }
            return trace.execute();  // no mask pass to count with (early exit)
        });
        return rays;
    }
    const uint64_t rays = p.precalc.execute();
    p.intersect.setUniform("shadowRays", anyHit ? 1 : 0);  // unlit materials cast no shadow
    const int limit = 2 * maxCells + 2;
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

uint64_t GridGl::trace(bool anyHit, GPUMask* mask) {
    if (!mask || !onePass()) return traceLoop(anyHit);
    GPUKernel& k = anyHit ? passes_->traceAnyMasked : passes_->traceMasked;
    return k.setMask(mask, false).execute();
}

std::optional<uint64_t> GridGl::traceCamera() {
    if (!onePass()) return std::nullopt;
    return passes_->traceCamera.execute();  // one pass: the rays are generated in the trace kernel
}

void GridGl::setRect(std::optional<StreamRect> rect) {
    for (GPUKernel* k : {&passes_->trace, &passes_->traceAny, &passes_->traceMasked, &passes_->traceAnyMasked})
        k->setRect(rect);
}

const GPUFloatArray& GridGl::steps() const { return passes_->voxel; }

size_t GridGl::bytes() const {
    auto size = [](const GPUFloatArray& a) { return a.elements() * size_t(a.channels()) * 4; };
    return size(voxelIndex_) + size(cellTriangles_);
}

// voxel (16 bytes) always; dda (16) and the masks' depth-stencil (4) for a stepped loop.
size_t GridGl::bytesPerRay() const { return onePass() ? 16 : 36; }

std::vector<GPUKernel*> GridGl::kernels() {
    if (!passes_) return {};
    return passes_->all();
}

std::unique_ptr<GlAccelerator> makeGridGl(const Scene& scene, const AccelStructure& structure,
                                          const GpuTracerOptions& options) {
    return std::make_unique<GridGl>(scene, *gridOf(&structure), options);
}

}  // namespace gpurt
