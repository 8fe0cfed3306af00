// Ray math shared word for word by the GLSL kernels (#include "common/raymath.h") and the C++
// CPU backend (src/raytrace/common/RayMath.h includes it inside a namespace with `using namespace glm`),
// so that both backends evaluate the same float operations in the same order.
// Only the common subset of GLSL 4.50 and C++/GLM: no swizzle writes, float literals with 'f'.
#ifndef GPURT_RAYMATH_H
#define GPURT_RAYMATH_H

#ifdef __cplusplus
#define GPURT_FN inline
// GPURT_INLINE_FN: a function of a traversal's inner loop, inlined into each caller on the cpu
// (so that closest hit and any hit get a copy each, anyHit a constant); GLSL inlines every function.
#define GPURT_INLINE_FN inline __attribute__((always_inline))
#define GPURT_OUT(T) T&
#define GPURT_INOUT(T) T&
#define GPURT_PRECISE
#else
#define GPURT_FN
#define GPURT_INLINE_FN
#define GPURT_OUT(T) out T
#define GPURT_INOUT(T) inout T
#define GPURT_PRECISE precise
#endif

// Ray states (Christen 2005, table 5.2).
#define RAY_INACTIVE 0  // no ray in this element (missed the grid's box, or no secondary ray)
#define RAY_ACTIVE 1    // traversing: the traverser moves it to the next non-empty cell
#define RAY_WAIT 2      // in a non-empty cell: waiting for the intersector
#define RAY_DEAD 3      // done: hit found (hit.w >= 0) or left the grid (hit.w < 0)
#define RAY_OVERFLOW 4  // stopped by the step limit (a bug or a pathological grid; reported)

#define GPURT_FAR 1e30f  // "no boundary": stands for +infinity in tMax and ray limits

// normalize(a) = a / sqrt(dot(a, a)) exactly as the contract writes it (GLSL's and GLM's
// normalize may use an approximate inverse square root).
GPURT_FN vec3 contractNormalize(vec3 a) { return a / sqrt(dot(a, a)); }

// The contract's primary ray through pixel (i, j), j counted from the top. `tanHalf` is
// float(tan(fovy * pi / 360)) computed in double; `aspect` = float(W) / float(H).
// cameraRayThrough: the same through any point (x, y) of the image plane, in pixels from the
// top left corner (the centre of pixel (i, j) is (i + 0.5, j + 0.5)); for --spp samples.
GPURT_FN vec3 cameraRayThrough(vec3 forward, vec3 right, vec3 upOrtho, float tanHalf,
                               float aspect, float x, float y, float width, float height) {
    float u = (x / width * 2.0f - 1.0f) * tanHalf * aspect;
    float v = (1.0f - y / height * 2.0f) * tanHalf;
    return contractNormalize(forward + u * right + v * upOrtho);
}

GPURT_FN vec3 cameraRayDirection(vec3 forward, vec3 right, vec3 upOrtho, float tanHalf,
                                 float aspect, float i, float j, float width, float height) {
    return cameraRayThrough(forward, right, upOrtho, tanHalf, aspect, i + 0.5f, j + 0.5f, width,
                            height);
}

// The thin lens (CONTRACT.md, depth of field). aperturePoint: the point of the aperture that the
// sample numbers u in [0, 1)^2 choose, in lens radii along (right, upOrtho): uniform on the unit
// disc for blades 0 (Shirley and Chiu's concentric map, which keeps the sampler's strata), else
// uniform on the regular polygon of `blades` corners on the unit circle, the first `rotation`
// radians from right towards upOrtho (u.x chooses the triangle (centre, corner k, corner k + 1),
// all of one area, and stretched back to [0, 1) places the point in it with u.y).
GPURT_FN vec2 aperturePoint(vec2 u, int blades, float rotation) {
    if (blades == 0) {
        vec2 a = u * 2.0f - 1.0f;
        if (a.x == 0.0f && a.y == 0.0f) return vec2(0.0f);
        float r = a.y;
        float phi = 1.57079633f - 0.785398163f * (a.x / a.y);
        if (abs(a.x) > abs(a.y)) {
            r = a.x;
            phi = 0.785398163f * (a.y / a.x);
        }
        return vec2(cos(phi), sin(phi)) * r;
    }
    float k = min(floor(u.x * float(blades)), float(blades - 1));
    float s = sqrt(min(u.x * float(blades) - k, 1.0f));
    float a0 = rotation + 6.28318531f * k / float(blades);
    float a1 = rotation + 6.28318531f * (k + 1.0f) / float(blades);
    return vec2(cos(a0), sin(a0)) * (s * (1.0f - u.y)) + vec2(cos(a1), sin(a1)) * (s * u.y);
}

