// Texture filtering shared word for word by the GLSL kernels (glsl/scene/shading.glsl, which
// fetches the texels) and the CPU backend (src/raytrace/materials/SurfaceTexture.cpp), after
// common/raymath.h. Same rules as raymath.h.
//
// Image coordinates: (0, 0) is the top-left corner of the image and (1, 1) its bottom-right one,
// glTF's convention (OBJ's vt, whose v axis points up, are stored as (u, 1 - v)). Filtering is
// bilinear between the four texel centres around the point, in linear colour (each texel's
// sRGB bytes decoded first), as a GPU samples an sRGB texture with GL_LINEAR.
#ifndef GPURT_TEXTURE_H
#define GPURT_TEXTURE_H

#ifndef GPURT_RAYMATH_H
#error "include common/raymath.h before common/texture.h"
#endif

// Wrap modes (glTF sampler wrapS / wrapT; MTL textures repeat). Scene.h's Texture uses the same values.
#define GPURT_WRAP_REPEAT 0
#define GPURT_WRAP_CLAMP 1
#define GPURT_WRAP_MIRROR 2

// The texture coordinates at barycentrics (u, v) of a triangle whose corners have t0, t1, t2.
GPURT_FN vec2 interpolateTexcoord(vec2 t0, vec2 t1, vec2 t2, float u, float v) {
    return t0 * (1.0f - u - v) + t1 * u + t2 * v;
}

// Coordinate t folded into [0, 1] by the wrap mode (anything not finite to 0).
GPURT_FN float wrapCoordinate(float t, int mode) {
    float m;
    if (mode == GPURT_WRAP_CLAMP) {
        m = min(max(t, 0.0f), 1.0f);
    } else if (mode == GPURT_WRAP_MIRROR) {
        m = t - 2.0f * floor(0.5f * t);  // [0, 2)
        if (m > 1.0f) m = 2.0f - m;
    } else {
        m = t - floor(t);
    }
    return m >= 0.0f && m <= 1.0f ? m : 0.0f;
}

// Texel i of a row of n (i in [-1, n]), wrapped: a repeating texture's neighbour across the edge
// is the texel at the other end; clamped and mirrored ones repeat their edge texel.
GPURT_FN int wrapTexel(int i, int n, int mode) {
    if (mode == GPURT_WRAP_REPEAT) return i < 0 ? n - 1 : (i >= n ? 0 : i);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

// The bilinear footprint of image coordinates t in a w x h texture: the texel columns
// (columns.x, columns.y), rows (rows.x, rows.y) and the weights f of the second column and row.
GPURT_FN void bilinearFootprint(vec2 t, int w, int h, int wrapS, int wrapT, GPURT_OUT(ivec2) columns,
                                GPURT_OUT(ivec2) rows, GPURT_OUT(vec2) f) {
    float x = wrapCoordinate(t.x, wrapS) * float(w) - 0.5f;
    float y = wrapCoordinate(t.y, wrapT) * float(h) - 0.5f;
    float fx = floor(x);
    float fy = floor(y);
    f = vec2(x - fx, y - fy);
    int ix = int(fx);  // in [-1, w - 1]
    int iy = int(fy);
    columns = ivec2(wrapTexel(ix, w, wrapS), wrapTexel(ix + 1, w, wrapS));
    rows = ivec2(wrapTexel(iy, h, wrapT), wrapTexel(iy + 1, h, wrapT));
}

// The filtered colour from the footprint's four texels (c01: second column, first row).
GPURT_FN vec3 bilinearBlend(vec3 c00, vec3 c01, vec3 c10, vec3 c11, vec2 f) {
    vec3 top = c00 * (1.0f - f.x) + c01 * f.x;
    vec3 bottom = c10 * (1.0f - f.x) + c11 * f.x;
    return top * (1.0f - f.y) + bottom * f.y;
}

// The sRGB transfer function's inverse (IEC 61966-2-1) for an 8-bit code: the kernels read it from
// a table of the 256 values the C++ side computed with this function.
GPURT_FN float srgbDecode8(int code) {
    float c = float(code) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : pow((c + 0.055f) / 1.055f, 2.4f);
}

#endif
