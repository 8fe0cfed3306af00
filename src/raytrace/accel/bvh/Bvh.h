// A bounding volume hierarchy over the scene's triangles (the second accelerator beside the
// uniform grid): binary, built on the CPU with the binned surface area heuristic (Wald 2007), each
// node holding its two children's boxes (Aila & Laine 2009) so that one visit tests both, the
// triangles of every leaf consecutive in one list in leaf order, as the grid's cell lists are.
// Both backends traverse this same tree with the same code (glsl/common/bvh.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/LargeArray.h"
#include "scene/Scene.h"

namespace gpurt {

struct Bvh {
    // One child of a node: its box and either an inner node (count 0, ref = node index > 0), a
    // leaf (count > 0: triangles [ref, ref + count) of `triangles`), or nothing (count 0, ref -1,
    // an empty box that no ray enters).
    struct Child {
        glm::vec3 min, max;
        int32_t ref;
        uint32_t count;
    };
    struct Node {
        Child child[2];
    };
    using BvhNodes = LargeArray<Node>;  // many megabytes for big models: huge pages
    BvhNodes nodes;                  // nodes[0] is the root; children follow their parents
    std::vector<uint32_t> triangles; // triangle ids in leaf order: each triangle exactly once
    glm::vec3 min{-1.0f}, max{1.0f}; // the scene's box, as the grid's (accel/SceneBox.h)
    int depth = 1;                   // nodes on the longest root-to-leaf path

    // The frame the kernels' nodes quantise the boxes in (bvhNodeTexels, glsl/common/bvh.h): a
    // box coordinate is origin + k * step, k in 0..65535; the frame holds every child box.
    void quantisation(glm::vec3& origin, glm::vec3& step) const;
    // The same tree for its scene turned by rotateUpToY(axis) (an accelerator owns its data): every
    // box's corners turned, an axis permutation with signs, exact in float; the leaves unchanged.
    void turnUp(UpAxis axis);
    // The same tree for its scene scaled by 2^-exponent (rescaleScene): exact in float.
    void rescale(int exponent);
    // Offset of secondary ray origins: the same as the grid's for the same scene.
    float rayOffset() const;
    // The nodes a ray may visit before both backends stop it (RAY_OVERFLOW): every node once and
    // a margin, so only a bug can reach it.
    int maxNodeSteps() const { return int(nodes.size()) + 2; }
    // The expected cost of a ray through the tree under the surface area heuristic (node visits
    // plus triangle tests, each weighed 1, per ray that enters the scene's box).
    double sahCost() const;
};

// The corners of an empty child's box (min, -min): inverted, so no ray enters it.
inline constexpr float kBvhEmptyBox = 1e30f;

// The most triangles a leaf may hold (the kernels' nodes keep a leaf's count in 4 bits).
inline constexpr int kBvhMaxLeafSize = 15;

// The deepest tree a build makes: the kernels' traversal stack has this many entries.
inline constexpr int kBvhMaxDepth = 64;

struct BvhOptions {
    int threads = 0;      // 0: all cores
    int maxLeafSize = 4;  // triangles a leaf may hold at most (1 to 15)
};

// Builds the tree on `options.threads` threads; the result is the same whatever the thread count.
// Throws InputError for a scene with non-finite vertices.
Bvh buildBvh(const Scene& scene, const BvhOptions& options = {});

// What is wrong with `bvh` as a tree over `triangleCount` triangles, or "" when nothing is: every
// triangle in exactly one leaf, inner children referring forward to nodes reached once (no cycle,
// no sharing), counts within the list, finite boxes, depth within kBvhMaxDepth, and, with
// `scene`, every child box holding its triangles and inside its parent's.
std::string checkBvh(const Bvh& bvh, size_t triangleCount, const Scene* scene = nullptr);

// The depth of a tree checkBvh accepts: nodes on the longest path from the root to a leaf, and one.
int bvhDepth(const Bvh& bvh);

}  // namespace gpurt
