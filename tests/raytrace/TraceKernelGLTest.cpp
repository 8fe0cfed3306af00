// The GL tracer's kernels one by one against the CPU reference (the contract's camera, the
// raymath.h DDA and triangle test, brute force over all triangles), on random inputs.
#include "../common/GLTest.h"

#include "raytrace/accel/bvh/BvhAccelerator.h"
#include "raytrace/accel/grid/GridAccelerator.h"
#include "raytrace/camera/Camera.h"
#include "raytrace/integrators/GpuPipeline.h"
#include "raytrace/scene/PackedScene.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/grid/GridTexels.h"
#include "raytrace/textures/SceneTextures.h"
#include "raytrace/accel/grid/GridGl.h"
#include "raytrace/accel/grid/UniformGrid.h"

#include <cmath>

namespace gpurt::test {
namespace {

using raymath::intersectBox;

class TraceKernels : public GLTest {};

constexpr float kMissedBox = -1.0f;

// CPU version of glsl/accel/grid/grid.glsl gridEntry.
float gridEntry(const UniformGrid& g, glm::vec3 o, glm::vec3 d, float tLimit) {
    const glm::vec2 box = intersectBox(o, d, g.min, g.max);
    const float tEnter = std::max(box.x, 0.0f);
    return tEnter > std::min(box.y, tLimit) ? kMissedBox : tEnter;
}

Scene randomTriangles(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), size(0.02f, 0.4f);
    Scene scene;
    scene.materials.push_back(Material{});
    for (int i = 0; i < n; ++i) {
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        const float s = size(rng);
        scene.triangles.push_back({c + s * glm::vec3(pos(rng), pos(rng), pos(rng)),
                                   c + s * glm::vec3(pos(rng), pos(rng), pos(rng)),
                                   c + s * glm::vec3(pos(rng), pos(rng), pos(rng))});
        scene.materialIds.push_back(0);
    }
    return scene;
}

std::vector<glm::vec4> asVec4(const std::vector<float>& flat) {
    std::vector<glm::vec4> v(flat.size() / 4);
    for (size_t i = 0; i < v.size(); ++i) v[i] = glm::vec4(flat[i * 4], flat[i * 4 + 1], flat[i * 4 + 2], flat[i * 4 + 3]);
    return v;
}

// The scene textures, the grid accelerator with the split kernels of one cell a traverser pass
// (its fused trace from the start), and a pipeline over its ray streams: the kernel tests drive
// the passes (p's and the grid's g) one by one.
struct Rig {
    SceneTextures textures;
    GridGl grid;
    GpuPipeline p;
    GridGl::Passes& g;
    Rig(const Scene& scene, const UniformGrid& uniformGrid, int w, int h)
        : textures(scene, uniformGrid.rayOffset()),
          grid(scene, uniformGrid, splitSeed()),
          p(w, h, textures, grid, MaskMode::EarlyExit),
          g(grid.passes()) {}
    static GpuTracerOptions splitSeed() {
        GpuTracerOptions o;
        o.kernel = TraceKernel::Split;
        o.traverseSteps = 1;
        return o;
    }
};

bool closeRel(float a, float b, float rel) { return a == b || std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)); }

TEST_F(TraceKernels, RaygenFollowsTheContractCamera) {
    const Scene scene = randomTriangles(50, 1);
    GridOptions options;
    const UniformGrid grid = buildGrid(scene, options);
    const int w = 37, h = 23;  // non-square, odd
    CameraSpec spec;
    spec.eye = {2.5f, 1.5f, 3.0f};
    spec.target = {0.1f, -0.2f, 0.0f};
    spec.up = {0.1f, 1.0f, 0.2f};
    spec.fovy = 52.0f;
    const CameraBasis camera = makeCamera(spec, w, h);
    Rig rig(scene, grid, w, h);
    GpuPipeline& p = rig.p;
    p.setCamera(camera);
    EXPECT_EQ(p.raygen.execute(), uint64_t(w * h));
    const auto dirs = asVec4(p.rayDir.download());
    const auto origins = asVec4(p.rayOrigin.download());

    // Independent double-precision evaluation of the contract's formula.
    const glm::dvec3 eye(spec.eye), target(spec.target), up(spec.up);
    const glm::dvec3 f = glm::normalize(target - eye);
    const glm::dvec3 r = glm::normalize(glm::cross(f, up));
    const glm::dvec3 u = glm::cross(r, f);
    const double t = std::tan(double(spec.fovy) * M_PI / 360.0), aspect = double(w) / h;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const size_t k = size_t(j * w + i);
            const double pu = ((i + 0.5) / w * 2 - 1) * t * aspect, pv = (1 - (j + 0.5) / h * 2) * t;
            const glm::dvec3 expected = glm::normalize(f + pu * r + pv * u);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(dirs[k][c], expected[c], 2e-6) << i << "," << j;
            const glm::vec3 cpu = primaryDirection(camera, i, j);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(dirs[k][c], cpu[c], 4e-7) << i << "," << j;
            ASSERT_EQ(glm::vec3(origins[k]), camera.eye);
            ASSERT_EQ(origins[k].w, 1e30f);       // no limit
            ASSERT_EQ(dirs[k].w, 0.0f) << i << "," << j;  // GPURT_A_RAY: the grid's entry is its own (precalc)
        }
}

