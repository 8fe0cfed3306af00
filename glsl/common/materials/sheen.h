// KHR_materials_sheen's lobe (the Charlie sheen) and its albedo table's lookup, shared word for
// word by the kernels and the CPU backend; included by materials/gltf.h, which layers it over the
// base (gltfBrdf, gltfSheenBase).
#ifndef GPURT_MATERIALS_SHEEN_H
#define GPURT_MATERIALS_SHEEN_H

// KHR_materials_sheen: the Charlie sheen (Conty Estevez and Kulla 2017) as the extension's
// implementation notes write it, alpha = roughness^2, its visibility with their fitted Lambda; a
// roughness below GPURT_SHEEN_MIN_ROUGHNESS is taken as that (the lobe's spike at grazing
// angles is past what a table and a cosine-weighted sampler resolve; three.js clamps the same).
#define GPURT_SHEEN_MIN_ROUGHNESS 0.07f

GPURT_FN float sheenAlpha(float roughness) {
    float r = max(roughness, GPURT_SHEEN_MIN_ROUGHNESS);
    return r * r;
}

// The Charlie distribution D at n.h = nh.
GPURT_FN float charlieDistribution(float alpha, float nh) {
    float invR = 1.0f / alpha;
    float sin2h = max(1.0f - nh * nh, 0.0f);
    return (2.0f + invR) * pow(sin2h, invR * 0.5f) / (2.0f * GPURT_PI);
}

GPURT_FN float charlieL(float x, float alpha) {
    float k = (1.0f - alpha) * (1.0f - alpha);
    float a = mix(21.5473f, 25.3245f, k);
    float b = mix(3.82987f, 3.32435f, k);
    float c = mix(0.19823f, 0.16801f, k);
    float d = mix(-1.97760f, -1.27393f, k);
    float e = mix(-4.32054f, -4.85967f, k);
    return a / (1.0f + b * pow(x, c)) + d * x + e;
}

// The sheen's Lambda at cosine c.
GPURT_FN float charlieLambda(float c, float alpha) {
    float x = abs(c);
    return x < 0.5f ? exp(charlieL(x, alpha)) : exp(2.0f * charlieL(0.5f, alpha) - charlieL(1.0f - x, alpha));
}

// The sheen lobe D V (before its colour) for cosines nh, nl, nv > 0.
GPURT_FN float sheenLobe(float alpha, float nh, float nl, float nv) {
    return charlieDistribution(alpha, nh) / ((1.0f + charlieLambda(nv, alpha) + charlieLambda(nl, alpha)) * (4.0f * nv * nl));
}

#if defined(__cplusplus) || defined(SCENE_SHEEN)  // SceneTextures::bind
// The sheen's directional albedo E(mu) of roughness r (its lobe of colour 1, integrated: the
// table sheenAlbedoTexel reads, raytrace/materials/SheenTable.cpp), bilinear between its entries.
GPURT_FN float sheenAlbedo(float mu, float r) {
    float x = sqrt(clamp(mu, 0.0f, 1.0f)) * float(GPURT_SHEEN_TABLE - 1);  // rows in sqrt(n.v): E is steep at grazing views
    float y = clamp(r, 0.0f, 1.0f) * float(GPURT_SHEEN_TABLE - 1);
    int i = min(int(x), GPURT_SHEEN_TABLE - 2);
    int j = min(int(y), GPURT_SHEEN_TABLE - 2);
    float fx = x - float(i);
    float a = mix(sheenAlbedoTexel(i, j), sheenAlbedoTexel(i + 1, j), fx);
    float b = mix(sheenAlbedoTexel(i, j + 1), sheenAlbedoTexel(i + 1, j + 1), fx);
    return mix(a, b, y - float(j));
}
#endif

#endif
