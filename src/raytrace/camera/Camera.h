// The contract's pinhole camera (CONTRACT.md, camera convention), evaluated in float32 in the
// contract's order so that both backends and outside checks shoot the same primary rays.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "raytrace/common/RenderTypes.h"
#include "scene/Scene.h"

namespace gpurt {

struct CameraBasis {
    glm::vec3 eye, forward, right, upOrtho;
    float tanHalf;  // float(tan(fovy * pi / 360)), computed in double
    float aspect;   // float(width) / float(height)
    int width, height;
    // The thin lens (CONTRACT.md, depth of field): lensRadius 0 is the pinhole camera.
    float lensRadius = 0.0f;     // scene units (an f-stop converted)
    float focusDistance = 1.0f;  // along forward
    int blades = 0;              // 0: a disc
    float bladeRotation = 0.0f;  // radians
    // The rows rendered (--tile): rowCount rows from rowBegin of the width x height image; the
    // render's output is width x rows(). rowCount 0: all of them.
    int rowBegin = 0, rowCount = 0;

    int rows() const { return rowCount > 0 ? rowCount : height; }
};

// Tile i of n of an image `height` rows high (--tile i/n, 0 <= i < n <= height): rows
// [floor(i H / n), floor((i + 1) H / n)), so that the tiles' heights differ by at most one row.
inline void tileRows(int height, int i, int n, int& begin, int& count) {
    begin = int(int64_t(i) * height / n);
    count = int(int64_t(i + 1) * height / n) - begin;
}

// Throws InputError for fovy outside (0, 180), eye == target, up parallel to the view direction,
// non-finite values, a size below 1x1, or a lens the contract does not know (a negative radius,
// an f-stop <= 0, 1 or 2 blades, a focus distance <= 0); the message starts with the option's
// name ("--fovy: ..."). An f-stop N becomes the lens radius f / (2 N) of the focal length f of a
// 36 mm sensor across the image's larger side (spec.metre scene units a metre).
CameraBasis makeCamera(const CameraSpec& spec, int width, int height);

// The contract's default camera: from the +z side, fitting the box's front face with a 10% margin.
// An empty box is treated as the unit cube around the origin.
CameraSpec defaultCamera(const Bounds& bounds, int width, int height, float fovy = 45.0f);

// Direction of the primary ray through pixel (i, j), j counted from the top row.
glm::vec3 primaryDirection(const CameraBasis& camera, int i, int j);

struct CameraRay {
    glm::vec3 origin, direction;
};

// The ray of sample s of n (--spp) through pixel (i, j): sampleDirection's from the eye, or with a
// lens, through the sample's lens point (glsl/common/raymath.h thinLensRay, sampling dimension
// GPURT_DIM_LENS).
CameraRay sampleRay(const CameraBasis& camera, int i, int j, uint32_t s, uint32_t n, uint32_t seed, SamplerKind sampler);

// Direction of the ray of sample s of n (--spp) through pixel (i, j) with --seed `seed` from
// `sampler` (glsl/common/sampling.h): the pixel centre for n = 1.
glm::vec3 sampleDirection(const CameraBasis& camera, int i, int j, uint32_t s, uint32_t n, uint32_t seed,
                          SamplerKind sampler);

}  // namespace gpurt
