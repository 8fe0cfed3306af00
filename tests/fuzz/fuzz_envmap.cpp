// libFuzzer target for the environment map readers (decodeEnvironmentImage: Radiance .hdr through
// stb_image, compiled here with the fuzzer's instrumentation; OpenEXR .exr when the input starts
// with EXR's magic number): any input must give a map within the size limits with texels in
// [0, 1e30] (kMaxEnvironmentRadiance), or an InputError, never a crash, a sanitizer report, a hang or another
// exception. An accepted map is then built into the environment light's table (its sampling
// distribution and spherical harmonics) and looked up and sampled in a few directions, which must
// give finite radiance and pdfs.
//   build-fuzz/tests/fuzz/fuzz_envmap -dict=tests/fuzz/envmap.dict CORPUS_DIR tests/fuzz/corpus/envmap
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include "image/EnvironmentImage.h"
#include "image/InputError.h"
#include "raytrace/lights/EnvironmentTable.h"

namespace {
bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    const bool exr = size >= 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
    gpurt::EnvironmentImage image;
    try {
        image = gpurt::decodeEnvironmentImage(bytes, exr ? "fuzz.exr" : "fuzz.hdr", exr);
    } catch (const gpurt::InputError&) {
        return 0;
    }
    if (image.width < 1 || image.height < 1 || image.width > gpurt::kMaxEnvironmentWidth ||
        image.height > gpurt::kMaxEnvironmentHeight || image.texels.size() != size_t(image.width) * size_t(image.height))
        std::abort();  // an accepted map must be whole and within the limits
    for (const glm::vec3& t : image.texels)
        if (!(t.x >= 0.0f && t.x <= gpurt::kMaxEnvironmentRadiance && t.y >= 0.0f && t.y <= gpurt::kMaxEnvironmentRadiance &&
              t.z >= 0.0f && t.z <= gpurt::kMaxEnvironmentRadiance))
            std::abort();
    gpurt::Scene scene;
    gpurt::Environment env;
    env.image = std::make_shared<const gpurt::EnvironmentImage>(std::move(image));
    env.rotation = 30.0f;
    scene.environment = env;
    const gpurt::EnvironmentTable table = gpurt::buildEnvironmentTable(scene);
    for (const glm::vec3 d : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0.6f, 0.0f, -0.8f)}) {
        if (!finite(table.radiance(d)) || !std::isfinite(table.pdf(d)) || !finite(table.irradiance(d))) std::abort();
    }
    for (const glm::vec2 u : {glm::vec2(0.0f), glm::vec2(0.5f), glm::vec2(0.99999994f), glm::vec2(0.25f, 0.75f)}) {
        glm::vec3 dir;
        float pdf;
        if (table.sample(u, dir, pdf) && (!finite(dir) || !std::isfinite(pdf) || !(pdf > 0.0f))) std::abort();
    }
    return 0;
}