// The ray through the lens point `lens` (aperturePoint, in lens radii) for the pinhole camera's
// ray direction dir: towards the point where dir meets the plane of focus, focusDistance along
// forward from the eye.
GPURT_FN void thinLensRay(vec3 eye, vec3 forward, vec3 right, vec3 upOrtho, vec3 dir, float lensRadius,
                          float focusDistance, vec2 lens, GPURT_OUT(vec3) origin, GPURT_OUT(vec3) direction) {
    vec3 focus = eye + dir * (focusDistance / dot(dir, forward));
    vec3 o = eye + right * (lens.x * lensRadius) + upOrtho * (lens.y * lensRadius);
    origin = o;
    direction = contractNormalize(focus - o);
}

// The parametric range [x, y] in which the ray o + t d lies inside the box; x > y when it misses.
// Axis-parallel rays are handled without dividing by zero.
GPURT_FN vec2 intersectBox(vec3 o, vec3 d, vec3 boxMin, vec3 boxMax) {
    // Vector operations throughout (llvmpipe does not unroll a loop over the axes).
    vec3 t0 = (boxMin - o) / d;
    vec3 t1 = (boxMax - o) / d;
    bvec3 parallel = equal(d, vec3(0.0f));
    vec3 tNear = mix(min(t0, t1), vec3(-GPURT_FAR), parallel);
    vec3 tFar = mix(max(t0, t1), vec3(GPURT_FAR), parallel);
    bvec3 outside = bvec3(ivec3(parallel) * (ivec3(lessThan(o, boxMin)) + ivec3(greaterThan(o, boxMax))));
    if (any(outside)) return vec2(1.0f, 0.0f);
    return vec2(max(tNear.x, max(tNear.y, tNear.z)), min(tFar.x, min(tFar.y, tFar.z)));
}

// Where the segment o + t d, 0 <= t <= tLimit, enters the box (0 when it starts inside), or -1
// when it misses the box (primary ray generation, Purcell 2002: rays that miss are rejected).
GPURT_FN float boxEntry(vec3 o, vec3 d, float tLimit, vec3 boxMin, vec3 boxMax) {
    vec2 box = intersectBox(o, d, boxMin, boxMax);
    float tEnter = max(box.x, 0.0f);
    return tEnter > min(box.y, tLimit) ? -1.0f : tEnter;
}

// Ray parameter at which the ray leaves cell index `cell` along one axis (3D-DDA). Computed from
// the cell's boundary each time instead of accumulating tDelta (Amanatides & Woo 1987), so long
// traversals do not drift.
GPURT_FN float ddaBoundary(float o, float d, float gridMin, float cellSize, int cell) {
    if (d > 0.0f) return (gridMin + float(cell + 1) * cellSize - o) / d;
    if (d < 0.0f) return (gridMin + float(cell) * cellSize - o) / d;
    return GPURT_FAR;
}

// ddaBoundary on all three axes at once, as vector operations (the same float operations per
// axis): llvmpipe does not unroll a loop over the axes, and a loop costs far more there.
GPURT_FN vec3 ddaBoundaries(vec3 o, vec3 d, vec3 gridMin, vec3 cellSize, ivec3 cell) {
    ivec3 next = cell + ivec3(greaterThan(d, vec3(0.0f)));
    vec3 t = (gridMin + vec3(next) * cellSize - o) / d;
    return mix(t, vec3(GPURT_FAR), equal(d, vec3(0.0f)));
}

// Voxel precalculation: the cell containing the point where the ray enters the grid (t = tEnter)
// and the ray parameter of the next boundary along each axis.
GPURT_FN void ddaSetup(vec3 o, vec3 d, float tEnter, vec3 gridMin, vec3 cellSize, ivec3 res,
                       GPURT_OUT(ivec3) voxel, GPURT_OUT(vec3) tMax) {
    vec3 p = o + tEnter * d;
    voxel = clamp(ivec3(floor((p - gridMin) / cellSize)), ivec3(0), res - ivec3(1));
    tMax = ddaBoundaries(o, d, gridMin, cellSize, voxel);
}

