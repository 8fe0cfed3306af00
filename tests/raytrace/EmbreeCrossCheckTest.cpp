// The CPU backend's primary hits against Embree 3 (rtcIntersect1 on the same float vertices):
// hit/miss, triangle id and depth per pixel, for the models' recommended cameras, an oblique
// camera, a camera inside the scene's box and a non-square image.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "scene/ObjLoader.h"
#include "raytrace/accel/BenchRays.h"
#include "raytrace/scene/SceneLoader.h"
#include "raytrace/accel/Acceleration.h"
#include "raytrace/accel/grid/UniformGrid.h"

namespace gpurt {
namespace {

// One Embree device and scene holding the scene's triangles as geometry 0, primID = our index.
class EmbreeScene {
  public:
    explicit EmbreeScene(const Scene& scene) {
        device_ = rtcNewDevice(nullptr);
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        const size_t n = scene.triangles.size();
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
        for (size_t k = 0; k < n; ++k) {
            const Triangle& t = scene.triangles[k];
            const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
            for (int c = 0; c < 3; ++c) {
                for (int a = 0; a < 3; ++a) vertices[9 * k + 3 * size_t(c) + size_t(a)] = v[c][a];
                indices[3 * k + size_t(c)] = unsigned(3 * k + size_t(c));
            }
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_);
    }
    ~EmbreeScene() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // (t, prim) of the first hit; prim = -1 on a miss.
    std::pair<float, int> intersect(glm::vec3 o, glm::vec3 d) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = o.x;
        rh.ray.org_y = o.y;
        rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = std::numeric_limits<float>::infinity();
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            return {std::numeric_limits<float>::infinity(), -1};
        return {rh.ray.tfar, int(rh.hit.primID)};
    }

    // Whether o + t d is blocked for 0 < t < tLimit (rtcOccluded1).
    bool occluded(glm::vec3 o, glm::vec3 d, float tLimit) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray{};
        ray.org_x = o.x;
        ray.org_y = o.y;
        ray.org_z = o.z;
        ray.dir_x = d.x;
        ray.dir_y = d.y;
        ray.dir_z = d.z;
        ray.tnear = 0.0f;
        ray.tfar = tLimit;
        ray.mask = 0xFFFFFFFFu;
        rtcOccluded1(scene_, &context, &ray);
        return ray.tfar == -std::numeric_limits<float>::infinity();
    }

  private:
    RTCDevice device_;
    RTCScene scene_;
};

void crossCheck(const struct CrossCheckCase& c, const char* choice);

struct CrossCheckCase {
    const char* name;
    const char* model;
    CameraSpec camera;
    int width, height;
};

void crossCheck(const CrossCheckCase& c) {
    for (const char* choice : {"grid", "bvh"}) crossCheck(c, choice);
}

void crossCheck(const CrossCheckCase& c, const char* choice) {
    const Scene scene = loadObj(std::string("../shared/models/") + c.model);
    const CameraBasis camera = makeCamera(c.camera, c.width, c.height);
    const Acceleration accel = chooseAcceleration(scene, choice, nullptr, {}, camera);
    const CpuTracer tracer(scene, makeCpuAccelerator(scene, accel), accel.rayOffset());
    const EmbreeScene embree(scene);
    RenderSettings settings;
    settings.maxBounces = 0;
    const RenderOutput out = tracer.render(camera, settings);
    EXPECT_EQ(out.stats.overflowRays, 0u);

    int pixels = 0, hitMissAgree = 0, bothHit = 0, primAgree = 0, depthAgree = 0;
    for (int j = 0; j < c.height; ++j)
        for (int i = 0; i < c.width; ++i) {
            const size_t k = size_t(j) * size_t(c.width) + size_t(i);
            const auto [t, prim] = embree.intersect(camera.eye, primaryDirection(camera, i, j));
            const int ours = int(out.prim[k]);
            ++pixels;
            if ((ours >= 0) != (prim >= 0)) continue;
            ++hitMissAgree;
            if (prim < 0) continue;
            ++bothHit;
            if (ours == prim) ++primAgree;
            if (std::abs(out.depth[k] - t) <= 1e-4f * t) ++depthAgree;
        }
    const double hitMiss = double(hitMissAgree) / pixels;
    const double primShare = bothHit ? double(primAgree) / bothHit : 1.0;
    const double depthShare = bothHit ? double(depthAgree) / bothHit : 1.0;
    std::printf(
        "[ embree   ] %s, %s (%dx%d): hit/miss agree %.4f%% of %d pixels; of %d hits: prim %.4f%%, "
        "depth %.4f%%\n",
        c.name, std::string(accel.name()).c_str(), c.width, c.height, 100.0 * hitMiss, pixels, bothHit, 100.0 * primShare,
        100.0 * depthShare);
    EXPECT_GT(bothHit, pixels / 10) << c.name << ": the camera sees too little of the model";
    EXPECT_GE(hitMiss, 0.999) << c.name;
    EXPECT_GE(primShare, 0.995) << c.name;
    EXPECT_GE(depthShare, 0.995) << c.name;
}