// The one-pass primary trace (trace.frag with CAMERA) generates the rays raygen.frag writes and
// gives the hits and cell counts of raygen followed by the fused trace, bit for bit; the camera
// is inside the grid's box for some scenes and outside for others.
TEST_F(TraceKernels, CameraTraceEqualsRaygenThenTrace) {
    const Scene scene = randomTriangles(400, 3);
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const int w = 41, h = 29;
    Rig rig(scene, grid, w, h);
    GpuPipeline& p = rig.p;
    GridGl::Passes& g = rig.g;
    for (const glm::vec3 eye : {glm::vec3(2.5f, 1.5f, 3.0f), glm::vec3(0.1f, 0.2f, -0.3f)}) {
        CameraSpec spec;
        spec.eye = eye;
        spec.target = {0.1f, -0.2f, 0.05f};
        spec.fovy = 60.0f;
        p.setCamera(makeCamera(spec, w, h));
        p.raygen.execute();
        EXPECT_EQ(g.trace.execute(), uint64_t(w * h));
        const auto hits = p.hit.download();
        const auto cells = g.voxel.downloadInt();
        p.hit.fill(-7.0f);
        g.voxel.fill(-7.0f);
        EXPECT_EQ(g.traceCamera.execute(), uint64_t(w * h));
        EXPECT_EQ(p.hit.download(), hits);
        EXPECT_EQ(g.voxel.downloadInt(), cells);
        size_t hitCount = 0;
        for (size_t i = 0; i < size_t(w * h); ++i) hitCount += hits[i * 4 + 3] >= 0.0f;
        EXPECT_GT(hitCount, size_t(w * h / 10));  // the scene is in view
    }
}

// Rays for the traversal tests: random ones from outside and inside the grid, axis-parallel
// ones, ones starting exactly on cell boundaries, and a pinhole camera inside the grid.
std::vector<std::pair<glm::vec3, glm::vec3>> testRays(const UniformGrid& g, int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), in(0.0f, 1.0f);
    std::vector<std::pair<glm::vec3, glm::vec3>> rays;
    const glm::vec3 extent = g.max - g.min;
    auto normalized = [](glm::vec3 v) { return raymath::contractNormalize(v); };
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    while (int(rays.size()) < count) {
        const int kind = int(rays.size()) % 4;
        glm::vec3 o, d;
        if (kind == 0) {  // from outside, aimed at a point inside
            o = g.min + extent * glm::vec3(in(rng), in(rng), in(rng)) + 2.0f * extent * glm::vec3(unit(rng), unit(rng), unit(rng));
            d = normalized(g.min + extent * glm::vec3(in(rng), in(rng), in(rng)) - o);
        } else if (kind == 1) {  // inside, any direction
            o = g.min + extent * glm::vec3(in(rng), in(rng), in(rng));
            d = normalized(glm::vec3(unit(rng), unit(rng), unit(rng)));
        } else if (kind == 2) {  // axis-parallel, from inside or outside
            o = g.min + extent * glm::vec3(in(rng), in(rng), in(rng)) * 1.4f - 0.2f * extent;
            d = axes[rng() % 6];
        } else {  // starting on a cell boundary (a grid vertex or face), oblique or axis-parallel
            const glm::ivec3 c(int(rng() % unsigned(g.resolution.x + 1)), int(rng() % unsigned(g.resolution.y + 1)),
                               int(rng() % unsigned(g.resolution.z + 1)));
            o = g.min + glm::vec3(c) * g.cellSize;
            d = (rng() % 2) ? axes[rng() % 6] : normalized(glm::vec3(unit(rng), unit(rng), unit(rng)));
        }
        rays.emplace_back(o, d);
    }
    return rays;
}

