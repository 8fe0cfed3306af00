// Alpha coverage and back-face culling inside the accelerators' traversals: whether a candidate
// hit counts (common/alpha.h, src/raytrace/materials/AlphaCoverage on the cpu backend). The accelerators'
// kernels include this file only when some material in use has alpha (SCENE_ALPHA), culls its
// back faces (SCENE_CULL_BACK: glTF doubleSided false) or casts no shadow (SCENE_SHADOWLESS:
// KHR_materials_unlit); each compiles only its own test.
// GpuTracer binds the scene textures it reads and sets the sample's uniforms.
#include "../common/sampling.h"
#include "shading.glsl"
#include "../common/alpha.h"

#ifdef SCENE_ALPHA
uniform uint coverageSample;  // the sample index and seed of the rays traced (GpuTracer::setSample)
uniform uint coverageSeed;
// 1 where an element's ray need not be its pixel's (the path integrator's packed paths after its
// first round): the pixel is then (y, z) of coveragePixels, the pathState stream (shading.glsl
// pathPixel); 0: the element's own pixel.
uniform int coverageFromStream;
uniform sampler2D coveragePixels;

// The coverage key of this element's ray: its pixel's sample.
uint elementCoverageKey() {
    uvec2 pixel = coverageFromStream != 0 ? uvec2(readStream(coveragePixels).yz) : imagePixel();
    return coverageKey(pixel.x, pixel.y, coverageSample, coverageSeed);
}
#else
uint elementCoverageKey() { return 0u; }  // culling alone needs no key
#endif

// Whether triangle `id` (edges e1, e2, coverage flags `flags`: common/alpha.h GPURT_COVER_*, the
// w of its second texel in the accelerators' lists) covers the ray of key `key` and direction d at
// barycentrics (u, v), a shadow ray (an any-hit traversal's) or not. Flags 0: it does, with no fetch; culling alone needs no fetch either;
// alpha reads its material's texel 7 (alpha mode, factor, cutoff, channel) and the channel at the
// hit's texture coordinates.
bool hitCovered(int id, float flags, float u, float v, uint key, vec3 d, vec3 e1, vec3 e2, bool shadowRay) {
    int f = int(flags);
    if (f == 0) return true;
#ifdef SCENE_SHADOWLESS
    if ((f & GPURT_COVER_SHADOWLESS) != 0 && shadowRay) return false;
#endif
#ifdef SCENE_CULL_BACK
    if ((f & GPURT_COVER_CULL) != 0 && backFacing(d, e1, e2)) return false;
#endif
#ifdef SCENE_ALPHA
    if ((f & GPURT_COVER_ALPHA) == 0) return true;
    ivec2 at = ivec2(3 * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    int m = int(texelFetch(triangles, at, 0).w);
    vec4 alpha = texelFetch(materials, GPURT_MATERIAL_TEXEL(m, 7), 0);
    int mode = int(alpha.x);
    float a = alpha.y * textureChannel(int(alpha.w), fetchTexcoord(id, u, v));
    return alphaCovers(mode, a, alpha.z, key, id);
#else
    return true;
#endif
}
