// `gpurt pack SCENE -o OUT.gpscene`: builds the uniform grid once and writes the scene with it as a
// packed file (docs/PACKED_FORMAT.md), prints what was packed, and with --dump writes the scene
// textures as PFM images and the grid's occupancy as PNG projections. CPU only: no GL context.
#include "Commands.h"
#include "CommonOptions.h"
#include "Progress.h"

#include "image/ImageIO.h"
#include "image/InputError.h"
#include "raytrace/scene/PackedScene.h"
#include "raytrace/scene/SceneLoader.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/bvh/BvhAccelerator.h"
#include "raytrace/accel/grid/GridAccelerator.h"
#include "raytrace/accel/grid/GridTexels.h"
#include "raytrace/camera/Camera.h"
#include "raytrace/accel/Acceleration.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "scene/SceneFile.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace gpurt {

namespace {

struct PackOptions {
    std::string scene;
    std::string output;
    std::string grid = "auto";
    std::string accel = "auto";
    float lambda = GridOptions{}.lambda;
    bool lambdaGiven = false;
    std::string dump;
    int threads = 0;
    std::string upAxis;  // --up-axis
    ProgressCliOptions progress;
};

// The largest side of an occupancy picture.
constexpr int kMaxOccupancySide = 8192;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// "auto" -> none; "NX,NY,NZ" -> the resolution (buildGrid checks the range).
std::optional<glm::ivec3> parseGrid(const std::string& text) {
    if (text == "auto") return std::nullopt;
    glm::ivec3 r(0);
    size_t at = 0;
    for (int a = 0; a < 3; ++a) {
        const size_t end = a < 2 ? text.find(',', at) : text.size();
        const std::string part = end == std::string::npos ? "" : text.substr(at, end - at);
        if (part.empty() || part.size() > 9 ||
            part.find_first_not_of("0123456789") != std::string::npos)
            throw InputError("--grid: '" + text + "' is not auto or three integers NX,NY,NZ");
        r[a] = std::stoi(part);
        at = end + 1;
    }
    return r;
}

// The PFM of a texture: its texels in upload order (row 0 first), so that the file's first
// scanline is texture row 0, as a PFM's first scanline is its bottom row. Two-channel texels get
// a zero third channel; four-channel ones are split into NAME.pfm (xyz) and NAME_w.pfm (w).
void dumpTexture(const std::filesystem::path& dir, const TextureTexels& t) {
    const size_t texels = t.texels();
    auto value = [&](size_t texel, int channel) {
        const size_t i = texel * size_t(t.channels) + size_t(channel);
        return t.isFloat ? t.floats[i] : float(t.uints[i]);
    };
    // writePfm takes rows top first and stores them bottom first.
    auto topFirstTexel = [&](size_t k) {
        const size_t row = k / size_t(t.width), column = k % size_t(t.width);
        return (size_t(t.rows) - 1 - row) * size_t(t.width) + column;
    };
    if (t.channels == 1) {
        std::vector<float> image(texels);
        for (size_t k = 0; k < texels; ++k) image[k] = value(topFirstTexel(k), 0);
        writePfm(dir / (t.name + ".pfm"), t.width, t.rows, 1, image);
        return;
    }
    std::vector<float> rgb(texels * 3, 0.0f), w;
    if (t.channels == 4) w.resize(texels);
    for (size_t k = 0; k < texels; ++k) {
        const size_t src = topFirstTexel(k);
        for (int c = 0; c < std::min(t.channels, 3); ++c) rgb[k * 3 + size_t(c)] = value(src, c);
        if (t.channels == 4) w[k] = value(src, 3);
    }
    writePfm(dir / (t.name + ".pfm"), t.width, t.rows, 3, rgb);
    if (t.channels == 4) writePfm(dir / (t.name + "_w.pfm"), t.width, t.rows, 1, w);
}

// occupancy_AXIS.png: the longest cell list along AXIS for each cell of the other two, black
// for none, grey up to white for the grid's longest list; small grids are enlarged so the larger
// side has at least 256 pixels, and huge ones reduced to at most kMaxOccupancySide. Horizontal and
// vertical axes: z -> (x, y), x -> (z, y), y -> (x, z); the vertical axis grows upwards.
void dumpOccupancy(const std::filesystem::path& dir, const UniformGrid& grid, uint32_t longest) {
    const char* names[3] = {"x", "y", "z"};
    const int horizontal[3] = {2, 0, 0}, vertical[3] = {1, 2, 1};
    for (int axis : {2, 0, 1}) {
        const int h = horizontal[axis], v = vertical[axis];
        const int w = grid.resolution[h], rows = grid.resolution[v];
        std::vector<uint32_t> projection(size_t(w) * size_t(rows), 0);
        glm::ivec3 cell;
        for (cell.z = 0; cell.z < grid.resolution.z; ++cell.z)
            for (cell.y = 0; cell.y < grid.resolution.y; ++cell.y)
                for (cell.x = 0; cell.x < grid.resolution.x; ++cell.x) {
                    const size_t c = size_t(grid.cellIndex(cell));
                    const uint32_t length = grid.cellStart[c + 1] - grid.cellStart[c];
                    uint32_t& p =
                        projection[size_t(rows - 1 - cell[v]) * size_t(w) + size_t(cell[h])];
                    p = std::max(p, length);
                }
        // Enlarged by `scale` (small grids), or each pixel the maximum of `shrink` x `shrink`
        // cells (grids wider than a PNG should be; libpng refuses more than 10^6 pixels a row).
        const int scale = std::max(1, 256 / std::max(w, rows));
        const int shrink = (std::max(w, rows) + kMaxOccupancySide - 1) / kMaxOccupancySide;
        const int imageW = (w + shrink - 1) / shrink * scale;
        const int imageH = (rows + shrink - 1) / shrink * scale;
        std::vector<glm::vec3> image(size_t(imageW) * size_t(imageH));
        for (int y = 0; y < rows; ++y)
            for (int x = 0; x < w; ++x) {
                const uint32_t length = projection[size_t(y) * size_t(w) + size_t(x)];
                const float grey =
                    length == 0 ? 0.0f : 0.02f + 0.98f * float(length) / float(longest);
                for (int dy = 0; dy < scale; ++dy)
                    for (int dx = 0; dx < scale; ++dx) {
                        glm::vec3& pixel = image[size_t(y / shrink * scale + dy) * size_t(imageW) +
                                                 size_t(x / shrink * scale + dx)];
                        pixel = glm::max(pixel, glm::vec3(grey));
                    }
            }
        writePng(dir / (std::string("occupancy_") + names[axis] + ".png"), imageW, imageH, image);
    }
}

// The grid's options from --grid and --lambda, and the output's and --dump's folders, checked
// before anything is read or written.
GridOptions checkedOptions(const PackOptions& o) {
    GridOptions gridOptions;
    gridOptions.resolution = parseGrid(o.grid);
    gridOptions.lambda = o.lambda;
    gridOptions.threads = o.threads;
    if (gridOptions.resolution && o.lambdaGiven)
        throw InputError("--lambda: only for --grid auto (the grid is given as " + o.grid + ")");
    if (o.accel != "grid" && o.accel != "auto" && (gridOptions.resolution || o.lambdaGiven))
        throw InputError(std::string(gridOptions.resolution ? "--grid" : "--lambda") + ": only with --accel grid or auto");
    // The output's folder must exist before --dump writes anything.
    const std::filesystem::path outputFolder = std::filesystem::absolute(o.output).parent_path();
    if (!std::filesystem::is_directory(outputFolder))
        throw InputError(o.output + ": cannot create file (no folder " + outputFolder.string() +
                         ")");
    if (!o.dump.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.dump, ec);
        if (!std::filesystem::is_directory(o.dump))
            throw InputError("--dump: " + o.dump + ": cannot create folder" +
                             (ec ? " (" + ec.message() + ")" : ""));
    }
    return gridOptions;
}

