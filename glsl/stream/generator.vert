// The stream generator's vertex shader (GPUStreamGenerator): covers the viewport with one
// triangle (vertex ids 0..2, the cheaper choice: no diagonal seam for the rasterizer to split
// 4x2 blocks along) or a quad as a triangle strip (vertex ids 4..7). Positions come from
// gl_VertexID: no vertex buffers.

uniform float gpu_depth;  // NDC z of the primitive; early-Z masking draws at 0 (window depth 0.5)

void main() {
    vec2 p;
    if (gl_VertexID < 4)
        p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID >> 1) * 4 - 1);  // (-1,-1) (3,-1) (-1,3)
    else
        p = vec2(((gl_VertexID - 4) & 1) * 2 - 1, ((gl_VertexID - 4) >> 1) * 2 - 1);
    gl_Position = vec4(p, gpu_depth, 1.0);
}
