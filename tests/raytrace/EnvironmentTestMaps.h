// Environment maps made by the tests (never pasted numbers): a function of the direction evaluated
// at each texel centre by the contract's convention (CONTRACT.md: u = 0.5 + atan2(d.x, -d.z) /
// (2 pi), v = acos(d.y) / pi, v = 0 the top row), written as a Radiance .hdr (gpurt's writeHdr)
// or an OpenEXR .exr of 32-bit float R, G, B (OpenEXR directly), and read back through gpurt's
// reader, as --env reads them.
#pragma once

#include "image/EnvironmentImage.h"
#include "scene/Scene.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <unistd.h>

namespace gpurt::test {

// The contract's direction of map coordinates (u, v), written out independently of
// glsl/common/environment.h.
inline glm::vec3 contractDirection(double u, double v) {
    const double pi = 3.14159265358979323846;
    const double phi = (u - 0.5) * 2.0 * pi, theta = v * pi;
    // atan2(x, -z) = phi and y = cos(theta): x = sin(theta) sin(phi), z = -sin(theta) cos(phi).
    return glm::vec3(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)), float(-std::sin(theta) * std::cos(phi)));
}

inline EnvironmentImage makeMap(int width, int height, const std::function<glm::vec3(glm::vec3)>& radiance) {
    EnvironmentImage image;
    image.width = width;
    image.height = height;
    image.texels.resize(size_t(width) * size_t(height));
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i)
            image.texels[size_t(j) * size_t(width) + size_t(i)] =
                radiance(contractDirection((i + 0.5) / width, (j + 0.5) / height));
    return image;
}

inline void writeExrMap(const std::filesystem::path& path, const EnvironmentImage& image) {
    Imf::Header header(image.width, image.height);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile out(path.c_str(), header);
    Imf::FrameBuffer frame;
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.texels.data()));
    const size_t stride = sizeof(glm::vec3);
    const char* names[3] = {"R", "G", "B"};
    for (size_t c = 0; c < 3; ++c)
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), stride, stride * size_t(image.width)));
    out.setFrameBuffer(frame);
    out.writePixels(image.height);
}

// A scratch folder for the maps of one test process, removed when the process ends.
inline std::filesystem::path mapFolder() {
    static const struct Scratch {
        std::filesystem::path dir = std::filesystem::temp_directory_path() / ("gpurt-env-" + std::to_string(::getpid()));
        ~Scratch() {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    } scratch;
    std::filesystem::create_directories(scratch.dir);
    return scratch.dir;
}

// The map written as NAME (.hdr or .exr) and read back as an environment of the scene.
inline Environment environmentThroughFile(const EnvironmentImage& image, const std::string& name, float strength = 1.0f,
                                          float rotation = 0.0f, bool sampled = true) {
    const std::filesystem::path path = mapFolder() / name;
    if (path.extension() == ".exr") writeExrMap(path, image);
    else writeHdr(path, image);
    Environment env;
    env.image = std::make_shared<const EnvironmentImage>(readEnvironmentImage(path));
    env.file = path.string();
    env.strength = strength;
    env.rotation = rotation;
    env.sampled = sampled;
    return env;
}

}  // namespace gpurt::test