// The grid's occupancy: non-empty cells and the longest cell list (its length and cell).
struct Occupancy {
    size_t nonEmpty = 0;
    uint32_t longest = 0;
    size_t longestCell = 0;
};

Occupancy occupancyOf(const UniformGrid& grid) {
    Occupancy o;
    for (size_t c = 0; c < grid.cells(); ++c) {
        const uint32_t length = grid.cellStart[c + 1] - grid.cellStart[c];
        o.nonEmpty += length > 0;
        if (length > o.longest) {
            o.longest = length;
            o.longestCell = c;
        }
    }
    return o;
}

// The scene's counts and its textures (name, size, wrap, users).
void printScene(const std::string& name, const Scene& scene) {
    std::printf("scene        %s\n", name.c_str());
    std::printf("triangles    %zu\n", scene.triangles.size());
    // The materials by model (scene/MaterialModels.h): "materials    3 (2 classic, 1 gltf)".
    std::string byModel;
    for (const MaterialModelInfo& model : materialModels()) {
        const auto n = std::count_if(scene.materials.begin(), scene.materials.end(),
                                     [&](const Material& m) { return m.model == model.id; });
        if (n > 0) byModel += (byModel.empty() ? "" : ", ") + std::to_string(n) + " " + std::string(model.name);
    }
    std::printf("materials    %zu%s\n", scene.materials.size(), byModel.empty() ? "" : (" (" + byModel + ")").c_str());
    std::printf("lights       %zu\n", scene.lights.size());
    static const char* const kWrapNames[] = {"repeat", "clamp", "mirror"};
    std::printf("textures     %zu%s\n", scene.textures.size(), scene.textures.empty() ? "" :
                scene.texcoords.empty() ? " (no texture coordinates: not sampled)" : "");
    for (size_t k = 0; k < scene.textures.size(); ++k) {
        const Texture& t = scene.textures[k];
        size_t users = 0;
        for (const Material& m : scene.materials)
            users += m.diffuseTexture == int(k) || m.roughnessTexture.texture == int(k) || m.metallicTexture.texture == int(k) ||
                     m.normalTexture == int(k) || m.emissiveTexture == int(k) || m.occlusionTexture.texture == int(k) ||
                     m.alphaTexture.texture == int(k) || m.transmissionTexture.texture == int(k);
        std::printf("  texture %zu  %s %dx%d, wrap %s/%s, %zu material%s\n", k, printable(t.name).c_str(), t.image.width,
                    t.image.height, kWrapNames[t.wrapS], kWrapNames[t.wrapT], users, users == 1 ? "" : "s");
    }
}

