// The BVH's scene textures (glsl/common/scene_layout.h, common/bvh.h): its quantised nodes and
// its leaf-ordered triangle list.
#include "raytrace/accel/bvh/BvhTexels.h"

#include <algorithm>
#include <cmath>

namespace gpurt {

namespace {
using namespace glm;
#include "../../../../glsl/common/scene_layout.h"
}  // namespace

namespace {
// A box coordinate in steps of the quantisation frame, rounded outwards: the step decoded as
// common/bvh.h bvhChildBox does is at most (roundUp false) or at least (true) the coordinate.
uint32_t quantise(float v, float origin, float step, bool roundUp) {
    const double exact = (double(v) - double(origin)) / double(step);
    double q = roundUp ? std::ceil(exact) + 1.0 : std::floor(exact) - 1.0;
    q = std::clamp(q, 0.0, double(GPURT_BVH_STEPS));
    uint32_t n = uint32_t(q);
    auto decoded = [&](uint32_t k) { return origin + float(k) * step; };
    while (!roundUp && n > 0 && decoded(n) > v) --n;
    while (roundUp && n < GPURT_BVH_STEPS && decoded(n) < v) ++n;
    return n;
}
}  // namespace

TextureTexels bvhNodeTexels(const Bvh& bvh) {
    TextureTexels nodes = emptyTexture("bvhNodes", 2 * GPURT_BVH_NODES_PER_ROW,
                                       textureRowsFor(bvh.nodes.size(), GPURT_BVH_NODES_PER_ROW), 4, false);
    glm::vec3 origin, step;
    bvh.quantisation(origin, step);
    for (size_t n = 0; n < bvh.nodes.size(); ++n) {
        for (int c = 0; c < 2; ++c) {
            const Bvh::Child& child = bvh.nodes[n].child[c];
            uint32_t* out = &nodes.uints[(2 * n + size_t(c)) * 4];
            if (child.ref < 0) {  // nothing: an empty box (min > max), w = 0
                out[0] = GPURT_BVH_STEPS | GPURT_BVH_STEPS << 16;
                out[1] = GPURT_BVH_STEPS;
                out[2] = 0;
                out[3] = 0;
                continue;
            }
            uint32_t lo[3], hi[3];
            for (int a = 0; a < 3; ++a) {
                lo[a] = quantise(child.min[a], origin[a], step[a], false);
                hi[a] = quantise(child.max[a], origin[a], step[a], true);
            }
            out[0] = lo[0] | lo[1] << 16;
            out[1] = lo[2] | hi[0] << 16;
            out[2] = hi[1] | hi[2] << 16;
            out[3] = uint32_t(child.ref) << 4 | child.count;
        }
    }
    return nodes;
}

TextureTexels bvhTriangleTexels(const Scene& scene, const Bvh& bvh) {
    return triangleListTexels(scene, bvh.triangles, "bvhTriangles");
}

std::vector<TextureTexels> sceneTextureTexels(const Scene& scene, const Bvh& bvh) {
    std::vector<TextureTexels> all{bvhNodeTexels(bvh), bvhTriangleTexels(scene, bvh)};
    for (TextureTexels& t : integratorTextureTexels(scene)) all.push_back(std::move(t));
    return all;
}

}  // namespace gpurt
