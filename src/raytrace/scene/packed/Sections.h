// The scene's sections of a packed file (docs/PACKED_FORMAT.md), one group a file: Geometry
// (TRIS, NRML, TXCO, VCOL, TANG), Materials (MATS, TEXS, MODL, PBRM, ALPH, SIDE, GLOW, TRNS, LAYR, VOLM, IRID,
// ANIS, THIN), Lights
// (LGTS, LGTX, ENVM) and View (CAMR, LENS, ANIM, BKGD, RNDR). Each section says when the writer
// stores it, how to write it and how to read it; each group the checks of validateScene that
// concern it. scene/PackedScene.cpp lays the sections out and reads the table; the acceleration
// structure's sections are its accelerator's (accel/Accelerator.h).
#pragma once

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "image/InputError.h"
#include "raytrace/common/PackedBytes.h"
#include "raytrace/common/Vec3.h"
#include "raytrace/scene/SceneLoader.h"

namespace gpurt::packed {

struct SceneSection {
    const char* tag;  // four ASCII characters, stored as they read
    // Whether the writer stores it for this scene (a required section always; an optional one
    // only for scenes that need it, so that other files stay as they were before it existed).
    bool (*present)(const LoadedScene& loaded);
    bool required;
    void (*write)(ByteWriter& out, const LoadedScene& loaded);
    // Reads it into the scene, after the sections before it in the writer's order, each sized by
    // its counts before anything is allocated; InputError naming the file for what does not fit.
    void (*read)(const PackedSection& in, LoadedScene& loaded);
};

extern const SceneSection kTriangleSection, kNormalSection, kTexcoordSection, kColorSection, kTangentSection;
extern const SceneSection kMaterialSection, kTextureSection, kModelSection, kPbrSection, kAlphaSection, kSideSection,
    kGlowSection, kTransmissionMapSection, kLayerSection, kVolumeSection, kFilmSection,
    kAnisotropySection, kThinSection, kDispersionSection;
extern const SceneSection kLightSection, kLightKindSection, kEnvironmentSection;
extern const SceneSection kCameraSection, kLensSection, kAnimationSection, kBackgroundSection, kRenderSection;

// The checks of validateScene (scene/PackedScene.cpp), by group; `file` names the scene in each
// message.
void checkTriangles(const FileLoc& file, const Scene& scene);
void checkColors(const FileLoc& file, const Scene& scene);
void checkTangents(const FileLoc& file, const Scene& scene);
void checkMaterials(const FileLoc& file, const Scene& scene);
void checkTextures(const FileLoc& file, const Scene& scene);
void checkLights(const FileLoc& file, const Scene& scene);
void checkCameras(const FileLoc& file, const Scene& scene);
void checkRenderSettings(const FileLoc& file, const LoadedScene& loaded);

// Shared by the groups.
bool nonNegative(const glm::vec3& v);
std::string formatFloat(float value);  // "%g"
// The leading count of a section of one record per triangle, material or light (read after
// those), which must be `expected`, the count of `of`; `limit` as for PackedSection::count.
uint64_t oneEach(ByteReader& in, const PackedSection& s, uint64_t recordBytes, const char* what, uint64_t limit,
                 uint64_t expected, const char* of);
uint64_t perTriangle(ByteReader& in, const PackedSection& s, uint64_t recordBytes, const char* what,
                     const Scene& scene);
// A name's length, then the name padded to 4 bytes.
// InputError for one longer than a u32 counts (`what` names its kind).
void writeName(ByteWriter& out, const std::string& text, const char* what);

}  // namespace gpurt::packed
