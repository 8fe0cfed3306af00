// Shared by the fuzz targets: a scratch folder with the files the inputs may refer to, and what is
// done with a scene a reader accepted.
#pragma once

#include <filesystem>
#include <optional>

#include "scene/Scene.h"
#include "raytrace/accel/Accelerator.h"

namespace gpurt::fuzz {

// A fresh folder (removed at exit) holding the OBJ and MTL files that seed inputs name: a.mtl,
// tri.obj, quad.obj + quad.mtl, bad.obj, empty.obj. Inputs are read as if they were files in it.
const std::filesystem::path& scratchFolder();

// Checks what every later stage relies on (one material per triangle, ids in range, finite
// vertices), then runs the CPU pipeline on a tiny image as the render command would: rescaling
// (SceneScale.h), grid, camera (the scene's, else the default one), trace with shadows and
// mirrors. Only an InputError from the scene file's own camera is accepted; anything else that
// is wrong aborts, which libFuzzer reports as a crash: an exception, a NaN in colour or depth, a
// depth without a hit, a ray stopped by the traversal limit.
// With `packed` (a packed scene's structure, a grid or a BVH), that is traced instead of a new grid.
void exerciseScene(const Scene& scene, const AccelStructure* packed = nullptr);

// Makes std::cerr silent (the OBJ reader's warnings would flood the fuzzer's output).
void silenceWarnings();

}  // namespace gpurt::fuzz