TEST(EmbreeCrossCheckTest, BunnyFront) {
    crossCheck(
        {"bunny front", "bunny.obj", {{0, 0, 3.43f}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 256, 256});
}

TEST(EmbreeCrossCheckTest, CornellBox) {
    crossCheck({"cornell box",
                "cornell_box.obj",
                {{278, 273, -800}, {278, 273, 0}, {0, 1, 0}, 39.3077f},
                256,
                256});
}

TEST(EmbreeCrossCheckTest, BunnyOblique) {
    crossCheck({"bunny oblique",
                "bunny.obj",
                {{2.1f, 1.6f, -1.9f}, {0.05f, -0.1f, 0.02f}, {0, 1, 0}, 40.0f},
                256,
                256});
}

TEST(EmbreeCrossCheckTest, CameraInsideTheBox) {
    crossCheck({"inside cornell box",
                "cornell_box.obj",
                {{278, 273, 150}, {120, 200, 500}, {0, 1, 0}, 70.0f},
                256,
                256});
    crossCheck({"inside bunny box",
                "bunny.obj",
                {{0.2f, 0.1f, 0.6f}, {-0.3f, -0.2f, -0.5f}, {0, 1, 0}, 60.0f},
                256,
                256});
}

TEST(EmbreeCrossCheckTest, NonSquareImages) {
    crossCheck({"bunny_lo wide",
                "bunny_lo.obj",
                {{0, 4.83f, 16.97f}, {0, 4.83f, 0.04f}, {0, 1, 0}, 45.0f},
                320,
                180});
    crossCheck(
        {"teapot tall", "teapot.obj", {{0, 0, 52.68f}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 150, 256});
}

// The bench views (the scene's camera, else the default one) of every scene of the scaling table:
// both accelerators find Embree's triangle on >= 99.9% of the primary rays that both hit (the rest
// are hits on edges shared by two triangles at the same distance, where any of the two is right,
// or grazing hits one test finds and the other misses), and agree with rtcOccluded1 on every
// shadow ray from Embree's hits to the scene's first light (the headlight without one).
TEST(EmbreeCrossCheckTest, BothAcceleratorsOnTheBenchViewsOfEveryScene) {
    for (const char* path : {"scenes/boxes.json", "scenes/room.json", "scenes/highlow.json", "scenes/cornell_blocks.json",
                             "../shared/models/teapot.obj", "../shared/models/bunny_lo.obj",
                             "../shared/models/bunny.obj"}) {
        const LoadedScene loaded = loadScene(path);
        const Scene& scene = loaded.scene;
        const int size = 128;
        const CameraSpec spec = scene.camera ? *scene.camera : defaultCamera(scene.bounds(), size, size);
        const CameraBasis camera = makeCamera(spec, size, size);
        const EmbreeScene embree(scene);
        const RayStream primary = primaryRays(camera);
        std::vector<glm::vec4> embreeHits(primary.tLimit.size(), glm::vec4(0, 0, 0, -1));
        for (size_t k = 0; k < primary.tLimit.size(); ++k) {
            const auto [t, prim] = embree.intersect(primary.origin[k], primary.direction[k]);
            if (prim >= 0) embreeHits[k] = glm::vec4(t, 0, 0, float(prim));
        }
        for (const char* choice : {"grid", "bvh"}) {
            const Acceleration accel = chooseAcceleration(scene, choice, nullptr, {}, camera);
            const std::unique_ptr<CpuAccelerator> tracer = makeCpuAccelerator(scene, accel);
            int bothHit = 0, same = 0, hitMissSame = 0;
            for (size_t k = 0; k < primary.tLimit.size(); ++k) {
                const TraceHit hit = tracer->closestHit(primary.origin[k], primary.direction[k], primary.tLimit[k], 0u);
                const int prim = int(embreeHits[k].w);
                hitMissSame += (hit.prim >= 0) == (prim >= 0);
                if (hit.prim < 0 || prim < 0) continue;
                ++bothHit;
                same += hit.prim == prim;
            }
            const RayStream shadow =
                shadowRays(scene, accel.rayOffset(), primary, embreeHits, shadowRayTarget(scene, camera.eye));
            int shadowRays = 0, occlusionSame = 0;
            for (size_t k = 0; k < shadow.tLimit.size(); ++k) {
                if (shadow.tLimit[k] < 0.0f) continue;
                ++shadowRays;
                const bool ours = tracer->anyHit(shadow.origin[k], shadow.direction[k], shadow.tLimit[k], 0u).prim >= 0;
                occlusionSame += ours == embree.occluded(shadow.origin[k], shadow.direction[k], shadow.tLimit[k]);
            }
            std::printf("[ embree   ] %s, %s: prim %.4f%% of %d hits, hit/miss %.4f%%, occlusion %d of %d shadow rays\n",
                        path, std::string(accel.name()).c_str(), 100.0 * same / std::max(1, bothHit), bothHit,
                        100.0 * hitMissSame / double(primary.tLimit.size()), occlusionSame, shadowRays);
            EXPECT_GT(bothHit, size * size / 20) << path;
            EXPECT_GE(double(same) / bothHit, 0.999) << path << " " << accel.name();
            EXPECT_GE(double(hitMissSame) / double(primary.tLimit.size()), 0.999) << path << " " << accel.name();
            EXPECT_EQ(occlusionSame, shadowRays) << path << " " << accel.name();
        }
    }
}

}  // namespace
}  // namespace gpurt
