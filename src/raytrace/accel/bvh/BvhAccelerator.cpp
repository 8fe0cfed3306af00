// The BVH's registry entry: build, the packed sections BVHN (the nodes) and BVHL (the leaves'
// triangle ids), the reader's and writer's checks (checkBvh), turning and rescaling (exact: an
// axis permutation with signs, a power of two).
#include "raytrace/accel/bvh/BvhAccelerator.h"

#include <algorithm>
#include <tuple>

#include "raytrace/accel/SceneBox.h"
#include "raytrace/accel/bvh/BvhCpu.h"
#include "raytrace/accel/bvh/BvhTexels.h"

namespace gpurt {

namespace {

constexpr char kBvhNodes[] = "BVHN";
constexpr char kBvhList[] = "BVHL";
// Bytes of a node in BVHN: two children of (min, max, ref, count).
constexpr size_t kBvhNodeBytes = 2 * (6 * 4 + 4 + 4);

// BVHN: the node count (u64), then each node's two children.
void readNodes(const PackedSection& s, Bvh& bvh, size_t triangles) {
    ByteReader in = s.reader();
    // A tree over n triangles has fewer than n inner nodes (one root over nothing when n is 0).
    const uint64_t n = s.count(in, kBvhNodeBytes, true, std::max<uint64_t>(1, triangles), "BVH nodes");
    if (n == 0) s.fail("section " + s.tag + ": no root node");
    bvh.nodes.resize(size_t(n));
    for (Bvh::Node& node : bvh.nodes)
        for (Bvh::Child& c : node.child) {
            c.min = in.vec3();
            c.max = in.vec3();
            c.ref = static_cast<int32_t>(in.u32());
            c.count = in.u32();
            if (c.count > uint32_t(kBvhMaxLeafSize))
                s.fail("section " + s.tag + ": a leaf of " + std::to_string(c.count) + " triangles (at most " +
                       std::to_string(kBvhMaxLeafSize) + ")");
        }
}

// BVHL: one u32 triangle id per triangle of the scene, in leaf order.
void readList(const PackedSection& s, Bvh& bvh, size_t triangles) {
    if (s.size() != uint64_t(triangles) * 4)
        s.fail("section " + s.tag + ": " + std::to_string(s.size()) + " bytes, expected " +
               std::to_string(uint64_t(triangles) * 4) + " for the " + std::to_string(triangles) + " triangles");
    ByteReader in = s.reader();
    bvh.triangles.resize(triangles);
    in.u32s(bvh.triangles);
}

void checkTree(const FileLoc& file, const Scene& scene, const Bvh& bvh) {
    const std::string problem = checkBvh(bvh, scene.triangles.size(), &scene);
    if (!problem.empty()) failAt(file, "bvh: " + problem);
}

class BvhStructure final : public AccelStructure {
  public:
    explicit BvhStructure(Bvh bvh) : bvh_(std::move(bvh)) {}
    const Bvh& bvh() const { return bvh_; }

    const AcceleratorInfo& accelerator() const override { return bvhAccelerator(); }
    float rayOffset() const override { return bvh_.rayOffset(); }
    std::string summary() const override {
        return "bvh, " + std::to_string(bvh_.nodes.size()) + " nodes, depth " + std::to_string(bvh_.depth);
    }
    std::vector<std::pair<std::string, double>> figures() const override {
        return {{"nodes", double(bvh_.nodes.size())}, {"depth", double(bvh_.depth)}};
    }
    std::shared_ptr<const AccelStructure> turnedUp(UpAxis axis) const override {
        Bvh b = bvh_;
        b.turnUp(axis);
        return makeStructure(std::move(b));
    }
    std::shared_ptr<const AccelStructure> rescaled(int exponent) const override {
        Bvh b = bvh_;
        b.rescale(exponent);
        return makeStructure(std::move(b));
    }
    std::unique_ptr<CpuAccelerator> cpu(const Scene& scene) const override {
        return std::make_unique<BvhCpu>(scene, bvh_);
    }
    std::vector<TextureTexels> texels(const Scene& scene) const override { return sceneTextureTexels(scene, bvh_); }
    void validate(const FileLoc& file, const Scene& scene) const override { checkTree(file, scene, bvh_); }
    void pack(std::string_view tag, ByteWriter& out) const override {
        if (tag == kBvhNodes) {
            out.u64(bvh_.nodes.size());
            for (const Bvh::Node& node : bvh_.nodes)
                for (const Bvh::Child& c : node.child) {
                    out.vec3(c.min);
                    out.vec3(c.max);
                    out.u32(static_cast<uint32_t>(c.ref));
                    out.u32(c.count);
                }
        } else if (tag == kBvhList) {
            out.u32s(bvh_.triangles);
        }
    }

  private:
    Bvh bvh_;
};

std::shared_ptr<const AccelStructure> build(const Scene& scene, const AccelOptions& options) {
    return makeStructure(buildBvh(scene, BvhOptions{options.threads}));
}

std::shared_ptr<const AccelStructure> unpack(std::span<const PackedSection> sections, const Scene& scene) {
    Bvh bvh;
    readNodes(sections[0], bvh, scene.triangles.size());
    readList(sections[1], bvh, scene.triangles.size());
    checkTree(sections[0].file, scene, bvh);
    // The box is the scene's (sceneBox), the depth what checkBvh found: derived, not stored.
    std::tie(bvh.min, bvh.max) = sceneBox(scene);
    bvh.depth = bvhDepth(bvh);
    return makeStructure(std::move(bvh));
}

std::shared_ptr<const AccelStructure> reuse(std::shared_ptr<const AccelStructure> packed, const AccelOptions&) {
    return packed;
}

}  // namespace

std::shared_ptr<const AccelStructure> makeStructure(Bvh bvh) { return std::make_shared<BvhStructure>(std::move(bvh)); }

const Bvh* bvhOf(const AccelStructure* structure) {
    const auto* b = dynamic_cast<const BvhStructure*>(structure);
    return b ? &b->bvh() : nullptr;
}

const AcceleratorInfo& bvhAccelerator() {
    // A node's visit costs 2.6 triangle tests on the gl backend (the same fit as the grid's cell,
    // grid/GridAccelerator.cpp).
    static const AcceleratorInfo info{"bvh",
                                      "bounding volume hierarchy, binned SAH",
                                      {kBvhNodes, kBvhList},
                                      2.6,
                                      build,
                                      unpack,
                                      reuse};
    return info;
}

}  // namespace gpurt
