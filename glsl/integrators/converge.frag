// Adaptive sampling's convergence pass (common/adaptive.h): after each round of samples, every
// active pixel looks at its 3 x 3 neighbourhood's errors (the sums of all and of the odd
// samples) and stays active while one of them is at or above the threshold. It writes 1 where the
// pixel stays active and discards where it stops, into a stream cleared to 0, so the pass's
// occlusion query counts the active pixels: the render ends when it counts none. The pass runs
// under the activity mask itself, so stopped pixels cost nothing and stay 0. Each pixel that stays
// active also appends its stream index to a packed list (an atomic counter gives each its slot,
// as the path megakernel packs live paths), so that the path megakernel's later camera passes run
// over ceil(active / width) rows instead of the whole masked image: llvmpipe's early-Z skips only
// 4 x 2 blocks whose pixels are all masked, and the path loop of a block runs as long as its
// longest path.
#include "common/stream.glsl"
#include "common/raymath.h"
#include "common/adaptive.h"

uniform sampler2D sampleSum;  // (sum of the pixel's samples, their count)
uniform sampler2D oddSum;     // (sum of its odd-numbered samples, 0)
uniform float threshold;      // --noise-threshold
uniform int packWidth;        // the list's width: slot k is element (k % width, k / width)
layout(rgba32f) uniform image2D activePixels;  // (stream x, stream y, 0, 0) of each active pixel
layout(r32ui) uniform uimage2D activeCount;    // texel 0: the slots taken

layout(location = 0) out vec4 stillActive;

void main() {
    ivec2 at = streamIndex();
    ivec2 size = textureSize(sampleSum, 0);
    float error = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = at + ivec2(dx, dy);
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
            vec4 s = texelFetch(sampleSum, q, 0);
            error = max(error, pixelError(s.xyz, texelFetch(oddSum, q, 0).xyz, s.w));
        }
    }
    if (pixelConverged(error, threshold)) discard;
    stillActive = vec4(1.0f);
    uint k = imageAtomicAdd(activeCount, ivec2(0, 0), 1u);
    imageStore(activePixels, ivec2(int(k) % packWidth, int(k) / packWidth), vec4(vec2(at), 0.0f, 0.0f));
}