// The ray parameter where the ray leaves its current cell.
GPURT_FN float ddaCellExit(vec3 tMax) { return min(tMax.x, min(tMax.y, tMax.z)); }

// One 3D-DDA step to the next cell along the axis whose boundary is nearest (ties: x, then y,
// then z). Returns false when the ray leaves the grid.
GPURT_INLINE_FN bool ddaStep(vec3 o, vec3 d, vec3 gridMin, vec3 cellSize, ivec3 res,
                             GPURT_INOUT(ivec3) voxel, GPURT_INOUT(vec3) tMax) {
    int a = (tMax.x <= tMax.y && tMax.x <= tMax.z) ? 0 : (tMax.y <= tMax.z ? 1 : 2);
    voxel[a] += d[a] > 0.0f ? 1 : -1;
    if (voxel[a] < 0 || voxel[a] >= res[a]) return false;
    tMax[a] = ddaBoundary(o[a], d[a], gridMin[a], cellSize[a], voxel[a]);
    return true;
}

// Empty-space skipping with proximity clouds (Cohen & Sheffer 1994): when every cell within
// chessboard distance k - 1 of the ray's cell is empty (UniformGrid::skip), the ray leaves that
// cube of cells in one move and enters the next cell along it. k = 1 is exactly ddaStep. The
// other axes never move backwards, so rounding cannot make a ray revisit cells. Returns false
// when the ray leaves the grid.
GPURT_INLINE_FN bool ddaLeaveCube(vec3 o, vec3 d, vec3 gridMin, vec3 cellSize, ivec3 res, int k,
                                  GPURT_INOUT(ivec3) voxel, GPURT_INOUT(vec3) tMax) {
    ivec3 lo = max(voxel - ivec3(k - 1), ivec3(0));
    ivec3 hi = min(voxel + ivec3(k - 1), res - ivec3(1));
    bvec3 forward = greaterThan(d, vec3(0.0f));
    vec3 tCube = ddaBoundaries(o, d, gridMin, cellSize, mix(lo, hi, forward));  // leaving the cube
    int axis = (tCube.x <= tCube.y && tCube.x <= tCube.z) ? 0 : (tCube.y <= tCube.z ? 1 : 2);
    ivec3 next = voxel;
    if (k > 1) {
        vec3 p = o + tCube[axis] * d;
        next = clamp(ivec3(floor((p - gridMin) / cellSize)), lo, hi);
        next = mix(min(next, voxel), max(next, voxel), forward);
    }
    next[axis] = forward[axis] ? hi[axis] + 1 : lo[axis] - 1;
    if (next[axis] < 0 || next[axis] >= res[axis]) return false;
    voxel = next;
    tMax = ddaBoundaries(o, d, gridMin, cellSize, voxel);
    return true;
}

// The traversal's step from a cell of skip distance k: ddaLeaveCube, on the cpu with k = 1 as
// ddaStep (the same cell and tMax, DdaTest; one axis's boundary, one division where the cube's
// form takes six: the cpu grid's traversal 13% fewer instructions). llvmpipe runs the vector form
// for every k: there the branch and ddaStep's run-time axis index made traversal 11% slower
// (docs/PERFORMANCE.md, "The cpu grid's step").
GPURT_INLINE_FN bool ddaAdvance(vec3 o, vec3 d, vec3 gridMin, vec3 cellSize, ivec3 res, int k,
                                GPURT_INOUT(ivec3) voxel, GPURT_INOUT(vec3) tMax) {
#ifdef __cplusplus
    if (k == 1) return ddaStep(o, d, gridMin, cellSize, res, voxel, tMax);
#endif
    return ddaLeaveCube(o, d, gridMin, cellSize, res, k, voxel, tMax);
}

