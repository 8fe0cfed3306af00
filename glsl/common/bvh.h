// The BVH traversal (accel/bvh/Bvh.h), shared word for word by the kernel
// (glsl/accel/bvh/trace.frag) and the cpu backend (accel/bvh/BvhCpu.cpp), after raymath.h.
// The includer defines how the tree is read:
//   GPURT_BVH_PARAMS    leading parameters of the functions (empty in GLSL: the samplers are
//                       uniforms), GPURT_BVH_ARGS the matching arguments
//   GPURT_BVH_NODE(i)   texel i (uvec4) of the nodes: two a node, one per child (bvhChildTexel)
//   GPURT_BVH_TRI(i)    texel i (vec4) of the leaf-ordered triangle list: three an entry, (v0, id),
//                       (v1, coverage flags), (v2, 0), as the grid's cell lists
//   GPURT_BVH_BOX_MIN   the scene box's corner and the size of one quantisation step on each axis
//   GPURT_BVH_BOX_STEP  (vec3 each): a child's box is stored in 16-bit steps of the scene box
//   GPURT_BVH_COVERED(id, flags, u, v, d, e1, e2, anyHit)  whether a candidate hit of triangle id at (u, v)
//                       counts (alpha coverage, back-face culling: common/alpha.h); flags: the
//                       triangle's coverage flags (GPURT_COVER_*), 0 when it counts everywhere
// A visit tests both children's boxes, intersects the triangles of the children that are leaves,
// the nearer first, in one loop, and goes on into the nearer inner child with the farther one on
// a stack (ordered traversal); a popped node is visited without a second box test.
#ifndef GPURT_BVH_H
#define GPURT_BVH_H

// Entries of the traversal stack: the deepest tree a build makes (kBvhMaxDepth).
#define GPURT_BVH_STACK 64

// A child in one texel (RGBA32UI): its box in steps of the scene box, rounded outwards,
// x = min.x | min.y << 16, y = min.z | max.x << 16, z = max.y | max.z << 16, and
// w = ref << 4 | count: a leaf of `count` triangles from entry `ref` of the list (count > 0), an
// inner node `ref` (count 0, ref > 0), or nothing (w = 0; its box is empty: min > max).
GPURT_FN void bvhChildBox(uvec4 texel, vec3 boxMin, vec3 boxStep, GPURT_OUT(vec3) lo, GPURT_OUT(vec3) hi) {
    lo = boxMin + vec3(float(texel.x & 65535u), float(texel.x >> 16u), float(texel.y & 65535u)) * boxStep;
    hi = boxMin + vec3(float(texel.y >> 16u), float(texel.z & 65535u), float(texel.z >> 16u)) * boxStep;
}

// The entry and exit parameters of o + t d in a box, with invD = 1 / d (no zero component).
GPURT_FN vec2 bvhSlabs(vec3 o, vec3 invD, vec3 boxMin, vec3 boxMax) {
    vec3 t0 = (boxMin - o) * invD;
    vec3 t1 = (boxMax - o) * invD;
    vec3 tNear = min(t0, t1);
    vec3 tFar = max(t0, t1);
    return vec2(max(max(tNear.x, tNear.y), max(tNear.z, 0.0f)), min(tFar.x, min(tFar.y, tFar.z)));
}

// The two children of node: where o + t d enters and leaves each one's box (bvhSlabs), and their
// w fields (ref << 4 | count, bvhChildBox).
GPURT_INLINE_FN void bvhChildren(GPURT_BVH_PARAMS int node, vec3 o, vec3 invD, GPURT_OUT(vec2) a, GPURT_OUT(vec2) b,
                                 GPURT_OUT(uint) wA, GPURT_OUT(uint) wB) {
    uvec4 ta = GPURT_BVH_NODE(2 * node);
    uvec4 tb = GPURT_BVH_NODE(2 * node + 1);
    vec3 lo;
    vec3 hi;
    bvhChildBox(ta, GPURT_BVH_BOX_MIN, GPURT_BVH_BOX_STEP, lo, hi);
    a = bvhSlabs(o, invD, lo, hi);
    bvhChildBox(tb, GPURT_BVH_BOX_MIN, GPURT_BVH_BOX_STEP, lo, hi);
    b = bvhSlabs(o, invD, lo, hi);
    wA = ta.w;
    wB = tb.w;
}