// The grid: resolution, cells, references, the longest list.
void printGrid(const PackOptions& o, const GridOptions& options, const UniformGrid& grid, size_t triangles,
               const Occupancy& occupancy) {
    const glm::ivec3 r = grid.resolution;
    const size_t c = occupancy.longestCell;
    const glm::ivec3 longestAt(int(c % size_t(r.x)), int(c / size_t(r.x) % size_t(r.y)), int(c / (size_t(r.x) * size_t(r.y))));
    if (options.resolution)
        std::printf("grid         %dx%dx%d (given)\n", r.x, r.y, r.z);
    else
        std::printf("grid         %dx%dx%d (auto, lambda %g)\n", r.x, r.y, r.z, double(o.lambda));
    std::printf("cells        %zu, %zu non-empty (%.1f%%)\n", grid.cells(), occupancy.nonEmpty,
                100.0 * double(occupancy.nonEmpty) / double(grid.cells()));
    std::printf("references   %zu, %.2f per triangle\n", grid.cellTriangles.size(),
                triangles ? double(grid.cellTriangles.size()) / double(triangles) : 0.0);
    std::printf("longest list %u triangles (cell %d,%d,%d)\n", occupancy.longest, longestAt.x, longestAt.y,
                longestAt.z);
}

int runPack(const PackOptions& o) {
    // Options first: nothing is read or written for a bad one.
    const GridOptions gridOptions = checkedOptions(o);
    const auto start = std::chrono::steady_clock::now();
    // Three steps: reading the scene, building the grid, encoding and writing.
    ProgressDisplay progress(o.progress.mode());
    LoadedScene loaded = loadScene(o.scene);
    loaded.accel.reset();  // a packed input is repacked with a structure built as asked
    turnSceneUp(loaded, o.upAxis);  // the packed scene is stored turned: its up axis is y
    progress.update(1.0 / 3.0);
    const auto gridStart = std::chrono::steady_clock::now();
    // auto: an explicit --grid NX,NY,NZ asks for the grid; else the estimate chooses, for the
    // scene's camera (the default camera without one).
    const std::string choice = o.accel == "auto" && gridOptions.resolution ? "grid" : o.accel;
    const CameraSpec view = loaded.scene.camera ? *loaded.scene.camera : defaultCamera(loaded.scene.bounds(), 64, 64);
    AccelOptions options;
    options.threads = o.threads;
    options.grid = gridOptions;
    const Acceleration accel = chooseAcceleration(loaded.scene, choice, nullptr, options, makeCamera(view, 64, 64));
    const UniformGrid* grid = gridOf(accel.structure);
    const double gridMs = millisecondsSince(gridStart);
    progress.update(2.0 / 3.0);
    const std::vector<unsigned char> bytes = encodePackedScene(loaded, *accel.structure, o.scene);
    const std::vector<TextureTexels> textures = accel.structure->texels(loaded.scene);
    if (!o.dump.empty()) {
        for (const TextureTexels& t : textures) dumpTexture(o.dump, t);
        if (grid) dumpOccupancy(o.dump, *grid, occupancyOf(*grid).longest);
    }
    writePackedScene(o.output, bytes);
    const double totalMs = millisecondsSince(start);
    progress.finish();

    printScene(o.scene, loaded.scene);
    if (grid) printGrid(o, gridOptions, *grid, loaded.scene.triangles.size(), occupancyOf(*grid));
    else if (const Bvh* bvh = bvhOf(accel.structure))
        std::printf("bvh          %zu nodes, depth %d, SAH cost %.2f\n", bvh->nodes.size(), bvh->depth, bvh->sahCost());
    else std::printf("accel        %s\n", accel.structure->summary().c_str());
    if (!accel.estimate.empty())
        std::printf("accel        %s (auto: estimated cost per ray %s)\n", std::string(accel.name()).c_str(),
                    estimateText(accel).c_str());
    size_t textureBytes = 0;
    for (const TextureTexels& t : textures) {
        std::printf("texture      %-10s %-8s %5dx%-6d %12zu bytes\n", t.name.c_str(),
                    t.formatName(), t.width, t.rows, t.bytes());
        textureBytes += t.bytes();
    }
    std::printf("textures     %zu bytes\n", textureBytes);
    std::printf("file         %s, %zu bytes\n", o.output.c_str(), bytes.size());
    std::printf("build time   %s %.1f ms, total %.1f ms\n", accel.estimate.empty() ? std::string(accel.name()).c_str() : "all structures", gridMs, totalMs);
    if (!o.dump.empty()) std::printf("dump         %s\n", o.dump.c_str());
    return 0;
}

}  // namespace

