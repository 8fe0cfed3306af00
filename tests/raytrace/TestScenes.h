// Scenes built in code and renders on both backends, for the tests of the pictures and of the
// path integrator (PictureGLTest, PathGLTest).
#pragma once

#include "raytrace/camera/Camera.h"
#include "image/Colour.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "image/ImageIO.h"
#include "raytrace/accel/grid/UniformGrid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace gpurt::test {

// The same render on the GL chain and on the CPU backend.
struct Both {
    RenderOutput gl, cpu;
};

inline Both renderBoth(const Scene& scene, const CameraSpec& spec, int width, int height, uint32_t samples,
                       int bounces = 3, Integrator integrator = Integrator::Whitted, uint32_t seed = 0) {
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(spec, width, height);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.samples = samples;
    settings.maxBounces = bounces;
    settings.integrator = integrator;
    settings.seed = seed;
    Both both;
    both.cpu = CpuTracer(scene, grid).render(camera, settings);
    GpuTracer tracer(scene, grid);
    both.gl = tracer.render(camera, settings);
    return both;
}

inline uint32_t addMaterial(Scene& scene, glm::vec3 kd, glm::vec3 emission = glm::vec3(0.0f), float ior = 0.0f,
                     glm::vec3 transmission = glm::vec3(1.0f)) {
    Material m;
    m.diffuse = kd;
    m.emission = emission;
    m.ior = ior;
    m.transmission = transmission;
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
}

// The polygon's corners as triangles (v0, vi, vi+1).
inline void addPolygon(Scene& scene, const std::vector<glm::vec3>& corners, uint32_t material) {
    for (size_t i = 1; i + 1 < corners.size(); ++i) {
        scene.triangles.push_back({corners[0], corners[i], corners[i + 1]});
        scene.materialIds.push_back(material);
    }
}

inline void addBox(Scene& scene, glm::vec3 lo, glm::vec3 hi, uint32_t material) {  // wound outward
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    for (const auto& f : faces) addPolygon(scene, {c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, material);
}

// The 8-bit pictures of both backends (default tone map): at most 1 level apart on 99.9% of the
// pixels.
// `sameRays` false: the pictures only (a scene whose rounding decides some rays' existence: an
// emitter's own points sampling it edge-on).
inline void expectSamePictures(const RenderOutput& gl, const RenderOutput& cpu, const std::string& what,
                               bool sameRays = true) {
    const std::vector<glm::vec3> a = toneMapImage(gl.color, {}), b = toneMapImage(cpu.color, {});
    size_t close = 0, nans = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(linearToSrgb8(a[i][c])) - int(linearToSrgb8(b[i][c]))));
        close += worst <= 1;
        nans += std::isnan(gl.color[i].x + gl.color[i].y + gl.color[i].z);
    }
    EXPECT_GE(double(close) / double(a.size()), 0.999) << what;
    EXPECT_EQ(nans, 0u) << what;
    if (!sameRays) return;
    // The same rays but where float differences send a glass ray another way (0.1%).
    EXPECT_NEAR(double(gl.stats.shadowRays), double(cpu.stats.shadowRays), 1e-3 * double(cpu.stats.shadowRays)) << what;
    EXPECT_NEAR(double(gl.stats.secondaryRays), double(cpu.stats.secondaryRays), 1e-3 * double(cpu.stats.secondaryRays)) << what;
}

// A sphere of radius r about c as a subdivided icosahedron (convex, faceted), wound outward.
inline void addIcosphere(Scene& scene, glm::vec3 c, float r, int subdivisions, uint32_t material) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<glm::ivec3> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                 {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (glm::vec3& p : v) p = glm::normalize(p);
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<glm::ivec3> next;
        for (const glm::ivec3& k : f) {
            int m[3];
            for (int e = 0; e < 3; ++e) {
                v.push_back(glm::normalize(v[size_t(k[e])] + v[size_t(k[(e + 1) % 3])]));
                m[e] = int(v.size() - 1);
            }
            next.insert(next.end(), {{k.x, m[0], m[2]}, {k.y, m[1], m[0]}, {k.z, m[2], m[1]}, {m[0], m[1], m[2]}});
        }
        f = next;
    }
    for (const glm::ivec3& k : f) {
        glm::vec3 a = c + r * v[size_t(k.x)], b = c + r * v[size_t(k.y)], d = c + r * v[size_t(k.z)];
        if (glm::dot(glm::cross(b - a, d - a), a + b + d - 3.0f * c) < 0.0f) std::swap(b, d);
        scene.triangles.push_back({a, b, d});
        scene.materialIds.push_back(material);
    }
}

}  // namespace gpurt::test
