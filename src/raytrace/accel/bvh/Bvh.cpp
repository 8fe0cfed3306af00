// The BVH build: top-down, each range of triangles split where the binned surface area heuristic
// (Wald 2007: 16 bins of the centroids' box on each axis) is cheapest, into a leaf where that is
// cheaper than any split (and the range at most maxLeafSize), at the middle of the range where
// the centroids cannot be told apart (all in one point) or the tree grows too deep. The two halves
// of the biggest ranges are built on two threads, each into its own node list, spliced back in
// the order a single thread makes them, so the tree does not depend on the thread count.
#include "raytrace/accel/bvh/Bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <limits>
#include <optional>

#include "image/InputError.h"
#include "base/LargeArray.h"
#include "base/Parallel.h"
#include "raytrace/accel/SceneBox.h"
#include "raytrace/common/Vec3.h"

namespace gpurt {

namespace {

constexpr int kBins = 16;
constexpr float kTraversalCost = 1.0f;  // a node visit, in triangle tests
constexpr float kIntersectCost = 1.0f;
// Past this depth ranges split at their middle, which adds at most log2(2^24) more levels.
constexpr int kMedianDepth = kBvhMaxDepth - 26;
// Ranges at least this big have their halves built on two threads (while threads are left).
constexpr uint32_t kParallelRange = 32768;

struct Box {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    void extend(glm::vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void extend(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return lo.x > hi.x; }
    float area() const {
        if (empty()) return 0.0f;
        const glm::vec3 e = hi - lo;
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

// A triangle as the build sees it: its box, its box's centre and its id. The build reorders these
// records themselves (not ids into them), so that each pass reads its range in memory order.
struct PrimRef {
    Box box;
    glm::vec3 centroid;
    uint32_t id;
};

// The box stored for a child: its triangles' box widened by a few parts per million of the
// coordinates, so that rounding in the slab test never loses a hit the triangle test finds.
Bvh::Child storedChild(const Box& b, int32_t ref, uint32_t count) {
    if (b.empty()) return {glm::vec3(kBvhEmptyBox), glm::vec3(-kBvhEmptyBox), -1, 0};
    const glm::vec3 padLo = glm::abs(b.lo) * 1e-6f + glm::vec3(1e-30f);
    const glm::vec3 padHi = glm::abs(b.hi) * 1e-6f + glm::vec3(1e-30f);
    return {b.lo - padLo, b.hi + padHi, ref, count};
}

// The boxes of a range of triangles: of the triangles, and of their centres.
struct RangeBoxes {
    Box box, centroids;
};

class Builder {
  public:
    Builder(const Scene& scene, const BvhOptions& options)
        : maxLeaf_(std::clamp(options.maxLeafSize, 1, kBvhMaxLeafSize)), threads_(resolveThreads(options.threads)) {
        const size_t n = scene.triangles.size();
        prims_.resize(n);
        parallelChunks(n, 65536, threads_, [&](size_t begin, size_t end, size_t) {
            for (size_t k = begin; k < end; ++k) {
                const Triangle& t = scene.triangles[k];
                Box b;
                b.extend(t.v0);
                b.extend(t.v1);
                b.extend(t.v2);
                prims_[k] = {b, 0.5f * (b.lo + b.hi), uint32_t(k)};
            }
        });
    }

    Bvh build() {
        Bvh bvh;
        const uint32_t n = uint32_t(prims_.size());
        const RangeBoxes all = rangeBoxes(0, n);
        if (n == 0) {
            bvh.nodes.push_back({{storedChild(Box{}, -1, 0), storedChild(Box{}, -1, 0)}});
        } else if (n <= uint32_t(maxLeaf_)) {
            bvh.nodes.push_back({{storedChild(all.box, 0, n), storedChild(Box{}, -1, 0)}});
            bvh.depth = 2;
        } else {
            int depth = 0;
            bvh.nodes.reserve(n - 1);  // a tree of n leaf triangles has at most n - 1 inner nodes
            subtree(bvh.nodes, 0, n, all, 1, threads_, depth);
            bvh.depth = depth;
        }
        bvh.triangles.resize(n);
        for (uint32_t k = 0; k < n; ++k) bvh.triangles[k] = prims_[k].id;
        return bvh;
    }

  private:
    RangeBoxes rangeBoxes(uint32_t begin, uint32_t end) const {
        RangeBoxes r;
        for (uint32_t k = begin; k < end; ++k) {
            r.box.extend(prims_[k].box);
            r.centroids.extend(prims_[k].centroid);
        }
        return r;
    }

    // The bin of a centre on an axis, for a range whose centres start at lo, kBins / extent scale.
    static int binOf(float c, float lo, float scale) { return std::min(kBins - 1, int((c - lo) * scale)); }

    struct Split {
        int axis = -1;
        int bin = 0;  // the left side holds bins 0..bin
        float cost = std::numeric_limits<float>::infinity();
        RangeBoxes left, right;  // the boxes of the two sides (the bins' unions: exact)
    };

    // The cheapest binned split of [begin, end) whose centroids span `cb`.
    Split bestSplit(uint32_t begin, uint32_t end, const Box& cb) const {
        Split best;
        const glm::vec3 extent = cb.hi - cb.lo;
        std::array<std::array<RangeBoxes, kBins>, 3> bins;
        std::array<std::array<uint32_t, kBins>, 3> counts{};
        glm::vec3 scale;
        for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? float(kBins) / extent[a] : 0.0f;
        for (uint32_t k = begin; k < end; ++k) {
            const PrimRef& p = prims_[k];
            for (int a = 0; a < 3; ++a) {
                if (scale[a] == 0.0f) continue;
                const int b = binOf(p.centroid[a], cb.lo[a], scale[a]);
                bins[a][b].box.extend(p.box);
                bins[a][b].centroids.extend(p.centroid);
                counts[a][b] += 1;
            }
        }
        for (int a = 0; a < 3; ++a) {
            if (scale[a] == 0.0f) continue;
            std::array<float, kBins> rightCost{};
            Box right;
            uint32_t rightCount = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.extend(bins[a][b].box);
                rightCount += counts[a][b];
                rightCost[b] = right.area() * float(rightCount);
            }
            Box left;
            uint32_t leftCount = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                left.extend(bins[a][b].box);
                leftCount += counts[a][b];
                if (leftCount == 0 || leftCount == end - begin) continue;
                const float cost = left.area() * float(leftCount) + rightCost[b + 1];
                if (cost < best.cost) {
                    best.axis = a;
                    best.bin = b;
                    best.cost = cost;
                }
            }
        }
        if (best.axis >= 0)
            for (int b = 0; b < kBins; ++b) {
                RangeBoxes& side = b <= best.bin ? best.left : best.right;
                side.box.extend(bins[best.axis][b].box);
                side.centroids.extend(bins[best.axis][b].centroids);
            }
        return best;
    }

    // The child over [begin, end) with boxes `boxes`: a leaf, or an inner node appended to `out`
    // (with its subtree after it). `depth` is the child's level; deepest gets the tree's depth.
    Bvh::Child subtree(Bvh::BvhNodes& out, uint32_t begin, uint32_t end, const RangeBoxes& boxes, int depth,
                       int threads, int& deepest) {
        const uint32_t count = end - begin;
        const Box& box = boxes.box;
        const Box& cb = boxes.centroids;
        uint32_t mid = begin + count / 2;
        std::optional<RangeBoxes> leftBoxes, rightBoxes;  // known when a binned split made them
        const bool spread = cb.hi.x > cb.lo.x || cb.hi.y > cb.lo.y || cb.hi.z > cb.lo.z;
        if (spread && depth < kMedianDepth) {
            const Split s = bestSplit(begin, end, cb);
            const float area = box.area();
            const float splitCost = kTraversalCost + (area > 0.0f ? s.cost / area : float(count)) * kIntersectCost;
            if (count <= uint32_t(maxLeaf_) && float(count) * kIntersectCost <= splitCost) return leaf(begin, count, box, depth, deepest);
            if (s.axis >= 0) {
                const float lo = cb.lo[s.axis], scale = float(kBins) / (cb.hi[s.axis] - cb.lo[s.axis]);
                const auto first = prims_.begin() + begin, last = prims_.begin() + end;
                mid = uint32_t(std::partition(first, last, [&](const PrimRef& p) {
                          return binOf(p.centroid[s.axis], lo, scale) <= s.bin;
                      }) - prims_.begin());
                if (mid == begin || mid == end) mid = begin + count / 2;
                else leftBoxes = s.left, rightBoxes = s.right;
            }
        } else if (count <= uint32_t(maxLeaf_)) {
            return leaf(begin, count, box, depth, deepest);
        } else if (spread) {
            // Too deep for the heuristic: the object median on the centroids' longest axis.
            const glm::vec3 e = cb.hi - cb.lo;
            const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
            std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                             [&](const PrimRef& a, const PrimRef& b) { return a.centroid[axis] < b.centroid[axis]; });
        }
        const int32_t index = int32_t(out.size());
        out.emplace_back();
        if (!leftBoxes) leftBoxes = rangeBoxes(begin, mid), rightBoxes = rangeBoxes(mid, end);
        Bvh::Child left, right;
        if (threads > 1 && count >= kParallelRange) {
            Bvh::BvhNodes leftNodes, rightNodes;
            leftNodes.reserve(mid - begin);
            rightNodes.reserve(end - mid);
            int leftDepth = 0, rightDepth = 0;
            auto leftTask = std::async(std::launch::async, [&] {
                return subtree(leftNodes, begin, mid, *leftBoxes, depth + 1, threads / 2, leftDepth);
            });
            right = subtree(rightNodes, mid, end, *rightBoxes, depth + 1, threads - threads / 2, rightDepth);
            left = leftTask.get();
            splice(out, leftNodes, left);
            splice(out, rightNodes, right);
            deepest = std::max({deepest, leftDepth, rightDepth});
        } else {
            left = subtree(out, begin, mid, *leftBoxes, depth + 1, 1, deepest);
            right = subtree(out, mid, end, *rightBoxes, depth + 1, 1, deepest);
        }
        out[size_t(index)] = {{left, right}};
        return storedChild(box, index, 0);
    }

