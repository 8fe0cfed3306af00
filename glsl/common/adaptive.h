// Adaptive sampling (--noise-threshold, CONTRACT.md "Sampling, adaptive sampling and denoising"),
// shared word for word by the convergence kernel (integrators/converge.frag) and the CPU backend
// (after common/raymath.h), so that both stop the same pixels. Same rules as raymath.h.
//
// A pixel's error is Cycles' (after Dammertz et al. 2009, "A hierarchical automatic stopping
// condition for Monte Carlo global illumination", section 2.1; Rousselle et al. 2012): the
// difference between the mean of all its samples and the mean of its odd-numbered samples, summed
// over the channels and divided by the square root of the mean's channel sum (the noise relative to
// what the eye sees of it). A pixel stops once the error of every pixel of its 3 x 3 neighbourhood
// is below the threshold times 5 (Cycles' factor, so that a threshold means what it means there),
// so that no isolated pixel stops on a lucky estimate. Pixels that stopped keep their sums, so
// their errors stay below it: the active pixels never rise in number.
#ifndef GPURT_ADAPTIVE_H
#define GPURT_ADAPTIVE_H

#ifndef GPURT_RAYMATH_H
#error "include common/raymath.h before common/adaptive.h"
#endif

// Cycles' scale of the threshold (Integrator::get_adaptive_sampling: "threshold *= 5").
#define GPURT_ADAPTIVE_SCALE 5.0f
// The samples between two convergence passes (Cycles' adaptive step): the first pass follows
// --min-spp samples, the later ones each multiple of this above it (RenderTypes.h
// adaptiveCheckAfter), a power of two so that each later round's samples are an aligned block of
// the sampler's (0, 2)-sequence.
#define GPURT_ADAPTIVE_STEP 16u

// The variance of the mean of n samples per channel, from their sum and the sum of their squares:
// (squares / n - mean^2) / (n - 1), 0 below two samples (the variance AOV; the denoiser's).
GPURT_FN vec3 sampleMeanVariance(vec3 sum, vec3 squares, float n) {
    if (!(n >= 2.0f)) return vec3(0.0f);
    vec3 mean = sum / n;
    return max(squares / n - mean * mean, vec3(0.0f)) / (n - 1.0f);
}

// The error of a pixel whose `count` samples sum to `sum`, its odd-numbered ones (1, 3, 5...) to
// `oddSum`; 1e30 before it has an odd sample.
GPURT_FN float pixelError(vec3 sum, vec3 oddSum, float count) {
    float odd = floor(count * 0.5f);
    if (!(odd >= 1.0f)) return 1e30f;
    vec3 mean = sum / count;
    vec3 d = abs(mean - oddSum / odd);
    return (d.x + d.y + d.z) / (0.0001f + sqrt(max(0.0f, mean.x + mean.y + mean.z)));
}

// Whether a pixel whose own and neighbours' largest error is `error` has converged under the
// threshold (--noise-threshold, > 0).
GPURT_FN bool pixelConverged(float error, float threshold) { return error < threshold * GPURT_ADAPTIVE_SCALE; }

#endif
