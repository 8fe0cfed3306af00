// Whitted's ray tree (Whitted 1980), shared word for word by the kernels
// (integrators/whitted/bounce.frag) and the CPU backend (integrators/whitted/WhittedCpu), so that
// both take the same rays in the same order: each pixel sample's tree is walked depth first, one
// ray a round; a hit's first child continues as the pixel's ray, its second waits on the pixel's
// stack; a ray without children hands over to the top of the stack. Only where the pending rays
// are stored differs (the GL's stack images, the CPU's array). Same rules as raymath.h.
//
// Limits: a tree holds at most GPURT_TREE_RAYS rays; children weighing less than
// GPURT_MIN_WEIGHT (their largest channel) are not traced (Hall & Greenberg 1983, adaptive tree
// depth); a pixel's stack holds at most min(bounces, GPURT_STACK_SLOTS) rays (a child that finds
// it full is dropped).
#ifndef GPURT_RAYTREE_H
#define GPURT_RAYTREE_H

#ifndef GPURT_RAYMATH_H
#error "include common/raymath.h before common/raytree.h"
#endif

#define GPURT_TREE_RAYS 64
#define GPURT_MIN_WEIGHT 1e-4f
#define GPURT_STACK_SLOTS 8

// What the pixel's ray does after a round (rayTreeNext).
#define GPURT_TREE_CONTINUE 0  // it continues as the hit's first child
#define GPURT_TREE_POP 1       // it takes the pending ray on top of the stack (slot `height`)
#define GPURT_TREE_DONE 2      // the pixel's tree is done

// How many of a hit's two candidate children (A continues the pixel's ray, B is pushed) are worth
// tracing (weight at least GPURT_MIN_WEIGHT): where only B is, it becomes A (leaving on the
// facing side, sideA 1). Returns 0, 1 or 2.
GPURT_FN int rayTreeChildren(GPURT_INOUT(vec3) dirA, GPURT_INOUT(vec3) weightA, GPURT_INOUT(float) sideA, vec3 dirB,
                             vec3 weightB) {
    bool a = max(weightA.x, max(weightA.y, weightA.z)) >= GPURT_MIN_WEIGHT;
    bool b = max(weightB.x, max(weightB.y, weightB.z)) >= GPURT_MIN_WEIGHT;
    if (!a && b) {  // only the second is worth tracing: it continues the pixel's ray
        dirA = dirB;
        weightA = weightB;
        sideA = 1.0f;
        return 1;
    }
    return a ? (b ? 2 : 1) : 0;
}

// Whether a hit of the ray at `depth` (hits after the primary one), in a tree that has taken
// `rays` rays, may spawn children.
GPURT_FN bool rayTreeMaySpawn(int depth, int rays, int maxBounces) {
    return depth < maxBounces && rays < GPURT_TREE_RAYS;
}

// The tree's next step after a round whose hit spawned `children` (0, 1 or 2; 0 for a miss) in a
// tree of depth, stack height and ray count as given, with `slots` stack slots: updates them and
// says whether the second child is pushed (into slot height - 1 after the call, with the new
// depth); a POP takes slot `height` (after the call) and its depth.
GPURT_FN int rayTreeNext(int children, int slots, GPURT_INOUT(int) depth, GPURT_INOUT(int) height,
                         GPURT_INOUT(int) rays, GPURT_OUT(bool) push) {
    push = false;
    if (children > 0) {
        depth += 1;
        rays += 1;
        if (children == 2 && rays < GPURT_TREE_RAYS && height < slots) {
            push = true;
            height += 1;
            rays += 1;
        }
        return GPURT_TREE_CONTINUE;
    }
    if (height > 0) {
        height -= 1;
        return GPURT_TREE_POP;
    }
    return GPURT_TREE_DONE;
}

#endif
