// Rendering scenes far from unit size. Both backends trace in float32, and some of their values
// grow with a power of the coordinates: the triangle test's t is a ratio of cubic terms, the
// normal's squared length is quartic. A scene at 1e10 loses its normals to overflow, one at 1e15
// or 1e-15 all its hits, and the default camera of one at 1e20 cannot even be set up.
// Multiplying every position by a power of two is exact, and so is every float operation of the
// backends on the scaled values as long as nothing over- or underflows; the image of the rescaled
// scene is therefore the image of the original, where that one was computable, and its depths
// scale back exactly. The render command rescales scenes whose coordinates are far from 1.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "raytrace/common/Vec3.h"
#include "scene/Scene.h"

namespace gpurt {

// The exponent e such that the scene times 2^-e renders without over- or underflow: 0 when its
// largest coordinate is within [2^-28, 2^28] in magnitude (those scenes are left as they are),
// else the power of two that brings it into [1, 2). 0 for a scene without triangles.
int renderScaleExponent(const Scene& scene);

// rescalePoint (p * 2^-exponent, exact): raytrace/common/Vec3.h.

// A camera's positions and lengths times 2^-exponent (eye, target, lens radius, focus distance,
// and its metre, so that an f-stop gives the same lens).
void rescaleCamera(CameraSpec& camera, int exponent);

// Multiplies every position of the scene by 2^-exponent (vertices, lights, the camera's eye and
// target, the volumes' attenuation distances) and light intensities by 2^-2*exponent, so that
// radiance, intensity / distance^2, stays the same.
void rescaleScene(Scene& scene, int exponent);

// Depths of the rescaled scene back in the original units: each times 2^exponent, at most the
// largest float (+inf stays a miss).
void unscaleDepth(std::vector<float>& depth, int exponent);

}  // namespace gpurt
