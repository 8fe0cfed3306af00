// The accelerator registry: each acceleration structure declares itself once (its folder's
// <Name>Accelerator.cpp: name, help, packed-format sections, how to build, unpack, turn,
// rescale, trace on the cpu and lay out its textures), and Registry.cpp lists it in one line;
// its gl form is one line of GlRegistry.cpp. `--accel`, its help, auto's estimate, the loader,
// the packer and the benchmarks read the registry, so a new structure touches nothing else.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raytrace/accel/CpuAccelerator.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "raytrace/common/PackedBytes.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "scene/Scene.h"

namespace gpurt {

class AccelStructure;

// What the command line asks of the builds; each accelerator reads what is its.
struct AccelOptions {
    int threads = 0;   // 0: all cores
    GridOptions grid;  // the grid's: --lambda, --skip, pack's --grid
    // The options ask for a grid built from the triangles (--lambda given): a packed grid does
    // not serve.
    bool newGrid = false;
};

struct AcceleratorInfo {
    std::string_view name;  // --accel NAME
    std::string_view help;  // one phrase for --help
    // Its packed-format sections (four-character tags), in the order the writer stores them.
    std::vector<std::string_view> sections;
    // The cost of one visit (a cell, a node) on the gl backend in triangle tests: auto's estimate
    // (accel/Acceleration.cpp) weighs the visits of the cpu traversal with it.
    double visitCost;
    // Builds the structure over the scene's triangles; InputError for options it refuses.
    std::shared_ptr<const AccelStructure> (*build)(const Scene& scene, const AccelOptions& options);
    // Reads the structure from its sections (all of `sections`, in that order) and checks it
    // against the scene, whose own sections were checked: InputError naming the file.
    std::shared_ptr<const AccelStructure> (*unpack)(std::span<const PackedSection> sections, const Scene& scene);
    // A packed structure as `options` want it, or null where they ask for one built anew.
    std::shared_ptr<const AccelStructure> (*reuse)(std::shared_ptr<const AccelStructure> packed,
                                                   const AccelOptions& options);
};

// A structure built (or read) over one scene.
class AccelStructure {
  public:
    virtual ~AccelStructure() = default;
    virtual const AcceleratorInfo& accelerator() const = 0;
    // Offset of secondary and shadow ray origins along the normal.
    virtual float rayOffset() const = 0;
    // One line for the statistics: "grid 8x8x8", "bvh, 301 nodes, depth 12".
    virtual std::string summary() const = 0;
    // Figures `--stats=json` reports under the accelerator's name (none: nothing reported).
    virtual std::vector<std::pair<std::string, double>> figures() const = 0;
    // The same structure for its scene turned by rotateUpToY(axis), or rescaled by 2^-exponent
    // (rescaleScene); null where it cannot follow (it is then built again for the new scene).
    virtual std::shared_ptr<const AccelStructure> turnedUp(UpAxis axis) const = 0;
    virtual std::shared_ptr<const AccelStructure> rescaled(int exponent) const = 0;
    // The cpu backend's traversal of it; the scene must outlive the result.
    virtual std::unique_ptr<CpuAccelerator> cpu(const Scene& scene) const = 0;
    // Its scene textures (gpurt pack prints their sizes and --dump writes them).
    virtual std::vector<TextureTexels> texels(const Scene& scene) const = 0;
    // Refuses (InputError "FILE: ...") a structure the reader would: the writer checks with it.
    virtual void validate(const FileLoc& file, const Scene& scene) const = 0;
    // Writes section `tag`, one of accelerator().sections.
    virtual void pack(std::string_view tag, ByteWriter& out) const = 0;
};

// The accelerators in registry order (auto keeps the first of equal estimates).
const std::vector<const AcceleratorInfo*>& accelerators();
// The one named `name`, or null.
const AcceleratorInfo* findAccelerator(std::string_view name);
// Their names, "grid|bvh".
std::string acceleratorNames(std::string_view separator);

// Each accelerator's entry, defined in its folder.
const AcceleratorInfo& gridAccelerator();
const AcceleratorInfo& bvhAccelerator();

}  // namespace gpurt
