#include "raytrace/accel/BenchRays.h"

#include "raytrace/common/RayMath.h"

namespace gpurt {

RayStream primaryRays(const CameraBasis& camera) {
    RayStream rays;
    rays.width = camera.width;
    rays.height = camera.height;
    const size_t n = size_t(camera.width) * size_t(camera.height);
    rays.origin.assign(n, camera.eye);
    rays.direction.resize(n);
    rays.tLimit.assign(n, GPURT_FAR);
    for (int j = 0; j < camera.height; ++j)
        for (int i = 0; i < camera.width; ++i)
            rays.direction[size_t(j) * size_t(camera.width) + size_t(i)] = primaryDirection(camera, i, j);
    return rays;
}

glm::vec3 shadowRayTarget(const Scene& scene, glm::vec3 eye) {
    const std::vector<Light> lights = lightsOrHeadlight(scene, eye);
    return lights.empty() ? eye : lights.front().position;
}

RayStream shadowRays(const Scene& scene, float rayOffset, const RayStream& primary,
                     const std::vector<glm::vec4>& hits, glm::vec3 light) {
    RayStream rays;
    const float offset = rayOffset;
    for (size_t i = 0; i < hits.size(); ++i) {
        if (hits[i].w < 0.0f) continue;
        const Triangle& tri = scene.triangles[size_t(hits[i].w)];
        const glm::vec3 d = primary.direction[i];
        const glm::vec3 p = primary.origin[i] + hits[i].x * d;
        const glm::vec3 n = raymath::facingNormal(tri.v1 - tri.v0, tri.v2 - tri.v0, d);
        glm::vec3 o, dir;
        float tLimit;
        raymath::shadowRay(p, n, offset, light, o, dir, tLimit);
        rays.origin.push_back(o);
        rays.direction.push_back(dir);
        rays.tLimit.push_back(tLimit);
    }
    rays.width = std::max(1, primary.width);
    rays.height = std::max<int>(1, int((rays.tLimit.size() + size_t(rays.width) - 1) / size_t(rays.width)));
    const size_t n = size_t(rays.width) * size_t(rays.height);
    rays.origin.resize(n, glm::vec3(0.0f));
    rays.direction.resize(n, glm::vec3(0.0f, 0.0f, 1.0f));
    rays.tLimit.resize(n, -1.0f);
    return rays;
}

}  // namespace gpurt
