// The scene in textures (Purcell et al. 2002, 3.1; Christen 2005, 5.3) for the integrators'
// kernels: the triangles, materials, vertex normals, texture coordinates, textures, emitters,
// vertex colours and the environment light,
// laid out as glsl/common/scene_layout.h says. The accelerator uploads its own (accel/). Triangle
// ids (carried as floats in the hit stream) are checked against 2^24.
#pragma once

#include "raytrace/lights/EmitterTable.h"
#include "raytrace/lights/EnvironmentTable.h"
#include "scene/Scene.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"

#include <optional>
#include <set>

namespace gpurt {

struct TextureTexels;

// Throw EnvironmentError naming `what` when a texture of width x rows texels, or a buffer texture
// of that many, does not fit the GL's limits.
void checkFits(const char* what, size_t width, size_t rows);
void checkFitsBuffer(const char* what, size_t width, size_t rows);
// A GL texture (or buffer texture) holding `texels`.
GPUFloatArray uploadTexels(const TextureTexels& texels, GPUFormat format, GPUStorage storage);

class SceneTextures {
  public:
    // Throws EnvironmentError when the scene does not fit the GL limits or the exact-index limits.
    // rayOffset: how far secondary rays start off a surface (UniformGrid::rayOffset).
    SceneTextures(const Scene& scene, float rayOffset);

    // Adds the scene textures as inputs of `kernel` (samplers triangles, materials,
    // vertexNormals, emitters, triangleTexcoords, textureTexels, textureTable, srgbTable,
    // vertexColors; vertexTangents where a normal map reads them), sets
    // the emitter uniforms and rayOffset, and defines what the scene has (SCENE_*).
    void bind(GPUKernel& kernel) const;
    // Whether some triangle's material has alpha (sceneUsesAlpha): the accelerators' kernels then test
    // candidate hits for coverage (glsl/scene/alpha.glsl).
    bool hasAlpha() const { return hasAlpha_; }
    // Whether some triangle's material culls its back faces (sceneCullsBackFaces).
    bool cullsBackFaces() const { return cullsBackFaces_; }
    // Whether the accelerators' kernels test candidate hits at all: alpha or culling.
    bool hasCoverage() const { return hasAlpha_ || cullsBackFaces_ || shadowless_; }
    // Defines SCENE_ALPHA and SCENE_CULL_BACK (each where the scene has it) in an accelerator's
    // kernel and adds what its coverage test reads (the triangles, materials, texture coordinates
    // and textures); nothing without coverage.
    void bindCoverage(GPUKernel& kernel) const;
    // Only the defines, for a kernel that bind() gave the textures already (the megakernels,
    // which trace inside).
    void bindCoverageDefines(GPUKernel& kernel) const;

    const GPUFloatArray& triangles() const { return triangles_; }
    const GPUFloatArray& materials() const { return materials_; }
    const GPUFloatArray& vertexNormals() const { return vertexNormals_; }
    const GPUFloatArray& emitters() const { return emitters_; }
    const GPUFloatArray& texcoords() const { return texcoords_; }
    const GPUFloatArray& textureTexels() const { return textureTexels_; }
    const GPUFloatArray& textureTable() const { return textureTable_; }
    const GPUFloatArray& srgbTable() const { return srgbTable_; }
    const GPUFloatArray& vertexColors() const { return vertexColors_; }
    const GPUFloatArray& vertexTangents() const { return vertexTangents_; }
    const EmitterTable& emitterTable() const { return emitterTable_; }
    const EnvironmentTable& environmentTable() const { return environmentTable_; }
    size_t bytes() const;

  private:
    float rayOffset_;
    GPUFloatArray triangles_;
    GPUFloatArray materials_;
    GPUFloatArray vertexNormals_;
    bool hasVertexNormals_;
    EmitterTable emitterTable_;
    GPUFloatArray emitters_;
    GPUFloatArray vertexColors_;  // SCENE_VERTEX_COLORS: the scene has vertex colours
    bool hasVertexColors_;
    GPUFloatArray vertexTangents_;  // SCENE_VERTEX_TANGENTS: the scene has vertex tangents (glTF TANGENT)
    bool hasVertexTangents_;
    GPUFloatArray texcoords_;
    bool hasTexcoords_;
    bool hasNormalMaps_ = false;
    bool hasTransmission_ = false;  // a glTF material with KHR_materials_transmission
    bool hasTransmissionMaps_ = false;  // one of them with a transmissionTexture (SCENE_TRANSMISSION_MAPS)
    bool hasSpecularLayer_ = false;  // a glTF material with KHR_materials_specular (SCENE_SPECULAR_LAYER)
    bool hasClearcoat_ = false;      // a glTF material with a clearcoat (SCENE_CLEARCOAT)
    bool hasVolume_ = false;         // a glTF material with an absorbing volume (SCENE_VOLUME)
    bool hasThinWalls_ = false;      // a glTF material transmitting through a thin wall (SCENE_THIN_WALLS)
    bool hasIridescence_ = false;    // a glTF material with a thin film (SCENE_IRIDESCENCE)
    bool hasAnisotropy_ = false;     // a glTF material with anisotropy (SCENE_ANISOTROPY)
    bool hasDispersion_ = false;     // a glTF solid with KHR_materials_dispersion (SCENE_DISPERSION)
    std::optional<GPUFloatArray> sheenTable_;  // a glTF material with a sheen: its albedo table (SCENE_SHEEN)
    bool hasAlpha_ = false;        // SCENE_ALPHA in the accelerators' kernels
    bool cullsBackFaces_ = false;  // SCENE_CULL_BACK in the accelerators' kernels
    bool shadowless_ = false;      // SCENE_SHADOWLESS in the accelerators' kernels
    bool lightKinds_ = false;      // SCENE_LIGHT_KINDS: some light is a spot, directional or has a range
    GPUFloatArray textureTexels_;
    GPUFloatArray textureTable_;
    GPUFloatArray srgbTable_;
    // The environment light (SCENE_ENVIRONMENT; 1 x 1 without one): its map, its distribution's
    // marginal and conditional cumulative tables, its spherical harmonics (glsl/scene/environment.glsl).
    EnvironmentTable environmentTable_;
    GPUFloatArray environmentMap_, environmentMarginal_, environmentConditional_, environmentHarmonics_;
    std::set<int> models_;  // the material models other than the classic one (0) the scene uses
};

}  // namespace gpurt
