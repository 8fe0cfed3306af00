// The mask pass (GPUMask, EarlyZ and Stencil modes; Purcell et al. 2002, section 4): writes depth
// or stencil for the elements whose state matches and discards the others. No colour output.
#include "mask_condition.glsl"

void main() {
    if (!gpu_maskAccepts()) discard;
}