TEST_F(TraceKernels, TraversalVisitsTheSameCellSequenceAsTheCpuDda) {
    // An empty grid: every traverser pass (one cell per pass) moves each live ray one cell on.
    Scene scene;
    scene.materials.push_back(Material{});
    UniformGrid grid;
    grid.resolution = {9, 7, 5};
    grid.min = {-1.0f, -2.0f, -1.5f};
    grid.max = {2.0f, 1.0f, 1.0f};
    grid.cellSize = (grid.max - grid.min) / glm::vec3(grid.resolution);
    grid.cellStart.assign(grid.cells() + 1, 0u);
    grid.skip.assign(grid.cells(), 1);  // no empty-space skipping: every cell along the ray
    const int w = 32, h = 32;
    const auto rays = testRays(grid, w * h, 2);
    std::vector<float> origins, dirs;
    for (const auto& [o, d] : rays) {
        origins.insert(origins.end(), {o.x, o.y, o.z, 1e30f});
        dirs.insert(dirs.end(), {d.x, d.y, d.z, gridEntry(grid, o, d, 1e30f)});
    }
    Rig rig(scene, grid, w, h);
    GpuPipeline& p = rig.p;
    GridGl::Passes& g = rig.g;
    p.rayOrigin.upload(origins);
    p.rayDir.upload(dirs);
    EXPECT_EQ(g.precalc.execute(), uint64_t(w * h));

    // CPU: the cells each ray visits, from raymath's ddaSetup / ddaStep.
    std::vector<std::vector<glm::ivec3>> expected(rays.size());
    size_t entering = 0;
    for (size_t k = 0; k < rays.size(); ++k) {
        const float tEnter = dirs[k * 4 + 3];
        if (tEnter == kMissedBox) continue;
        ++entering;
        glm::ivec3 cell;
        glm::vec3 tMax;
        raymath::ddaSetup(rays[k].first, rays[k].second, tEnter, grid.min, grid.cellSize, grid.resolution, cell, tMax);
        do expected[k].push_back(cell);
        while (raymath::ddaStep(rays[k].first, rays[k].second, grid.min, grid.cellSize, grid.resolution, cell, tMax));
    }
    ASSERT_GT(entering, rays.size() / 2);

    size_t mismatches = 0, longest = 0;
    for (const auto& cells : expected) longest = std::max(longest, cells.size());
    std::vector<bool> bad(rays.size(), false);
    for (int pass = 0;; ++pass) {
        const auto cells = g.voxel.downloadInt();
        const auto dda = asVec4(g.dda.download());
        for (size_t k = 0; k < rays.size(); ++k) {
            const int state = int(dda[k].w);
            if (expected[k].empty()) {
                if (state != RAY_INACTIVE && !bad[k]) bad[k] = true, ++mismatches;
                continue;
            }
            if (state == RAY_ACTIVE) {
                const glm::ivec3 cell(cells[k * 4], cells[k * 4 + 1], cells[k * 4 + 2]);
                if ((size_t(pass) >= expected[k].size() || cell != expected[k][size_t(pass)]) && !bad[k])
                    bad[k] = true, ++mismatches;
            } else if (state == RAY_DEAD && size_t(pass) < expected[k].size() && !bad[k]) {
                bad[k] = true, ++mismatches;  // left the grid early (late shows as a wrong cell)
            }
        }
        if (g.traverse.execute() == 0) {
            EXPECT_EQ(size_t(pass), longest);  // the longest walk's last pass made it DEAD
            break;
        }
        ASSERT_LT(pass, 64) << "traversal did not end";
    }
    EXPECT_EQ(mismatches, 0u) << "of " << entering << " rays entering the grid";
}

TEST_F(TraceKernels, IntersectorFindsTheClosestWatertightHit) {
    // One cell holding every triangle: one intersector pass tests them all.
    const Scene scene = randomTriangles(300, 3);
    GridOptions options;
    options.resolution = glm::ivec3(1);
    const UniformGrid grid = buildGrid(scene, options);
    const int w = 40, h = 30;
    const auto rays = testRays(grid, w * h, 4);
    std::vector<float> origins, dirs;
    for (const auto& [o, d] : rays) {
        origins.insert(origins.end(), {o.x, o.y, o.z, 1e30f});
        dirs.insert(dirs.end(), {d.x, d.y, d.z, gridEntry(grid, o, d, 1e30f)});
    }
    Rig rig(scene, grid, w, h);
    GpuPipeline& p = rig.p;
    p.rayOrigin.upload(origins);
    p.rayDir.upload(dirs);
    rig.g.precalc.execute();
    rig.g.traverse.execute();  // every entering ray waits in the single cell
    rig.g.intersect.execute();
    const auto hits = asVec4(p.hit.download());

    size_t hitsExpected = 0, agree = 0;
    for (size_t k = 0; k < rays.size(); ++k) {
        // Brute force over all triangles with the same acceptance rule (t > 0, closest, lowest id).
        float best = 1e30f;
        int bestId = -1;
        const bool enters = dirs[k * 4 + 3] != kMissedBox;
        const raymath::WatertightRay ray = raymath::watertightRay(rays[k].first, rays[k].second);
        for (size_t t = 0; enters && t < scene.triangles.size(); ++t) {
            const Triangle& tri = scene.triangles[t];
            float tt, u, v;
            if (raymath::intersectTriangle(ray, tri.v0, tri.v1, tri.v2, tt, u, v) &&
                tt > 0.0f && tt < best) {
                best = tt;
                bestId = int(t);
            }
        }
        hitsExpected += bestId >= 0;
        const bool same = int(hits[k].w) == bestId && (bestId < 0 || closeRel(hits[k].x, best, 1e-5f));
        agree += same;
    }
    EXPECT_GT(hitsExpected, rays.size() / 8);
    EXPECT_GE(double(agree), 0.999 * double(rays.size())) << agree << " of " << rays.size();
}

