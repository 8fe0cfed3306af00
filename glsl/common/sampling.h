// Sample positions and random numbers, shared word for word by the kernels and the CPU backend
// (after common/raymath.h). Every number is a pure function of (pixel, sample index, seed,
// dimension), a counter-based hash, never a per-thread generator: images do not depend on tiling,
// thread count or backend (CONTRACT.md, sampling).
//
// A pixel's N samples of one 2D dimension are Kensler's correlated multi-jittered pattern
// (Kensler 2013, "Correlated Multi-Jittered Sampling", Pixar tech memo 13-01): stratified in 2D
// and in each 1D projection for any N, the pattern and the jitter chosen per pixel by the hash.
// The hash is PCG's output permutation as a hash (Jarzynski & Olano 2020, "Hash Functions for GPU
// Rendering"). Same rules as raymath.h; integer arithmetic is 32-bit unsigned and wraps.
#ifndef GPURT_SAMPLING_H
#define GPURT_SAMPLING_H

#ifndef GPURT_RAYMATH_H
#error "include common/raymath.h before common/sampling.h"
#endif

// The sample dimensions (each a 2D pattern of its own).
#define GPURT_DIM_PIXEL 0u    // position in the pixel
#define GPURT_DIM_EMITTER 1u  // the point on an emitter (area lights)

GPURT_FN uint hashPcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The key of one pixel's pattern in one dimension.
GPURT_FN uint samplePattern(uint x, uint y, uint seed, uint dimension) {
    return hashPcg(hashPcg(hashPcg(hashPcg(seed) + x) + y) + dimension);
}

// A float in [0, 1) from the top 24 bits of a hash (exact in both languages).
GPURT_FN float unitFloat(uint h) { return float(h >> 8u) * 5.9604645e-08f; }

// A permutation of [0, l) chosen by p, applied to i (Kensler 2013, listing 3: a hash that is a
// bijection on the next power of two, cycle-walked into [0, l)).
GPURT_FN uint permuteIndex(uint i, uint l, uint p) {
    uint w = l - 1u;
    w |= w >> 1u;
    w |= w >> 2u;
    w |= w >> 4u;
    w |= w >> 8u;
    w |= w >> 16u;
    do {
        i ^= p;
        i *= 0xe170893du;
        i ^= p >> 16u;
        i ^= (i & w) >> 4u;
        i ^= p >> 8u;
        i *= 0x0929eb3fu;
        i ^= p >> 23u;
        i ^= (i & w) >> 1u;
        i *= 1u | (p >> 27u);
        i *= 0x6935fa69u;
        i ^= (i & w) >> 11u;
        i *= 0x74dcb303u;
        i ^= (i & w) >> 2u;
        i *= 0x9e501cc3u;
        i ^= (i & w) >> 2u;
        i *= 0xc860a3dfu;
        i &= w;
        i ^= i >> 5u;
    } while (i >= l);
    return (i + p) % l;
}

// Sample s of n of the correlated multi-jittered pattern p, in [0, 1)^2 (Kensler 2013, listing 5,
// with m x k cells, m = floor(sqrt(n)), k = ceil(n / m)).
GPURT_FN vec2 cmjSample(uint s, uint n, uint p) {
    uint m = uint(sqrt(float(n)));
    uint k = (n + m - 1u) / m;
    s = permuteIndex(s, n, p * 0x51633e2du);
    uint sx = permuteIndex(s % m, m, p * 0x68bc21ebu);
    uint sy = permuteIndex(s / m, k, p * 0x02e5be93u);
    float jx = unitFloat(hashPcg(s ^ (p * 0x967a889bu)));
    float jy = unitFloat(hashPcg(s ^ (p * 0x368cc8b7u)));
    return vec2((float(sx) + (float(sy) + jx) / float(k)) / float(m), (float(s) + jy) / float(n));
}

// Two independent uniform numbers in [0, 1) for sample s of the pattern p, without
// stratification: for choices that gain little from it (a lobe, Russian roulette), at a fraction
// of cmjSample's cost.
GPURT_FN vec2 randomPair(uint s, uint p) {
    return vec2(unitFloat(hashPcg(s ^ (p * 0x8a4f2c1bu))), unitFloat(hashPcg(s ^ (p * 0x27d4eb2fu))));
}

// Where sample s of n of pixel (x, y) lies in the pixel, in [0, 1)^2: the centre for n = 1 (the
// contract's pixel-centre ray), else the pixel's stratified pattern.
GPURT_FN vec2 pixelSampleOffset(uint x, uint y, uint s, uint n, uint seed) {
    if (n == 1u) return vec2(0.5f);
    return cmjSample(s, n, samplePattern(x, y, seed, GPURT_DIM_PIXEL));
}

#endif
