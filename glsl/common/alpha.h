// Alpha coverage (glTF alphaMode MASK / BLEND, MTL d / map_d) and back-face culling (glTF
// doubleSided false), shared word for word by the accelerators' kernels (glsl/scene/alpha.glsl)
// and the cpu backend (src/raytrace/materials/AlphaCoverage), after raymath.h and sampling.h. A candidate hit on a surface with alpha counts only where the
// surface covers the ray: MASK where alpha >= alphaCutoff, BLEND with probability alpha (stochastic
// transparency: rays pass the surface with probability 1 - alpha). BLEND's choice is a hash of the
// ray's key and the triangle, never a generator: every ray of one sample of one pixel (primary,
// secondary and shadow rays alike) has the same key, so images do not depend on tiling, thread
// count or backend (CONTRACT.md, sampling).
#ifndef GPURT_ALPHA_H
#define GPURT_ALPHA_H

#ifndef GPURT_SAMPLING_H
#error "include common/sampling.h before common/alpha.h"
#endif

// Material alpha modes (Material::alphaMode; material texel 7's x).
#define GPURT_ALPHA_OPAQUE 0
#define GPURT_ALPHA_MASK 1
#define GPURT_ALPHA_BLEND 2

// A triangle's coverage flags, the w of its second texel in the accelerators' triangle lists (the
// grid's cell lists, the BVH's leaves): whether its material culls back faces
// (Material::cullsBackFaces: glTF doubleSided false, not transmissive: a candidate hit on a back
// face, raymath.h backFacing, does not count, as an uncovered one does not), whether it has
// alpha. A triangle with neither (0) counts wherever it is hit: the kernels test it without
// fetching its material; culling alone needs only the ray and the edges.
#define GPURT_COVER_CULL 1
#define GPURT_COVER_ALPHA 2
#define GPURT_COVER_SHADOWLESS 4  // shadow rays (any-hit traversals) pass it: KHR_materials_unlit

// The pattern dimension of the coverage keys (apart from every other dimension's range).
#define GPURT_DIM_COVERAGE 8191u

// The coverage key of every ray of sample s of pixel (x, y).
GPURT_FN uint coverageKey(uint x, uint y, uint s, uint seed) {
    return hashPcg(samplePattern(x, y, seed, GPURT_DIM_COVERAGE) + s);
}

// Whether a surface of alpha mode `mode` and alpha `alpha` (factor times texture) covers the ray
// of coverage key `key` at triangle `triangle`.
GPURT_FN bool alphaCovers(int mode, float alpha, float cutoff, uint key, int triangle) {
    if (mode == GPURT_ALPHA_MASK) return alpha >= cutoff;
    if (mode == GPURT_ALPHA_BLEND) return unitFloat(hashPcg(key ^ hashPcg(uint(triangle) + 0x5bd1e995u))) < alpha;
    return true;
}

#endif
