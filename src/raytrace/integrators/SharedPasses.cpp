#include "raytrace/integrators/SharedPasses.h"
#include "raytrace/lights/PunctualLights.h"

namespace gpurt {

std::vector<std::string> passDefines(unsigned flags) {
    std::vector<std::string> defines;
    if (flags & kEmitterPass) defines.push_back("EMITTER");
    if (flags & kPathPass) defines.push_back("PATH");
    if (flags & kPackPass) defines.push_back("PACK");
    if (flags & kLastRound) defines.push_back("LAST_ROUND");
    if (flags & kPixelCentre) defines.push_back("PIXEL_CENTRE");
    if (flags & kEnvironmentPass) defines.push_back("ENVIRONMENT");
    if (flags & kCameraPass) defines.push_back("CAMERA");
    if (flags & kAovPass) defines.push_back("AOVS");
    return defines;
}

void declareSurfacePass(GPUKernel& k, GpuPipeline& p, bool path) {
    k.addInput(p.rayOrigin, "rayOrigin").addInput(p.rayDir, "rayDir").addInput(p.hit, "hitState");
    k.addInput(p.weight, "weight").addInOut(p.color, "colorState");
    k.addOutput(p.surfacePoint).addOutput(p.surfaceNormal).addOutput(p.surfaceView).addOutput(p.localColor);
    k.addOutput(p.surfaceShading);
    if (path) k.addInput(p.pathState, "pathState");
}

void declareShadowgenPass(GPUKernel& k, GpuPipeline& p, bool path, bool emitter) {
    k.addInput(p.surfacePoint, "surfacePoint").addInput(p.surfaceNormal, "surfaceNormal");
    k.addOutput(p.rayOrigin).addOutput(p.rayDir);
    if (emitter && p.needs.emitters) k.addOutput(p.lightSample);
    if (emitter && path) k.addInput(p.pathState, "pathState");
    if (path)  // the lobes at the hit's texture coordinates
        k.addInput(p.surfaceView, "surfaceView").addInput(p.surfaceShading, "surfaceShading");
}

void declareEnvironmentShadowgenPass(GPUKernel& k, GpuPipeline& p) {
    k.addInput(p.surfacePoint, "surfacePoint").addInput(p.surfaceNormal, "surfaceNormal");
    k.addOutput(p.rayOrigin).addOutput(p.rayDir).addOutput(p.lightSample);
    k.addInput(p.pathState, "pathState");
    k.addInput(p.surfaceView, "surfaceView").addInput(p.surfaceShading, "surfaceShading");
}

void declareLightPass(GPUKernel& k, GpuPipeline& p, bool emitter) {
    k.addInput(p.surfacePoint, "surfacePoint").addInput(p.surfaceNormal, "surfaceNormal");
    k.addInput(p.surfaceView, "surfaceView").addInput(p.hit, "hitState");
    if (emitter) k.addInput(p.lightSample, "lightSample");
    k.addInOut(p.localColor, "localState");
    k.addInput(p.surfaceShading, "surfaceShading");
}

void declareAccumulatePass(GPUKernel& k, GpuPipeline& p, const GPUFloatArray& colour) {
    if (p.needs.sums) k.addInput(colour, "colorState").addInOut(p.sampleSum, "sumState");
    if (p.needs.adaptive) {  // the odd samples' sums too, for the active pixels only
        k.addDefine("ODD_SUM").addInOut(p.oddSum, "oddState").setMask(p.activeMask.get(), false);
    }
    if (p.needs.variance) k.addDefine("SQUARE_SUM").addInOut(p.squareSum, "squareState");
    if (p.needs.features && p.needs.sums) {
        k.addDefine("FEATURE_SUM").addInput(p.pixelAlbedo, "albedoSample").addInput(p.pixelNormal, "normalSample");
        k.addInOut(p.albedoSum, "albedoState").addInOut(p.normalSum, "normalState");
    }
}

void setLightUniforms(GPUKernel& k, const Light& light) {
    const raymath::PunctualLight l = punctualOf(light);
    k.setUniform("lightKind", l.kind)
        .setUniform("lightPosition", l.position)
        .setUniform("lightDirection", l.direction)
        .setUniform("lightColor", l.color)
        .setUniform("lightIntensity", l.intensity)
        .setUniform("lightCone", l.cone)
        .setUniform("lightRange", l.range);
}

}  // namespace gpurt
