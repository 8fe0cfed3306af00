// The denoiser's images from files (gpurt denoise): EXR or PFM, as render writes its AOVs.
#include "raytrace/denoise/Denoise.h"

#include "image/AtomicFile.h"
#include "image/ExrIO.h"
#include "image/ImageIO.h"
#include "image/InputError.h"

#include <cmath>
#include <filesystem>
#include <string>

namespace gpurt {

namespace {

// The first of the layouts (channel names, each as float then half) the EXR file has.
std::vector<float> readExrChannels(const std::filesystem::path& path, const std::vector<std::vector<std::string>>& names,
                                   int& width, int& height) {
    std::string tried;
    for (const std::vector<std::string>& channels : names) {
        for (bool half : {false, true}) {
            try {
                return readExr(path, ExrLayout{channels, half}, width, height);
            } catch (const InputError& e) {
                const std::string what = e.what();  // another layout may fit; anything else is final
                if (what.find(": no channel ") == std::string::npos && what.find(" is not ") == std::string::npos) throw;
            }
        }
        std::string joined;
        for (const std::string& c : channels) joined += (joined.empty() ? "" : ",") + c;
        tried += (tried.empty() ? "" : " or ") + joined;
    }
    throw InputError(path.string() + ": no channels " + tried + " (float or half)");
}

}  // namespace

std::vector<float> readDenoiseImage(const std::string& file, const std::string& role, int channels, int& width,
                                    int& height) {
    const std::filesystem::path path(file);
    const std::string ext = lowerExtension(path);
    std::vector<float> values;
    if (ext == ".pfm") {
        int c = 0;
        values = readPfm(path, width, height, c);
        if (c != channels)
            throw InputError(file + ": " + std::to_string(c) + " channels, the " + role + " has " +
                             std::to_string(channels));
    } else if (ext == ".exr") {
        const std::vector<std::vector<std::string>> names =
            channels == 1 ? std::vector<std::vector<std::string>>{{"Z"}, {"R"}, {"Y"}}
            : role == "normal" ? std::vector<std::vector<std::string>>{{"X", "Y", "Z"}, {"R", "G", "B"}}
                               : std::vector<std::vector<std::string>>{{"R", "G", "B"}};
        values = readExrChannels(path, names, width, height);
    } else {
        throw InputError(file + ": the " + role + " must be an EXR or PFM file (32-bit or half float), not '" + ext + "'");
    }
    for (size_t i = 0; i < values.size(); ++i) {
        const float v = values[i];
        // The depth's +inf is a miss; nothing else may be other than finite.
        if (std::isnan(v) || (std::isinf(v) && !(role == "depth" && v > 0.0f)))
            throw InputError(file + ": pixel " + std::to_string(i / size_t(channels) % size_t(width)) + "," +
                             std::to_string(i / size_t(channels) / size_t(width)) + " of the " + role +
                             " is not finite (" + std::to_string(v) + ")");
    }
    return values;
}

DenoiseImages readDenoiseImages(const DenoiseFiles& files) {
    DenoiseImages in;
    // An image of the colour's size (the colour's own sets it), or none for an optional one not given.
    auto read = [&](const std::string& file, const std::string& role, int channels) {
        if (file.empty()) return std::vector<float>();
        int w = 0, h = 0;
        std::vector<float> v = readDenoiseImage(file, role, channels, w, h);
        if (role == "color") {
            in.width = w;
            in.height = h;
        } else if (w != in.width || h != in.height) {
            throw InputError(file + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels, the color image (" +
                             files.color + ") has " + std::to_string(in.width) + "x" + std::to_string(in.height));
        }
        return v;
    };
    auto vectors = [&](const std::string& file, const std::string& role) {
        const std::vector<float> v = read(file, role, 3);
        std::vector<glm::vec3> out(v.size() / 3);
        for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        return out;
    };
    in.color = vectors(files.color, "color");
    in.albedo = vectors(files.albedo, "albedo");
    in.normal = vectors(files.normal, "normal");
    in.variance = vectors(files.variance, "variance");
    in.depth = read(files.depth, "depth", 1);
    return in;
}

}  // namespace gpurt
