// The streams a bounce pass reads (whitted/bounce.frag, path/bounce.frag): the surface records the
// surface pass wrote, the light gathered at them, and the paths' state so far.
uniform sampler2D surfacePoint;    // (p, triangle | -1)
uniform sampler2D surfaceNormal;   // (facing geometric normal, material)
uniform sampler2D surfaceView;     // (ray direction, barycentric u)
uniform sampler2D surfaceShading;  // (shading normal, barycentric v)
uniform sampler2D localColor;      // (the light gathered at the hit, the hit's distance along the ray)
uniform sampler2D colorState;      // the path's colour so far; w: 1 once it follows one colour channel (path: pathDisperse)
uniform sampler2D weightState;     // (throughput, alive)
uniform sampler2D pathStateIn;     // Whitted: (depth, stack height, rays after the first, 0); path: (pdf of the ray's direction, pixel x, pixel y, features closed)

// Throughput w of the ray that reached the hit at surface point s (surfacePoint), times what the
// medium it crossed let through (common/material.h materialTransmittance: a KHR_materials_volume
// solid seen from inside). The surface pass weighs the emission with it but does not write the
// throughput back, so the bounce passes apply it again.
vec3 crossedWeight(vec3 w, vec4 s) {
#ifdef SCENE_VOLUME  // SceneTextures::bind: compiled out without a volume
    vec4 nm = readStream(surfaceNormal);
    vec4 view = readStream(surfaceView);
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(int(s.w), v0, e1, e2, material);
    MaterialRecord m = materialFacing(fetchMaterialRecord(int(nm.w), int(s.w), vec2(view.w, readStream(surfaceShading).w), view.xyz),
                                      frontFace(e1, e2, view.xyz));
    return w * materialTransmittance(m, readStream(localColor).w);
#else
    return w;
#endif
}
