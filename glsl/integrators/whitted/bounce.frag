// Shading, last step of a round of the ray tree (Whitted 1980; Christen 2005, eq. 5.1):
// colour += weight * local colour; then the pixel's next ray. The hit's children (common/material.h
// materialChildren: the reflected and refracted rays of glass, the mirror ray) are spawned while the
// ray's depth is below `maxBounces` and the tree has rays left: the first continues as the pixel's
// ray, the second is pushed on the pixel's stack. A ray without children hands over to the top of
// the stack (its depth and weight with it); with the stack empty the pixel's tree is done
// (common/raytree.h, the same steps as the CPU backend's). One ray
// per pixel per round, so the passes stay image-sized and the rounds end when the trace counts no
// ray (WhittedGl::sample). The stack is the one store outside the pixel's own element: slot s
// of pixel (x, y) is element (x, y + s H) of the stack images, written only by that pixel.
// The bounce also widens a box (rayBounds) to every element that has a ray next round: the next
// round's passes run over that box only (WhittedGl::spawnRays), so the late rounds of glass
// cost the pixels that see it, not the image.
// LAST_ROUND: the variant for a round after which no ray can follow (no mirror or glass in the
// scene, or no bounce allowed): only the colour, one output instead of five.
#include "scene/shading.glsl"

// colorState, weightState and pathStateIn in place
#include "integrators/surface_streams.glsl"
layout(rgba32f) uniform image2D stackOrigin;  // (o, depth)
layout(rgba32f) uniform image2D stackDir;     // (d, 0)
layout(rgba32f) uniform image2D stackWeight;  // (weight, 0)
layout(r32ui) uniform uimage2D rayBounds;     // 4 x 1: min x, min y, max x, max y of the next rays
uniform int maxBounces;
uniform int stackSlots;

layout(location = 0) out vec4 color;
#ifdef LAST_ROUND
void main() {
    vec4 s = readStream(surfacePoint);
    vec4 w = readStream(weightState);
    color = readStream(colorState);
    if (w.w != 0.0f && s.w >= 0.0f) color = vec4(color.xyz + crossedWeight(w.xyz, s) * readStream(localColor).xyz, 0.0f);
}
#else
layout(location = 1) out vec4 weight;     // (weight of the pixel's ray, alive)
layout(location = 2) out vec4 rayOrigin;  // the pixel's next ray
layout(location = 3) out vec4 rayDir;
layout(location = 4) out vec4 pathState;  // (depth, stack height, rays of the tree after the first, 0)

void main() {
    vec4 s = readStream(surfacePoint);
    vec4 w = readStream(weightState);
    vec4 ps = readStream(pathStateIn);
    color = readStream(colorState);
    weight = vec4(w.xyz, 0.0f);
    pathState = ps;
    rayOrigin = vec4(0.0f);
    rayDir = vec4(0.0f, 0.0f, 0.0f, GPURT_NO_RAY);
    if (w.w == 0.0f) return;  // the pixel's tree was done before this round
    int depth = int(ps.x), height = int(ps.y), rays = int(ps.z) + 1;
    int children = 0;
    vec3 dirA, weightA, dirB, weightB;
    float sideA;
    int imageHeight = textureSize(colorState, 0).y;
    if (s.w >= 0.0f) {  // a miss was shaded by the surface pass; a hit adds its local colour
        w.xyz = crossedWeight(w.xyz, s);
        color = vec4(color.xyz + w.xyz * readStream(localColor).xyz, 0.0f);
        if (rayTreeMaySpawn(depth, rays, maxBounces)) {
            vec4 nm = readStream(surfaceNormal);
            vec4 view = readStream(surfaceView);
            vec4 shading = readStream(surfaceShading);
            MaterialRecord m = fetchMaterialRecord(int(nm.w), int(s.w), vec2(view.w, shading.w), view.xyz);
            if (materialSpawns(m)) {  // only mirrors and glass have children
                vec3 d = view.xyz;
                vec3 v0, e1, e2;
                int material;
                fetchTriangle(int(s.w), v0, e1, e2, material);
                m = materialFacing(m, frontFace(e1, e2, d));
                children = materialChildren(m, d, nm.xyz, shading.xyz, frontFace(e1, e2, d), w.xyz, dirA, weightA,
                                            sideA, dirB, weightB);
            }
        }
    }
    bool push;
    int next = rayTreeNext(children, stackSlots, depth, height, rays, push);
    if (next == GPURT_TREE_CONTINUE) {
        vec4 nm = readStream(surfaceNormal);
        vec3 o = offsetOrigin(s.xyz, sideA * nm.xyz, rayOffset);
        weight = vec4(weightA, 1.0f);
        rayOrigin = vec4(o, GPURT_FAR);
        rayDir = vec4(dirA, GPURT_A_RAY);
        if (push) {
            ivec2 at = streamIndex() + ivec2(0, (height - 1) * imageHeight);
            imageStore(stackOrigin, at, vec4(offsetOrigin(s.xyz, nm.xyz, rayOffset), float(depth)));
            imageStore(stackDir, at, vec4(dirB, 0.0f));
            imageStore(stackWeight, at, vec4(weightB, 0.0f));
        }
    } else if (next == GPURT_TREE_POP) {  // the pending ray on top of the stack
        ivec2 at = streamIndex() + ivec2(0, height * imageHeight);
        vec4 o = imageLoad(stackOrigin, at);
        vec3 d = imageLoad(stackDir, at).xyz;
        weight = vec4(imageLoad(stackWeight, at).xyz, 1.0f);
        rayOrigin = vec4(o.xyz, GPURT_FAR);
        rayDir = vec4(d, GPURT_A_RAY);
        depth = int(o.w);
    }
    pathState = vec4(float(depth), float(height), float(rays - 1), 0.0f);
    if (weight.w != 0.0f) {  // a ray next round: the round's passes must cover this element
        uvec2 at = uvec2(streamIndex());
        imageAtomicMin(rayBounds, ivec2(0, 0), at.x);
        imageAtomicMin(rayBounds, ivec2(1, 0), at.y);
        imageAtomicMax(rayBounds, ivec2(2, 0), at.x);
        imageAtomicMax(rayBounds, ivec2(3, 0), at.y);
    }
}
#endif
