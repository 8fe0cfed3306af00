#include "raytrace/MaterialRecord.h"

#include "raytrace/SurfaceTexture.h"

namespace gpurt {

raymath::MaterialRecord materialRecord(const Scene& scene, uint32_t prim, float u, float v) {
    const Material& m = scene.materials[scene.materialIds[prim]];
    raymath::MaterialRecord r = materialRecord(m);
    r.kd = diffuseAt(scene, m, prim, u, v);
    r.kd = r.kd * vertexColorAt(scene, prim, u, v);
    return r;
}

raymath::MaterialRecord materialRecord(const Material& m) {
    raymath::MaterialRecord r;
    r.model = m.model;
    r.kd = m.diffuse;
    r.ks = m.specular;
    r.ns = m.shininess;
    r.reflectivity = m.reflectivity;
    r.tf = m.transmission;
    r.ior = m.ior;
    r.emission = m.emission;
    return r;
}

}  // namespace gpurt
