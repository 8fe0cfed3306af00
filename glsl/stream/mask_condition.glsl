// The masking condition shared by the mask pass (mask.frag) and early-exit kernels (GPUKernel
// wraps their main): an element is active when its state, one channel of a state stream, lies in
// [gpu_maskRange.x, gpu_maskRange.y].

uniform sampler2D gpu_maskState;
uniform int gpu_maskChannel;
uniform vec2 gpu_maskRange;

bool gpu_maskAccepts() {
    float state = texelFetch(gpu_maskState, ivec2(gl_FragCoord.xy), 0)[gpu_maskChannel];
    return state >= gpu_maskRange.x && state <= gpu_maskRange.y;
}
