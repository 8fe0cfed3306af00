#include "FuzzScene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include <unistd.h>

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "image/InputError.h"
#include "raytrace/scene/SceneScale.h"
#include "raytrace/accel/grid/GridAccelerator.h"

namespace gpurt::fuzz {
namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz check failed: %s\n", what);
    std::abort();
}

#define FUZZ_CHECK(condition) \
    if (!(condition)) fail(#condition)

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::filesystem::path makeScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "gpurt-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) fail("cannot create a scratch folder");
    const std::filesystem::path folder(pattern);
    auto write = [&](const char* name, const std::string& text) {
        std::ofstream(folder / name, std::ios::binary) << text;
    };
    write("a.mtl",
          "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 20\nillum 2\n"
          "newmtl mirror\nKd 0.1 0.1 0.1\nKs 0.9 0.9 0.9\nNs 200\nillum 3\n");
    write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write("quad.mtl", "newmtl glass\nKd 0 0 0\nKs 0.8 0.8 0.8\nillum 5\n");
    write("quad.obj",
          "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl glass\nf 1 2 3 4\n");
    write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    write("empty.obj", "");
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};  // little endian, as glTF buffers
    write("tri.bin", std::string(reinterpret_cast<const char*>(triangle), sizeof triangle));
    write("tri.ply",
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    std::atexit([] { std::filesystem::remove_all(scratchFolder()); });
    return folder;
}

}  // namespace

const std::filesystem::path& scratchFolder() {
    static const std::filesystem::path folder = makeScratchFolder();
    return folder;
}

void silenceWarnings() { std::cerr.setstate(std::ios::badbit); }

void exerciseScene(const Scene& original, const AccelStructure* packed) {
    FUZZ_CHECK(!original.materials.empty());
    FUZZ_CHECK(original.materialIds.size() == original.triangles.size());
    for (uint32_t id : original.materialIds) FUZZ_CHECK(id < original.materials.size());
    for (const Triangle& t : original.triangles)
        FUZZ_CHECK(finite(t.v0) && finite(t.v1) && finite(t.v2));
    // Vertex colours: none, or one record per triangle, linear RGB in [0, 1].
    FUZZ_CHECK(original.colors.empty() || original.colors.size() == original.triangles.size());
    for (const TriangleColors& c : original.colors)
        for (const glm::vec3 v : {c.c0, c.c1, c.c2})
            FUZZ_CHECK(v.x >= 0.0f && v.x <= 1.0f && v.y >= 0.0f && v.y <= 1.0f && v.z >= 0.0f && v.z <= 1.0f);

    // As the render command does: far from unit size, the scene is rescaled (SceneScale.h).
    Scene scene = original;
    const int scaleExponent = renderScaleExponent(scene);
    rescaleScene(scene, scaleExponent);
    std::shared_ptr<const AccelStructure> structure;
    if (packed) {  // a packed scene's own structure, validated by its reader
        structure = packed->rescaled(scaleExponent);
    } else {
        AccelOptions options;
        options.threads = 1;
        structure = gridAccelerator().build(scene, options);
    }
    if (const UniformGrid* grid = gridOf(structure)) {
        FUZZ_CHECK(grid->cellStart.size() == grid->cells() + 1);
        FUZZ_CHECK(grid->cellStart.back() == grid->cellTriangles.size());
    }

    constexpr int kSize = 6;
    // An animation's frames interpolate its keys: each either makes a camera or is refused, around
    // and between the keys' times (frames from 0 up to past the last key).
    if (scene.animation) {
        const CameraAnimation& a = *scene.animation;
        const double end = std::min(double(a.keys.back().time) * a.fps + 2.0, 50.0);
        for (int frame = 0; frame <= int(std::max(end, 0.0)); ++frame) {
            const CameraSpec c = a.at(frame);
            try {
                makeCamera(c, kSize, kSize);
            } catch (const InputError&) {
            }
        }
    }
    CameraBasis camera;
    if (scene.camera) {
        try {
            camera = makeCamera(*scene.camera, kSize, kSize);
        } catch (const InputError&) {
            return;  // the file's camera may be unusable after all (e.g. at 1e38 from the scene)
        }
    } else {
        // The default camera exists for every scene a reader accepts.
        camera = makeCamera(defaultCamera(scene.bounds(), kSize, kSize), kSize, kSize);
    }
    RenderSettings settings;
    settings.threads = 1;
    settings.maxBounces = std::min(scene.maxBounces, 2);
    const RenderOutput out = CpuTracer(scene, structure->cpu(scene), structure->rayOffset()).render(camera, settings);
    FUZZ_CHECK(out.stats.overflowRays == 0);
    for (size_t k = 0; k < out.depth.size(); ++k) {
        FUZZ_CHECK(!std::isnan(out.depth[k]));
        FUZZ_CHECK(!std::isnan(out.color[k].x) && !std::isnan(out.color[k].y) &&
                   !std::isnan(out.color[k].z));
        const bool hit = out.prim[k] >= 0.0f;
        FUZZ_CHECK(hit == std::isfinite(out.depth[k]));
        FUZZ_CHECK(out.prim[k] < float(scene.triangles.size()));
        FUZZ_CHECK(!hit || out.depth[k] > 0.0f);
    }
}

}  // namespace gpurt::fuzz