    Bvh::Child leaf(uint32_t begin, uint32_t count, const Box& box, int depth, int& deepest) {
        deepest = std::max(deepest, depth);
        return storedChild(box, int32_t(begin), count);
    }

    // Appends `nodes` (a subtree built on its own, its root at 0) to `out`, moving its node
    // references, and `child`'s, by where it lands.
    static void splice(Bvh::BvhNodes& out, const Bvh::BvhNodes& nodes, Bvh::Child& child) {
        const int32_t offset = int32_t(out.size());
        out.insert(out.end(), nodes.begin(), nodes.end());
        for (size_t k = size_t(offset); k < out.size(); ++k)
            for (Bvh::Child& c : out[k].child)
                if (c.count == 0 && c.ref >= 0) c.ref += offset;
        if (child.count == 0 && child.ref >= 0) child.ref += offset;
    }

    int maxLeaf_;
    int threads_;
    LargeArray<PrimRef> prims_;  // in leaf order once built
};

}  // namespace

void Bvh::quantisation(glm::vec3& origin, glm::vec3& step) const {
    glm::vec3 lo = min, hi = max;
    for (const Child& c : nodes.front().child)
        if (c.ref >= 0) {
            lo = glm::min(lo, c.min);
            hi = glm::max(hi, c.max);
        }
    origin = lo;
    step = (hi - lo) / 65535.0f;
}

float Bvh::rayOffset() const { return sceneRayOffset(min, max); }

namespace {

// Applies f to the corners of box [lo, hi] and makes the result a box again (f maps each axis to
// an axis, with or without its sign: exact).
template <typename F>
void mapBox(glm::vec3& lo, glm::vec3& hi, F f) {
    const glm::vec3 a = f(lo), b = f(hi);
    lo = glm::min(a, b);
    hi = glm::max(a, b);
}

template <typename F>
void mapBoxes(Bvh& bvh, F f) {
    mapBox(bvh.min, bvh.max, f);
    for (Bvh::Node& node : bvh.nodes)
        for (Bvh::Child& child : node.child)
            if (child.count > 0 || child.ref > 0) mapBox(child.min, child.max, f);  // an empty child keeps its empty box
}

}  // namespace

void Bvh::turnUp(UpAxis axis) {
    if (axis != UpAxis::PosY) mapBoxes(*this, [axis](glm::vec3 v) { return upAxisToY(v, axis); });
}

void Bvh::rescale(int exponent) {
    if (exponent == 0) return;
    mapBoxes(*this, [exponent](glm::vec3 v) { return rescalePoint(v, exponent); });
}

double Bvh::sahCost() const {
    auto area = [](const Child& c) {
        if (c.ref < 0 && c.count == 0) return 0.0;
        const glm::dvec3 e = glm::dvec3(c.max) - glm::dvec3(c.min);
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    };
    const glm::dvec3 e = glm::dvec3(max) - glm::dvec3(min);
    const double root = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    if (!(root > 0.0)) return 0.0;
    double cost = kTraversalCost;  // the root's visit
    for (const Node& node : nodes)
        for (const Child& c : node.child)
            cost += area(c) / root * (c.count > 0 ? double(c.count) * kIntersectCost : kTraversalCost);
    return cost;
}

Bvh buildBvh(const Scene& scene, const BvhOptions& options) {
    const auto [lo, hi] = sceneBox(scene);  // throws for non-finite vertices
    Bvh bvh = Builder(scene, options).build();
    bvh.min = lo;
    bvh.max = hi;
    return bvh;
}

int bvhDepth(const Bvh& bvh) {
    std::vector<int> level(bvh.nodes.size(), 1);
    int depth = 1;
    for (size_t n = 0; n < bvh.nodes.size(); ++n)
        for (const Bvh::Child& c : bvh.nodes[n].child) {
            if (c.count > 0) depth = std::max(depth, level[n] + 1);
            else if (c.ref > int32_t(n) && size_t(c.ref) < bvh.nodes.size()) level[size_t(c.ref)] = level[n] + 1;
        }
    return depth;
}

std::string checkBvh(const Bvh& bvh, size_t triangleCount, const Scene* scene) {
    if (bvh.nodes.empty()) return "no root node";
    if (bvh.triangles.size() != triangleCount)
        return std::to_string(bvh.triangles.size()) + " leaf triangles for " + std::to_string(triangleCount) + " triangles";
    std::vector<uint8_t> seen(triangleCount, 0);
    std::vector<uint8_t> reached(bvh.nodes.size(), 0);
    std::vector<int> level(bvh.nodes.size(), 0);
    reached[0] = 1;
    level[0] = 1;
    int depth = 1;
    for (size_t n = 0; n < bvh.nodes.size(); ++n) {
        if (!reached[n]) return "node " + std::to_string(n) + " is not reached from the root";
        for (const Bvh::Child& c : bvh.nodes[n].child) {
            const std::string where = "node " + std::to_string(n);
            const bool none = c.ref < 0 && c.count == 0;
            if (!none) {
                for (int a = 0; a < 3; ++a)
                    if (!std::isfinite(c.min[a]) || !std::isfinite(c.max[a]) || c.min[a] > c.max[a])
                        return where + ": a child's box is not finite or inverted";
            }
            if (c.count > 0) {
                if (c.ref < 0 || uint64_t(c.ref) + c.count > triangleCount)
                    return where + ": a leaf's triangles run past the list's end";
                for (uint32_t k = uint32_t(c.ref); k < uint32_t(c.ref) + c.count; ++k) {
                    const uint32_t id = bvh.triangles[k];
                    if (id >= triangleCount) return where + ": triangle id " + std::to_string(id) + " out of range";
                    if (seen[id]++) return "triangle " + std::to_string(id) + " is in more than one leaf";
                    if (scene) {
                        const Triangle& t = scene->triangles[id];
                        for (const glm::vec3& v : {t.v0, t.v1, t.v2})
                            if (glm::any(glm::lessThan(v, c.min)) || glm::any(glm::greaterThan(v, c.max)))
                                return where + ": triangle " + std::to_string(id) + " sticks out of its leaf's box";
                    }
                }
                depth = std::max(depth, level[n] + 1);
            } else if (!none) {
                if (c.ref <= int32_t(n) || size_t(c.ref) >= bvh.nodes.size())
                    return where + ": child node " + std::to_string(c.ref) + " is not a later node";
                if (reached[size_t(c.ref)]++) return "node " + std::to_string(c.ref) + " has two parents";
                level[size_t(c.ref)] = level[n] + 1;
                if (scene) {
                    for (const Bvh::Child& g : bvh.nodes[size_t(c.ref)].child)
                        if (!(g.ref < 0 && g.count == 0) &&
                            (glm::any(glm::lessThan(g.min, c.min)) || glm::any(glm::greaterThan(g.max, c.max))))
                            return "node " + std::to_string(c.ref) + ": a child's box is not inside its parent's";
                }
            } else if (c.ref != -1) {
                return where + ": an empty child with reference " + std::to_string(c.ref);
            }
        }
    }
    for (size_t id = 0; id < triangleCount; ++id)
        if (!seen[id]) return "triangle " + std::to_string(id) + " is in no leaf";
    if (depth > kBvhMaxDepth) return "depth " + std::to_string(depth) + " exceeds " + std::to_string(kBvhMaxDepth);
    return "";
}

}  // namespace gpurt
