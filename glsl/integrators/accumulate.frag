// The sample loop's sum (--spp): adds this sample's pixel colour to the running sum of the
// pixel's samples. The mean is the sum divided by the samples taken (GpuTracer::render, and the
// viewer's present pass), so each sample costs one more pass over the chain, not more.
#include "common/stream.glsl"

uniform sampler2D colorState;  // this sample's colour
uniform sampler2D sumState;    // in place

layout(location = 0) out vec4 sum;

void main() { sum = vec4(readStream(sumState).xyz + readStream(colorState).xyz, 0.0f); }
