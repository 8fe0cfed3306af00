// libFuzzer target for the texture image reader (decodeImage: PNG through libpng, JPEG through
// libjpeg-turbo): any input must give an image within the size limits or an InputError, never a
// crash, a sanitizer report, a hang or another exception; an accepted image is then filtered at
// a few points with each wrap mode (SurfaceTexture, the CPU side of the kernels' sampling).
//   build-fuzz/tests/fuzz/fuzz_texture -dict=tests/fuzz/texture.dict CORPUS_DIR tests/fuzz/corpus/texture
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "image/InputError.h"
#include "image/TextureImage.h"
#include "raytrace/materials/SurfaceTexture.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    gpurt::Texture texture;
    try {
        texture.image = gpurt::decodeImage(data, size, "fuzz.img");  // at most 2^20 texels here
    } catch (const gpurt::InputError&) {
        return 0;
    }
    const gpurt::Rgba8Image& image = texture.image;
    if (image.width < 1 || image.height < 1 || image.width > gpurt::kMaxTextureSide ||
        image.height > gpurt::kMaxTextureSide ||
        uint64_t(image.width) * uint64_t(image.height) > gpurt::kMaxTextureTexels || image.texels.size() != size_t(image.width) * size_t(image.height))
        std::abort();  // an accepted image must be whole and within the limits
    for (uint32_t wrap : {gpurt::kWrapRepeat, gpurt::kWrapClamp, gpurt::kWrapMirror}) {
        texture.wrapS = texture.wrapT = wrap;
        for (const glm::vec2 t : {glm::vec2(0.0f), glm::vec2(1.0f), glm::vec2(-0.3f, 7.9f), glm::vec2(0.999f, -1e9f)}) {
            const glm::vec3 c = gpurt::sampleTexture(texture, t);
            if (!(c.x >= 0.0f && c.x <= 1.0f && c.y >= 0.0f && c.y <= 1.0f && c.z >= 0.0f && c.z <= 1.0f)) std::abort();
        }
    }
    return 0;
}
