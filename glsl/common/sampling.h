// Sample positions and random numbers, shared word for word by the kernels and the CPU backend
// (after common/raymath.h). Every number is a pure function of (pixel, sample index, seed,
// dimension), a counter-based hash, never a per-thread generator: images do not depend on tiling,
// thread count or backend (CONTRACT.md, sampling).
//
// Three samplers (--sampler, CONTRACT.md "Sampling"), each a function of the same key:
// - sobol (the default): Owen-scrambled Sobol points, each 2D dimension its own shuffled and
//   scrambled copy of Sobol's first two dimensions (Burley 2020, "Practical Hash-based Owen
//   Scrambling", JCGT 9(4), sections 3-4: hash-based nested uniform scrambling and padding by
//   shuffling). Any prefix of 2^k samples of a 2D dimension is a (0, k, 2)-net, so a render that
//   does not know its sample count in advance (adaptive sampling, the viewer) stays stratified;
// - stratified: Kensler's correlated multi-jittered pattern (Kensler 2013, "Correlated
//   Multi-Jittered Sampling", Pixar tech memo 13-01): stratified in 2D and in each 1D projection
//   for the N samples it is told of, not for a prefix of them;
// - random: independent uniform numbers, the baseline.
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
#define GPURT_DIM_LENS 8190u  // the point on the lens (raymath.h aperturePoint)

// The samplers (RenderTypes.h SamplerKind: the same values).
#define GPURT_SAMPLER_SOBOL 0u
#define GPURT_SAMPLER_STRATIFIED 1u
#define GPURT_SAMPLER_RANDOM 2u

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

// v with its 32 bits in reverse order.
GPURT_FN uint reverseBits(uint v) {
    v = ((v >> 1u) & 0x55555555u) | ((v & 0x55555555u) << 1u);
    v = ((v >> 2u) & 0x33333333u) | ((v & 0x33333333u) << 2u);
    v = ((v >> 4u) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4u);
    v = ((v >> 8u) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8u);
    return (v >> 16u) | (v << 16u);
}

// The Laine-Karras permutation under the key k (Burley 2020, listing 4, with its constants): each
// bit of x is flipped as a hash of the bits below it decides.
GPURT_FN uint laineKarras(uint x, uint k) {
    x += k;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

// A nested uniform (Owen) scramble of the 32-bit fraction x under the key k: each bit is flipped
// as a hash of the bits above it decides (Burley 2020, listing 5: Laine-Karras on the reversed
// bits). As a permutation of sample indices it keeps each aligned block of 2^k indices together
// (listing 6's shuffle).
GPURT_FN uint owenScramble(uint x, uint k) { return reverseBits(laineKarras(reverseBits(x), k)); }

// Sobol's second dimension of index i as a 32-bit fraction (its generator matrix: the direction
// numbers of the polynomial x + 1, v_1 = 1/2, v_k = v_{k-1} xor v_{k-1} / 2).
GPURT_FN uint sobolSecond(uint i) {
    uint v = 0x80000000u;
    uint x = 0u;
    for (; i != 0u; i >>= 1u) {
        if ((i & 1u) != 0u) x ^= v;
        v ^= v >> 1u;
    }
    return x;
}

// Sample s of the Owen-scrambled Sobol pattern p, in [0, 1)^2 (Burley 2020, listing 6): the index
// shuffled, then Sobol's first two dimensions, each scrambled with a key of its own. The first
// dimension is the index's bits reversed, so its scramble, owenScramble(reverseBits(i)), is
// Laine-Karras on i itself, reversed once.
GPURT_FN vec2 sobolSample(uint s, uint p) {
    uint i = owenScramble(s, hashPcg(p ^ 0x5bd1e995u));
    uint x = reverseBits(laineKarras(i, hashPcg(p ^ 0x2545f491u)));
    uint y = owenScramble(sobolSecond(i), hashPcg(p ^ 0x9e3779b9u));
    return vec2(unitFloat(x), unitFloat(y));
}

// Sample s of n of pixel (x, y) in the 2D dimension `dimension`, in [0, 1)^2, from `sampler`.
GPURT_FN vec2 sample2D(uint sampler, uint x, uint y, uint s, uint n, uint seed, uint dimension) {
    uint p = samplePattern(x, y, seed, dimension);
    if (sampler == GPURT_SAMPLER_STRATIFIED) return cmjSample(s, n, p);
    if (sampler == GPURT_SAMPLER_RANDOM) return randomPair(s, p);
    return sobolSample(s, p);
}

// The pair of numbers for choices that gain little from stratification (a lobe, Russian
// roulette): the stratified sampler's are independent (randomPair: it has no pattern for a
// prefix); sobol's are its points as any dimension's.
GPURT_FN vec2 sampleChoice(uint sampler, uint x, uint y, uint s, uint n, uint seed, uint dimension) {
    if (sampler == GPURT_SAMPLER_STRATIFIED) return randomPair(s, samplePattern(x, y, seed, dimension));
    return sample2D(sampler, x, y, s, n, seed, dimension);
}

// Where sample s of n of pixel (x, y) lies in the pixel, in [0, 1)^2: the centre for n = 1 (the
// contract's pixel-centre ray), else the sampler's point of the pixel dimension.
GPURT_FN vec2 pixelSampleOffset(uint sampler, uint x, uint y, uint s, uint n, uint seed) {
    if (n == 1u) return vec2(0.5f);
    return sample2D(sampler, x, y, s, n, seed, GPURT_DIM_PIXEL);
}

#endif
