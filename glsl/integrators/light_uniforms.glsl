// One punctual light as uniforms (the wavefront's shadowgen and light passes run once a light;
// SharedPasses.cpp setLightUniforms, from PunctualLights.h punctualOf).
uniform int lightKind;
uniform vec3 lightPosition;
uniform vec3 lightDirection;
uniform vec3 lightColor;
uniform float lightIntensity;
uniform vec2 lightCone;
uniform float lightRange;

PunctualLight uniformLight() {
    return PunctualLight(lightKind, lightPosition, lightDirection, lightColor, lightIntensity, lightCone, lightRange);
}
