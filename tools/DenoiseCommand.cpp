// `gpurt denoise COLOR --albedo A --normal N [--depth D] [--variance V] -o OUT`: the filter of render
// --denoise (raytrace/denoise) on files, as Open Image Denoise's oidnDenoise does: a stitched farm
// render's AOVs, or another renderer's.
#include "Commands.h"
#include "CommonOptions.h"

#include "image/AtomicFile.h"
#include "image/Colour.h"
#include "image/ExrIO.h"
#include "image/ImageIO.h"
#include "image/InputError.h"
#include "raytrace/denoise/DenoiseGl.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace gpurt {

namespace {

struct DenoiseOptions {
    DenoiseFiles files;
    std::string output;
    std::string backend = "gl";
    std::string exposure = "0", tonemap = "aces";
    ContextOptions context;
};

int runDenoise(const DenoiseOptions& o) {
    const std::string ext = lowerExtension(o.output);
    if (ext != ".png" && ext != ".exr" && ext != ".pfm")
        throw InputError("-o: " + o.output + " is not a .png, .exr or .pfm file");
    ColourSettings colour;
    colour.exposure = parseFiniteFloat("--exposure", o.exposure);
    if (std::abs(colour.exposure) > 64.0f) throw InputError("--exposure: " + o.exposure + " is outside [-64, 64]");
    if (!parseToneMap(o.tonemap, colour.toneMap)) throw InputError("--tonemap: '" + o.tonemap + "' is not aces, reinhard or clamp");
    const DenoiseImages in = readDenoiseImages(o.files);
    const Backend backend = o.backend == "cpu" ? Backend::Cpu : Backend::Gl;
    std::optional<GLContext> context;
    if (backend == Backend::Gl) context.emplace(o.context.makeContext());
    const std::vector<glm::vec3> out = denoise(backend, in);
    AtomicFileSet files;
    if (ext == ".png") {
        writePng(files, o.output, in.width, in.height, toneMapImage(out, colour));
    } else {  // linear, times 2^EV as render's EXR
        const float scale = exposureScale(colour.exposure);
        std::vector<float> flat;
        flat.reserve(out.size() * 3);
        for (const glm::vec3& c : out) flat.insert(flat.end(), {c.x * scale, c.y * scale, c.z * scale});
        if (ext == ".exr") writeExr(files, o.output, in.width, in.height, exrLayout("exr"), flat);
        else writePfm(files, o.output, in.width, in.height, 3, flat);
    }
    files.commit();
    return 0;
}

}  // namespace

void addDenoiseCommand(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<DenoiseOptions>();
    auto* cmd = app.add_subcommand(
        "denoise", "Denoise a path-traced image with its albedo, shading normal (and depth, variance) images, as render "
                   "--denoise does");
    cmd->add_option("color", o->files.color, "The noisy colour: EXR or PFM (render's color AOV)")->required()->check(kNotEmpty);
    cmd->add_option("--albedo", o->files.albedo, "The albedo image (render's albedo AOV)")->required()->check(kNotEmpty);
    cmd->add_option("--normal", o->files.normal, "The shading normal image (render's shading_normal AOV)")
        ->required()
        ->check(kNotEmpty);
    cmd->add_option("--depth", o->files.depth, "The depth image (render's depth AOV; +inf: no hit)")->check(kNotEmpty);
    cmd->add_option("--variance", o->files.variance,
                    "The variance of each pixel's mean (render's variance AOV; without it, estimated from the "
                    "neighbourhood)")
        ->check(kNotEmpty);
    cmd->add_option("-o,--output", o->output, "Output: .png (tone mapped sRGB), .exr (half float) or .pfm (linear)")
        ->required()
        ->check(kNotEmpty);
    cmd->add_option("--backend", o->backend, "gl (stream kernels, default) or cpu (same filter in C++)")
        ->check(CLI::IsMember({"gl", "cpu"}));
    cmd->add_option("--exposure", o->exposure, "Exposure in EV of the output (as render's)");
    cmd->add_option("--tonemap", o->tonemap, "Tone map of a PNG output: aces (default), reinhard or clamp");
    addContextOptions(*cmd, o->context);
    cmd->callback([&run, o] { run = [o] { return runDenoise(*o); }; });
}

}  // namespace gpurt
