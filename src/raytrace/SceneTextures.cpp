#include "raytrace/SceneTextures.h"

#include "stream/StreamErrors.h"

#include <glm/glm.hpp>

#include <algorithm>

namespace gpurt {

namespace {
using namespace glm;
#include "../../glsl/common/scene_layout.h"

// Rows needed to hold `count` items at `perRow` a row (at least one row).
int rowsFor(size_t count, size_t perRow) { return int(std::max<size_t>(1, (count + perRow - 1) / perRow)); }

void checkFits(const char* what, int width, int rows) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (width > maxSize || rows > maxSize)
        throw EnvironmentError(std::string("scene too large for this GL: the ") + what + " texture needs " +
                               std::to_string(width) + "x" + std::to_string(rows) +
                               " texels, GL_MAX_TEXTURE_SIZE is " + std::to_string(maxSize));
}

GPUFloatArray makeVoxelIndex(const UniformGrid& grid) {
    const size_t cells = grid.cells();
    const int rows = rowsFor(cells, GPURT_INDEX_WIDTH);
    checkFits("voxel index", GPURT_INDEX_WIDTH, rows);
    std::vector<uint32_t> texels(size_t(GPURT_INDEX_WIDTH) * size_t(rows) * 2, 0u);
    for (size_t c = 0; c < cells; ++c) {
        // An empty cell carries its skip distance instead of a list start (count 0 tells).
        texels[c * 2] = grid.cellStart[c + 1] != grid.cellStart[c] ? grid.cellStart[c] : uint32_t(grid.skipDistance(c));
        texels[c * 2 + 1] = grid.cellStart[c + 1] - grid.cellStart[c];
    }
    GPUFloatArray index(GPURT_INDEX_WIDTH, rows, GPUFormat::RG32UI, "voxelIndex");
    index.upload(texels);
    return index;
}

// Three RGBA32F texels for triangle t: (v0, w), (e1, 0), (e2, 0), with the same float edges
// as the CPU backend (e = v - v0, rounded once).
void writeTriangle(const Triangle& tri, float w, float* out) {
    const vec3 e1 = tri.v1 - tri.v0;
    const vec3 e2 = tri.v2 - tri.v0;
    const vec4 texel[3] = {vec4(tri.v0, w), vec4(e1, 0.0f), vec4(e2, 0.0f)};
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 4; ++c) out[k * 4 + c] = texel[k][c];
}

// The cells' triangle lists with each triangle's vertices in place of its id (w = the id): the
// intersector reads three texels per test instead of an id and then three.
GPUFloatArray makeCellTriangles(const Scene& scene, const UniformGrid& grid) {
    const size_t refs = grid.cellTriangles.size();
    const int rows = rowsFor(refs, GPURT_REFS_PER_ROW);
    const int width = 3 * GPURT_REFS_PER_ROW;
    checkFits("cell triangle", width, rows);
    std::vector<float> texels(size_t(width) * size_t(rows) * 4, 0.0f);
    for (size_t k = 0; k < refs; ++k) {
        const uint32_t id = grid.cellTriangles[k];
        writeTriangle(scene.triangles[id], float(id), &texels[k * 12]);
    }
    GPUFloatArray list(width, rows, GPUFormat::RGBA32F, "cellTriangles");
    list.upload(texels);
    return list;
}

GPUFloatArray makeTriangles(const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (n >= (size_t(1) << 24))
        throw EnvironmentError("scene has " + std::to_string(n) +
                               " triangles; the GL backend carries triangle ids as float32, exact "
                               "only below 16777216 (2^24)");
    const int rows = rowsFor(n, GPURT_TRIANGLES_PER_ROW);
    const int width = 3 * GPURT_TRIANGLES_PER_ROW;
    checkFits("triangle", width, rows);
    std::vector<float> texels(size_t(width) * size_t(rows) * 4, 0.0f);
    for (size_t t = 0; t < n; ++t)
        writeTriangle(scene.triangles[t], float(scene.materialIds[t]), &texels[t * 12]);
    GPUFloatArray triangles(width, rows, GPUFormat::RGBA32F, "triangles");
    triangles.upload(texels);
    return triangles;
}

GPUFloatArray makeMaterials(const Scene& scene) {
    const size_t n = std::max<size_t>(1, scene.materials.size());
    const int width = int(n) * GPURT_MATERIAL_TEXELS;
    checkFits("material", width, 1);
    std::vector<float> texels(size_t(width) * 4, 0.0f);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        const vec4 texel[GPURT_MATERIAL_TEXELS] = {vec4(mat.diffuse, mat.shininess), vec4(mat.specular, 0.0f),
                                                  vec4(mat.reflectivity, 0.0f)};
        for (int k = 0; k < GPURT_MATERIAL_TEXELS; ++k)
            for (int c = 0; c < 4; ++c) texels[(m * GPURT_MATERIAL_TEXELS + size_t(k)) * 4 + size_t(c)] = texel[k][c];
    }
    GPUFloatArray materials(width, 1, GPUFormat::RGBA32F, "materials");
    materials.upload(texels);
    return materials;
}

}  // namespace

SceneTextures::SceneTextures(const Scene& scene, const UniformGrid& grid)
    : grid_(grid),
      voxelIndex_(makeVoxelIndex(grid)),
      triangles_(makeTriangles(scene)),
      cellTriangles_(makeCellTriangles(scene, grid)),
      materials_(makeMaterials(scene)) {}

void SceneTextures::bind(GPUKernel& kernel) const {
    kernel.addInput(voxelIndex_, "voxelIndex")
        .addInput(cellTriangles_, "cellTriangles")
        .addInput(triangles_, "triangles")
        .addInput(materials_, "materials")
        .setUniform("gridMin", grid_.min)
        .setUniform("gridMax", grid_.max)
        .setUniform("cellSize", grid_.cellSize)
        .setUniform("gridRes", grid_.resolution)
        .setUniform("cellTolerance", grid_.hitTolerance())
        .setUniform("maxCellSteps", grid_.resolution.x + grid_.resolution.y + grid_.resolution.z + 3)
        .setUniform("rayOffset", grid_.rayOffset());
}

size_t SceneTextures::bytes() const {
    auto size = [](const GPUFloatArray& a) { return a.elements() * size_t(a.channels()) * 4; };
    return size(voxelIndex_) + size(cellTriangles_) + size(triangles_) + size(materials_);
}

}  // namespace gpurt