void addPackCommand(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<PackOptions>();
    auto* cmd = app.add_subcommand(
        "pack", "Build the acceleration structure once and write the scene with it as a packed .gpscene file");
    cmd->add_option("scene", o->scene, "Scene file (.obj, .json, .gltf/.glb, .ply or packed .gpscene)")->required();
    cmd->add_option("-o,--output", o->output, "Output packed scene (.gpscene)")->required();
    cmd->add_option("--accel", o->accel,
                    "Acceleration structure stored: grid, bvh or auto (default: the cheaper by the estimate "
                    "gpurt render --accel auto makes, for the scene's camera; grid when --grid gives a resolution)")
        ->check(CLI::IsMember(accelChoices()));
    cmd->add_option("--grid", o->grid, "Grid resolution: auto (default) or NX,NY,NZ");
    auto* lambda = cmd->add_option("--lambda", o->lambda,
                                   "With --grid auto: cells along the longest axis ~ lambda * "
                                   "N^(1/3) (default 3, as gpurt render)")
                       ->check(CLI::Range(0.01f, 64.0f));
    cmd->add_option("--dump", o->dump,
                    "Also write the scene textures as PFM and the grid occupancy as PNG into DIR");
    cmd->add_option("--threads", o->threads,
                    "Grid build threads (0: all cores; same file either way)")
        ->check(CLI::Range(0, 1024));
    addUpAxisOption(*cmd, o->upAxis);
    o->progress.add(*cmd);
    cmd->callback([&run, o, lambda] {
        o->lambdaGiven = lambda->count() > 0;
        run = [o] { return runPack(*o); };
    });
}

}  // namespace gpurt
