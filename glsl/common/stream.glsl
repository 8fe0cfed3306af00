// Helpers for stream kernels: the element a fragment works on is the texel under it.

// The 2D index of this fragment's stream element.
ivec2 streamIndex() { return ivec2(gl_FragCoord.xy); }

// The element of `s` at this fragment's index (a stream "read"; other texels are "gathers").
vec4 readStream(sampler2D s) { return texelFetch(s, streamIndex(), 0); }
uvec4 readStream(usampler2D s) { return texelFetch(s, streamIndex(), 0); }
ivec4 readStream(isampler2D s) { return texelFetch(s, streamIndex(), 0); }
