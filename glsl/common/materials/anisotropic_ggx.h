// KHR_materials_anisotropy's microfacet lobe (glsl/common/materials/gltf.h, for scenes with
// anisotropy: SCENE_ANISOTROPY), shared word for word by the kernels and the CPU backend: GGX
// stretched by alpha_t along the unit tangent t and alpha_b along b = n x t, as the extension
// writes it (after Kulla and Conty 2017 and Filament):
//   D = 1 / (pi at ab ((t.h / at)^2 + (b.h / ab)^2 + (n.h)^2)^2)
//   V = 1 / (2 (n.l |(at t.v, ab b.v, n.v)| + n.v |(at t.l, ab b.l, n.l)|))
// (Smith's height-correlated G2 / (4 n.l n.v)), and Smith's masking of one direction,
// G1 = 2 n.v / (n.v + |(at t.v, ab b.v, n.v)|). With at = ab = alpha these are gltf.h's isotropic
// ggxDistribution, smithVisibility and smithMasking.
#ifndef GPURT_MATERIALS_ANISOTROPIC_GGX_H
#define GPURT_MATERIALS_ANISOTROPIC_GGX_H

// D for h's cosines th = t.h, bh = b.h, nh = n.h.
GPURT_FN float ggxAnisotropicDistribution(float at, float ab, float th, float bh, float nh) {
    float x = th / at;
    float y = bh / ab;
    float k = x * x + y * y + nh * nh;
    return 1.0f / (GPURT_PI * at * ab * k * k);
}

// |(at t.w, ab b.w, n.w)| for a direction w's cosines tw, bw, nw: Smith's Lambda(w) is
// (it / n.w - 1) / 2.
GPURT_FN float ggxAnisotropicLength(float at, float ab, float tw, float bw, float nw) {
    return sqrt(at * at * tw * tw + ab * ab * bw * bw + nw * nw);
}

// V for v's and l's cosines (nv, nl > 0; tv, bv, tl, bl about t and b).
GPURT_FN float ggxAnisotropicVisibility(float at, float ab, float tv, float bv, float nv, float tl, float bl, float nl) {
    float s = nl * ggxAnisotropicLength(at, ab, tv, bv, nv) + nv * ggxAnisotropicLength(at, ab, tl, bl, nl);
    return s > 0.0f ? 0.5f / s : 0.0f;
}

// G1 of the view at cosines tv, bv, nv.
GPURT_FN float ggxAnisotropicMasking(float at, float ab, float tv, float bv, float nv) {
    return 2.0f * nv / (nv + ggxAnisotropicLength(at, ab, tv, bv, nv));
}

#endif
