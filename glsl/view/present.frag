// The viewer's present pass: draws the streams into the window's back buffer, flipped (stream row
// 0 is the image's top row, the window's row 0 its bottom). Shaded: the running mean of the
// samples (or with showDenoised its denoised colour, raytrace/denoise), then exposure, tone map and
// the sRGB transfer function of common/colour.h, as the PNG of `gpurt render` is made. The AOVs of the pixel centres in false colour (docs: README, viewer):
//   depth:  grey 1 - (t - near) / (far - near), clamped, near and far bounding the scene's box
//   normal: n * 0.5 + 0.5
//   prim:   the colour of the triangle id's hash (common/sampling.h hashPcg: bytes 0, 1, 2)
//   steps:  (s, 0.25, 1 - s) with s = cells / 64, clamped
// and black where the ray missed (steps: everywhere).
#include "../common/raymath.h"
#include "../common/colour.h"
#include "../common/sampling.h"

uniform sampler2D sampleSum;
uniform sampler2D aovHit;
uniform isampler2D aovCells;
uniform sampler2D aovNormal;
uniform sampler2D denoised;  // (colour, 1): the denoiser's output
uniform int showDenoised;
uniform int mode;          // 0 shaded, 1 depth, 2 normal, 3 prim, 4 steps
uniform float samples;     // samples in the sums (at least 1)
                           // (each pixel's own count is its sum's w: adaptive sampling stops some)
uniform float exposureScale;
uniform int toneMapMode;   // GPURT_TONEMAP_*
uniform vec2 depthRange;   // (near, far)

layout(location = 0) out vec4 display;

void main() {
    ivec2 size = textureSize(sampleSum, 0);
    ivec2 at = ivec2(int(gl_FragCoord.x), size.y - 1 - int(gl_FragCoord.y));
    vec4 hit = texelFetch(aovHit, at, 0);
    vec3 c = vec3(0.0f);
    if (mode == 0) {
        vec4 sum = texelFetch(sampleSum, at, 0);
        vec3 linear = showDenoised != 0 ? texelFetch(denoised, at, 0).xyz : sum.xyz / max(sum.w, 1.0f);
        vec3 mapped = toneMap(linear, exposureScale, toneMapMode);
        c = vec3(srgbEncode(mapped.x), srgbEncode(mapped.y), srgbEncode(mapped.z));
    } else if (mode == 4) {
        float s = clamp(float(texelFetch(aovCells, at, 0).w) / 64.0f, 0.0f, 1.0f);
        c = vec3(s, 0.25f, 1.0f - s);
    } else if (hit.w >= 0.0f) {
        if (mode == 1) c = vec3(1.0f - clamp((hit.x - depthRange.x) / (depthRange.y - depthRange.x), 0.0f, 1.0f));
        if (mode == 2) c = texelFetch(aovNormal, at, 0).xyz * 0.5f + 0.5f;
        if (mode == 3) {
            uint h = hashPcg(uint(hit.w));
            c = vec3(float(h & 255u), float((h >> 8u) & 255u), float((h >> 16u) & 255u)) / 255.0f;
        }
    }
    display = vec4(c, 1.0f);
}
