// The scene in textures (Purcell et al. 2002, 3.1; Christen 2005, 5.3): the uniform grid's voxel
// index and element lists, the triangles and the materials, laid out as glsl/common/
// scene_layout.h says. Indices are exact: integer textures for the index and lists, and triangle
// ids (carried as floats in the hit stream) are checked against 2^24.
#pragma once

#include "raytrace/EmitterTable.h"
#include "scene/Scene.h"
#include "raytrace/UniformGrid.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"

namespace gpurt {

class SceneTextures {
  public:
    // Throws EnvironmentError when the scene does not fit the GL limits or the exact-index limits.
    SceneTextures(const Scene& scene, const UniformGrid& grid);

    // Adds the scene textures as inputs of `kernel` (samplers voxelIndex, cellTriangles, triangles,
    // materials, vertexNormals, emitters, triangleTexcoords, textureTexels, textureTable,
    // srgbTable) and sets the grid, emitter and texture uniforms.
    void bind(GPUKernel& kernel) const;

    const GPUFloatArray& voxelIndex() const { return voxelIndex_; }
    const GPUFloatArray& triangles() const { return triangles_; }
    const GPUFloatArray& cellTriangles() const { return cellTriangles_; }
    const GPUFloatArray& materials() const { return materials_; }
    const GPUFloatArray& vertexNormals() const { return vertexNormals_; }
    const GPUFloatArray& emitters() const { return emitters_; }
    const GPUFloatArray& texcoords() const { return texcoords_; }
    const GPUFloatArray& textureTexels() const { return textureTexels_; }
    const GPUFloatArray& textureTable() const { return textureTable_; }
    const GPUFloatArray& srgbTable() const { return srgbTable_; }
    const EmitterTable& emitterTable() const { return emitterTable_; }
    size_t bytes() const;

  private:
    const UniformGrid& grid_;
    GPUFloatArray voxelIndex_;
    GPUFloatArray triangles_;
    GPUFloatArray cellTriangles_;
    GPUFloatArray materials_;
    GPUFloatArray vertexNormals_;
    bool hasVertexNormals_;
    EmitterTable emitterTable_;
    GPUFloatArray emitters_;
    GPUFloatArray texcoords_;
    bool hasTexcoords_;
    GPUFloatArray textureTexels_;
    GPUFloatArray textureTable_;
    GPUFloatArray srgbTable_;
};

}  // namespace gpurt