// The textures SceneTextures and the grid accelerator upload are the CPU layout that `gpurt pack --dump` writes, texel for
// texel, also for a scene read back from a packed file (whose grid is not rebuilt).
TEST_F(TraceKernels, UploadedTexturesAreTheCpuLayout) {
    LoadedScene source;
    source.scene = randomTriangles(1500, 9);
    Material m;
    m.diffuse = {0.1f, 0.2f, 0.3f};
    m.specular = {0.4f, 0.5f, 0.6f};
    m.shininess = 7.0f;
    m.reflectivity = {0.25f, 0.5f, 0.75f};
    m.name = "m";
    source.scene.materials.push_back(m);
    source.scene.materials.back().emission = {1.0f, 2.0f, 3.0f};  // every other triangle emits
    for (size_t t = 0; t < source.scene.materialIds.size(); t += 2) source.scene.materialIds[t] = 1;
    for (size_t t = 0; t < source.scene.triangles.size(); ++t)  // vertex normals, in the packed file too
        source.scene.normals.push_back({glm::vec3(float(t), 1, 0), glm::vec3(0, float(t), 1), glm::vec3(1, 0, float(t))});
    for (size_t t = 0; t < source.scene.triangles.size(); ++t)  // vertex colours
        source.scene.colors.push_back({glm::vec3(float(t % 7) / 7.0f, 1, 0), glm::vec3(0, 0.5f, 1), glm::vec3(1, 0, 0.25f)});
    for (size_t t = 0; t < source.scene.triangles.size(); ++t)  // texture coordinates and two textures
        source.scene.texcoords.push_back({glm::vec2(float(t), 0.5f), glm::vec2(-1.0f, float(t)), glm::vec2(0.25f, 2.0f)});
    for (int k = 0; k < 2; ++k) {
        Texture texture;
        texture.name = "t" + std::to_string(k);
        texture.image.width = 3 + k;
        texture.image.height = 5000 + k;  // more than a row of the texel table
        for (uint32_t i = 0; i < uint32_t(texture.image.width * texture.image.height); ++i)
            texture.image.texels.push_back(i * 2654435761u + uint32_t(k));
        texture.wrapS = uint32_t(k);
        texture.wrapT = kWrapMirror;
        source.scene.textures.push_back(texture);
    }
    source.scene.materials.back().diffuseTexture = 1;
    const UniformGrid grid = buildGrid(source.scene, {});
    const LoadedScene packed =
        decodePackedScene(encodePackedScene(source, *makeStructure(grid), "random"), "random.gpscene");
    const SceneTextures textures(packed.scene, gridOf(packed.accel)->rayOffset());
    const GridGl accel(packed.scene, *gridOf(packed.accel), {});
    const std::vector<TextureTexels> cpu = sceneTextureTexels(source.scene, grid);
    const GPUFloatArray* gpu[] = {&accel.voxelIndex(), &accel.cellTriangles(), &textures.triangles(),
                                  &textures.materials(), &textures.vertexNormals(), &textures.emitters(),
                                  &textures.texcoords(), &textures.textureTexels(), &textures.textureTable(),
                                  &textures.srgbTable(), &textures.vertexColors()};
    ASSERT_EQ(cpu.size(), std::size(gpu));
    size_t bytes = 0;
    for (size_t k = 0; k < cpu.size(); ++k) {
        EXPECT_EQ(gpu[k]->name(), cpu[k].name);
        EXPECT_EQ(gpu[k]->width(), cpu[k].width) << cpu[k].name;
        EXPECT_EQ(gpu[k]->height(), cpu[k].rows) << cpu[k].name;
        EXPECT_EQ(gpu[k]->channels(), cpu[k].channels) << cpu[k].name;
        if (cpu[k].isFloat)
            EXPECT_EQ(gpu[k]->download(), std::vector<float>(cpu[k].floats.begin(), cpu[k].floats.end())) << cpu[k].name;
        else
            EXPECT_EQ(gpu[k]->downloadUint(), std::vector<uint32_t>(cpu[k].uints.begin(), cpu[k].uints.end())) << cpu[k].name;
        bytes += cpu[k].bytes();
    }
    EXPECT_EQ(textures.bytes() + accel.bytes(), bytes);
}

}  // namespace
}  // namespace gpurt::test
