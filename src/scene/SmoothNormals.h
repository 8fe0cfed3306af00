// Vertex normals for smooth shading (--smooth DEG): the triangles that have no normals from their
// file get angle-weighted vertex normals (Thurmer & Wuthrich 1998: each face's normal weighted by
// its angle at the vertex), averaged only over the faces around the vertex whose normals are
// within the crease angle of the face's own (Blender's "auto smooth"), so that a cube keeps its
// edges while a scanned model turns smooth. Vertices are shared by position.
#pragma once

#include "scene/Scene.h"

namespace gpurt {

// The default crease angle of --smooth, in degrees.
inline constexpr float kDefaultCreaseDegrees = 60.0f;

// creaseDegrees < 0 (--smooth off): every triangle faceted, the file's normals dropped too.
// Otherwise fills scene.normals (one per triangle) where the file gave none. Normals that are
// not finite or zero from the file are treated as none. Runs on `threads` threads (0: all cores);
// the normals are the same whatever the count.
void smoothNormals(Scene& scene, float creaseDegrees, int threads = 0);

}  // namespace gpurt