// The watertight ray/triangle test (Woop, Benthin and Wald 2013, "Watertight Ray/Triangle
// Intersection", as Embree and pbrt-v4 use it). The triangle is moved into the ray's frame: the
// ray's origin to 0, its direction sheared onto +z (after the axes are permuted so that z is the
// largest component of |d|), so that the test is 2D: the signs of the three edge functions
// U, V, W at the origin. Each vertex's sheared coordinates depend on that vertex and the ray only,
// and a shared edge's function in the two triangles is the same two products subtracted the other
// way round (an exact negation), so a ray through a shared edge or vertex of a closed mesh meets
// at least one of its triangles: no ray passes between them (Moller-Trumbore, with edges stored
// as rounded differences, lets a few through). Rounding keeps each product's order
// (monotonic), so a computed edge function never has the wrong sign, only sometimes 0; 0 counts
// as on the edge (inclusive), which can add a hit next to an edge but never loses one. The
// paper's double-precision recomputation when U, V or W is 0 (which removes such extra hits) is
// left out, as Embree does: GLSL would pay for doubles on every lane, and it does not change
// whether the test is watertight. GPURT_PRECISE keeps the kernels' compiler from fusing the
// products into fused multiply-adds or reordering them, which would break the exact negation, and
// keeps every kernel that inlines the test (trace kernels, megakernels) computing the same hits as
// C++, which compiles without contraction.
//
// The per-ray part, made once before a traversal: the axis kz of the largest |d| component, kx
// and ky after it (swapped when d[kz] < 0, keeping the triangles' winding), and the shear.
struct WatertightRay {
    vec3 o;      // the ray's origin
    int kx;      // the axes of the ray's frame: z = kz is the largest component of |d|
    int ky;
    int kz;
    vec3 shear;  // (d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz])
};

GPURT_FN WatertightRay watertightRay(vec3 o, vec3 d) {
    WatertightRay r;
    r.o = o;
    vec3 a = abs(d);
    r.kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    r.kx = r.kz == 2 ? 0 : r.kz + 1;
    r.ky = r.kx == 2 ? 0 : r.kx + 1;
    if (d[r.kz] < 0.0f) {
        int k = r.kx;
        r.kx = r.ky;
        r.ky = k;
    }
    GPURT_PRECISE float sz = 1.0f / d[r.kz];
    r.shear = vec3(d[r.kx] * sz, d[r.ky] * sz, sz);
    return r;
}

// The test of the ray r (watertightRay) against the triangle v0, v1, v2: true with t (along the
// ray's d), u (the weight of v1) and v (of v2) on a hit (edges inclusive, any facing);
// degenerate triangles and triangles seen edge-on (U + V + W == 0) are never hit.
GPURT_FN bool intersectTriangle(WatertightRay r, vec3 v0, vec3 v1, vec3 v2, GPURT_OUT(float) t,
                                GPURT_OUT(float) u, GPURT_OUT(float) v) {
    GPURT_PRECISE vec3 a = v0 - r.o;
    GPURT_PRECISE vec3 b = v1 - r.o;
    GPURT_PRECISE vec3 c = v2 - r.o;
    GPURT_PRECISE float ax = a[r.kx] - r.shear.x * a[r.kz];
    GPURT_PRECISE float ay = a[r.ky] - r.shear.y * a[r.kz];
    GPURT_PRECISE float bx = b[r.kx] - r.shear.x * b[r.kz];
    GPURT_PRECISE float by = b[r.ky] - r.shear.y * b[r.kz];
    GPURT_PRECISE float cx = c[r.kx] - r.shear.x * c[r.kz];
    GPURT_PRECISE float cy = c[r.ky] - r.shear.y * c[r.kz];
    GPURT_PRECISE float eu = cx * by - cy * bx;  // U: the edge v1 v2, the weight of v0
    GPURT_PRECISE float ev = ax * cy - ay * cx;  // V: the edge v2 v0, the weight of v1
    GPURT_PRECISE float ew = bx * ay - by * ax;  // W: the edge v0 v1, the weight of v2
    bool negative = eu < 0.0f || ev < 0.0f || ew < 0.0f;
    bool positive = eu > 0.0f || ev > 0.0f || ew > 0.0f;
    GPURT_PRECISE float det = eu + ev + ew;
    GPURT_PRECISE float tScaled = eu * a[r.kz] + ev * b[r.kz] + ew * c[r.kz];
    GPURT_PRECISE float invDet = 1.0f / det;
    GPURT_PRECISE float tHit = tScaled * r.shear.z * invDet;
    GPURT_PRECISE float uHit = ev * invDet;
    GPURT_PRECISE float vHit = ew * invDet;
    t = tHit;
    u = uHit;
    v = vHit;
    return det != 0.0f && !(negative && positive);
}

// Whether a ray of direction d meets the back face of the triangle of edges e1 = v1 - v0,
// e2 = v2 - v0: the front is the side from which v0, v1, v2 run counter-clockwise (glTF), i.e.
// the side cross(e1, e2) points to.
GPURT_FN bool backFacing(vec3 d, vec3 e1, vec3 e2) {
    return dot(d, cross(e1, e2)) > 0.0f;
}

#endif