// The triangles of two leaves, countA from entry refA of the list and countB from refB (0: not a
// leaf, or not entered), A's first when aFirst, against the ray o + t d (ray: its watertightRay): a
// hit nearer than bestT replaces (bestT, bestId, bestU, bestV); with anyHit the first such hit ends
// the loop. tests counts the triangle tests. One loop over both lists, for the SIMD lanes of a
// kernel to share however many of the two are leaves.
GPURT_INLINE_FN void bvhLeafHits(GPURT_BVH_PARAMS bool aFirst, int refA, int countA, int refB, int countB,
                                 WatertightRay ray, vec3 d, bool anyHit, GPURT_INOUT(float) bestT,
                                 GPURT_INOUT(int) bestId, GPURT_INOUT(float) bestU, GPURT_INOUT(float) bestV,
                                 GPURT_INOUT(int) tests) {
    int first0 = aFirst ? refA : refB;
    int count0 = aFirst ? countA : countB;
    int first1 = aFirst ? refB : refA;
    int count1 = aFirst ? countB : countA;
    for (int i = 0; i < count0 + count1; ++i) {
        int k = i < count0 ? first0 + i : first1 + (i - count0);
        tests += 1;
        vec4 tri = GPURT_BVH_TRI(3 * k);
        vec4 v1Flags = GPURT_BVH_TRI(3 * k + 1);
        vec3 v0 = vec3(tri);
        vec3 v1 = vec3(v1Flags);
        vec3 v2 = vec3(GPURT_BVH_TRI(3 * k + 2));
        float t;
        float u;
        float v;
        if (intersectTriangle(ray, v0, v1, v2, t, u, v) && t > 0.0f && t < bestT &&
            GPURT_BVH_COVERED(int(tri.w), v1Flags.w, u, v, d, v1 - v0, v2 - v0, anyHit)) {
            bestT = t;
            bestU = u;
            bestV = v;
            bestId = int(tri.w);
            if (anyHit) break;
        }
    }
}

// The closest hit of o + t d with 0 < t < tLimit (any hit with anyHit): the triangle id or -1,
// with t, u, v; steps counts the nodes visited, tests the triangle tests, state is RAY_DEAD, or
// RAY_OVERFLOW when the ray visited maxSteps nodes or the stack ran out (a bug or a damaged tree:
// reported, never a hang; steps is then maxSteps).
GPURT_INLINE_FN int bvhTrace(GPURT_BVH_PARAMS vec3 o, vec3 d, float tLimit, bool anyHit, int maxSteps,
                             GPURT_OUT(float) bestT, GPURT_OUT(float) bestU, GPURT_OUT(float) bestV,
                             GPURT_OUT(int) steps, GPURT_OUT(int) tests, GPURT_OUT(int) state) {
    vec3 invD = 1.0f / mix(d, vec3(1e-30f), equal(d, vec3(0.0f)));
    WatertightRay ray = watertightRay(o, d);  // the triangle test's per-ray part
    int stack[GPURT_BVH_STACK];
    int top = 0;
    int node = 0;
    int bestId = -1;
    bestT = tLimit;
    bestU = 0.0f;
    bestV = 0.0f;
    steps = 0;
    tests = 0;
    state = RAY_DEAD;
    while (node >= 0) {
        if (steps >= maxSteps) {
            state = RAY_OVERFLOW;
            break;
        }
        steps += 1;
        vec2 a;
        vec2 b;
        uint wA;
        uint wB;
        bvhChildren(GPURT_BVH_ARGS node, o, invD, a, b, wA, wB);
        int refA = int(wA >> 4u);
        int countA = int(wA & 15u);
        int refB = int(wB >> 4u);
        int countB = int(wB & 15u);
        bool enterA = a.x <= a.y && a.x < bestT;
        bool enterB = b.x <= b.y && b.x < bestT;
        bool aFirst = a.x <= b.x;
        bvhLeafHits(GPURT_BVH_ARGS aFirst, refA, enterA ? countA : 0, refB, enterB ? countB : 0, ray, d, anyHit,
                    bestT, bestId, bestU, bestV, tests);  // leaf children, the nearer first
        if (anyHit && bestId >= 0) break;
        // Inner children still in front of the best hit.
        enterA = enterA && countA == 0 && refA > 0 && a.x < bestT;
        enterB = enterB && countB == 0 && refB > 0 && b.x < bestT;
        if (enterA && enterB) {
            if (top == GPURT_BVH_STACK) {
                state = RAY_OVERFLOW;
                steps = maxSteps;  // the callers see an overflow in the steps
                break;
            }
            stack[top] = aFirst ? refB : refA;
            top += 1;
            node = aFirst ? refA : refB;
        } else if (enterA) {
            node = refA;
        } else if (enterB) {
            node = refB;
        } else if (top > 0) {
            top -= 1;
            node = stack[top];
        } else {
            node = -1;
        }
    }
    return bestId;
}

#endif
