// The contract camera as uniforms (GpuPipeline::setCamera), for the kernels that generate primary
// rays: one ray per pixel through the pixel centre (common/raymath.h cameraRayDirection).
uniform vec3 eye;
uniform vec3 forward;
uniform vec3 right;
uniform vec3 upOrtho;
uniform float tanHalf;
uniform float aspect;
uniform vec2 imageSize;

// The direction of this fragment's primary ray (stream row y = image row from the top).
vec3 primaryDirection() {
    vec2 pixel = floor(gl_FragCoord.xy);
    return cameraRayDirection(forward, right, upOrtho, tanHalf, aspect, pixel.x, pixel.y,
                              imageSize.x, imageSize.y);
}
