// Ambient occlusion's gl form (integrators/GlRegistry.h): its megakernel, one pass a sample
// (glsl/integrators/ao/megakernel.frag). It has no wavefront chain: one trace and one occlusion ray
// a sample leave nothing for passes to share.
#include "raytrace/integrators/GlRegistry.h"
#include "raytrace/integrators/Megakernel.h"

namespace gpurt {

std::unique_ptr<GlIntegrator> makeAoGl(const GlIntegratorSetup& s) {    return std::make_unique<OnePassMegakernelGl>(s.pipeline, s.textures, "aoMegakernel", "integrators/ao/megakernel.frag",                                                 s.maxLights, s.aovs);}}  // namespace gpurt
