// glTF materials (CONTRACT.md, "Physically based materials") on both backends:
//  - the white furnace: a sphere of each of several (metallic, roughness, base colour) under a
//    uniform environment of radiance 1, path traced, shows its directional albedo E(n.v), computed
//    by quadrature of Appendix B's BRDF in the test (GltfReference.h), per region of n.v, within
//    the samples' standard error;
//  - normal maps: the shading normal a constant normal map gives a quad (shown by the debug
//    normal model as 0.5 n + 0.5) is the tangent frame's closed form: T along +u, B along -v
//    (image up), N the face's normal, bent by the texel's (2 c - 1) with x, y times the scale;
//  - vertex tangents (glTF TANGENT): the normal map bends the normal in the given frame, T the
//    tangent made orthogonal to N, B = cross(N, T) w; degenerate tangents (zero, NaN, infinite,
//    along the normal) give the generated frame's image exactly; a packed scene renders as its
//    source;
//  - metallic-roughness, emissive and occlusion maps: a texture of one value is the factor times
//    that value (against the same material with the value folded into its factors);
//  - transmissionTexture: a glTF quad whose transmission is the factor times the texture's R in
//    bands of 0, 128/255 and 1 shows, band by band, the radiance the formula gives (the opaque
//    dielectric's direct light and ambient, the emitter behind through the transmitting share);
//  - KHR_materials_volume: a slab seen through in a uniform sky transmits Beer-Lambert's
//    attenuationColor^(length inside / attenuationDistance), on every backend and kernel form;
//  - KHR_materials_anisotropy: the direction in the tangent frame (TANGENT or the texture
//    coordinates'), its map, the furnace;
//  - real files made by others (tests/assets/gltf/khronos) render without a "not used" warning.
#include "../common/GLTest.h"
#include "EnvironmentTestMaps.h"
#include "GltfReference.h"
#include "LiftedNormal.h"
#include "TestScenes.h"
#include "raytrace/accel/bvh/BvhAccelerator.h"
#include "raytrace/accel/grid/GridAccelerator.h"
#include "raytrace/materials/MaterialRecord.h"
#include "raytrace/scene/PackedScene.h"
#include "scene/GltfLoader.h"
#include "../common/TransmissionQuad.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace gpurt::test {
namespace {

class GltfMaterials : public GLTest {};

struct Mean {
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    void add(double x) {
        sum += x;
        sum2 += x * x;
        ++n;
    }
    double mean() const { return sum / double(n); }
    double error() const {
        const double m = mean();
        return n > 1 ? std::sqrt(std::max(0.0, sum2 / double(n) - m * m) / double(n - 1)) : 0.0;
    }
};

// Every channel of every pixel that sees the object (the furnace's sphere).
Mean objectMean(const RenderOutput& out) {
    Mean m;
    for (size_t at = 0; at < out.color.size(); ++at)
        if (out.prim[at] >= 0.0f)
            for (int c = 0; c < 3; ++c) m.add(out.color[at][c]);
    return m;
}

uint32_t addGltfMaterial(Scene& scene, const GltfParams& p) {
    Material m;
    m.model = GPURT_MODEL_GLTF;
    m.diffuse = glm::vec3(p.base);
    m.metallic = float(p.metallic);
    m.roughness = float(p.roughness);
    m.specularFactor = float(p.specularFactor);
    m.specularColor = glm::vec3(p.specularColor);
    m.clearcoat = float(p.clearcoat);
    m.clearcoatRoughness = float(p.clearcoatRoughness);
    m.sheenColor = glm::vec3(p.sheenColor);
    m.sheenRoughness = float(p.sheenRoughness);
    m.iridescenceFactor = float(p.iridescence);
    m.iridescenceIor = float(p.iridescenceIor);
    m.iridescenceThicknessMin = m.iridescenceThicknessMax = float(p.iridescenceThickness);
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
}

// The contract's camera ray through the centre of pixel (i, j) of a size x size image (written
// out here, independently of raytrace/Camera).
glm::dvec3 pixelRay(const CameraSpec& spec, int size, int i, int j) {
    const glm::dvec3 forward = glm::normalize(glm::dvec3(spec.target - spec.eye));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(spec.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double t = std::tan(double(spec.fovy) * gltfref::kPi / 360.0);
    const double x = (2.0 * (i + 0.5) / size - 1.0) * t, y = (1.0 - 2.0 * (j + 0.5) / size) * t;
    return glm::normalize(forward + x * right + y * up);
}

// Each material of `cases` on a sphere in the white furnace, path traced on both backends: every
// pixel shows the directional albedo (GltfReference.h gltfReferenceCoatedAlbedo) at its n.v.
void expectFurnaceAlbedo(const std::vector<GltfParams>& cases) {
    const EnvironmentImage white = makeMap(16, 8, [](glm::vec3) { return glm::vec3(1.0f); });
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.2f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    const int size = 40, seeds = 24;
    for (const GltfParams& p : cases) {
        SCOPED_TRACE("metallic " + std::to_string(p.metallic) + " roughness " + std::to_string(p.roughness));
        Scene scene;
        addIcosphere(scene, glm::vec3(0.0f), 1.0f, 3, addGltfMaterial(scene, p));  // faceted: n is the AOV's
        scene.environment = environmentThroughFile(white, "white.hdr");
        ASSERT_EQ(scene.environment->image->texels[0], glm::vec3(1.0f));
        const UniformGrid grid = buildGrid(scene, GridOptions{});
        const CameraBasis camera = makeCamera(spec, size, size);
        RenderSettings settings;
        settings.width = settings.height = size;
        settings.samples = 1;  // the pixel's centre: the AOV's normal is the sample's
        settings.maxBounces = 4;
        settings.integrator = Integrator::Path;
        CpuTracer cpu(scene, grid);
        GpuTracer gl(scene, grid);
        // E(mu) tabulated by quadrature, looked up linearly.
        const int table = 64;
        std::vector<glm::dvec3> albedo(table + 1);
        for (int k = 0; k <= table; ++k) albedo[size_t(k)] = gltfReferenceCoatedAlbedo(p, std::max(1e-3, double(k) / table), 200);
        auto expected = [&](double mu) {
            const double x = std::clamp(mu, 0.0, 1.0) * table;
            const int k = std::min(table - 1, int(x));
            return glm::mix(albedo[size_t(k)], albedo[size_t(k + 1)], x - k);
        };
        for (int backend = 0; backend < 2; ++backend) {
            SCOPED_TRACE(backend == 0 ? "gl" : "cpu");
            // The residual in three bands of n.v apart, each channel: a wrong Fresnel at grazing
            // views cannot hide behind the centre.
            Mean bands[3][3];
            for (int s = 0; s < seeds; ++s) {
                settings.seed = uint32_t(s);
                const RenderOutput out = backend == 0 ? gl.render(camera, settings) : cpu.render(camera, settings);
                for (int j = 0; j < size; ++j)
                    for (int i = 0; i < size; ++i) {
                        const size_t at = size_t(j * size + i);
                        if (out.prim[at] < 0.0f) {
                            ASSERT_NEAR(out.color[at].x, 1.0f, 1e-5f);
                            continue;
                        }
                        const double mu = -glm::dot(glm::dvec3(out.normal[at]), pixelRay(spec, size, i, j));
                        const glm::dvec3 e = expected(mu);
                        const int band = mu > 0.7 ? 0 : (mu > 0.35 ? 1 : 2);
                        for (int c = 0; c < 3; ++c) bands[band][c].add(out.color[at][c] - e[c]);
                    }
            }
            for (int band = 0; band < 3; ++band)
                for (int c = 0; c < 3; ++c) {
                    const Mean& m = bands[band][c];
                    ASSERT_GT(m.n, 50u) << "band " << band;
                    EXPECT_NEAR(m.mean(), 0.0, 5.0 * m.error() + 3e-3) << "band " << band << " channel " << c << ", standard error "
                                                                      << m.error();
                }
        }
    }
}

TEST_F(GltfMaterials, FurnaceSpheresShowTheirDirectionalAlbedo) {
    expectFurnaceAlbedo({
        {glm::dvec3(0.8), 0.0, 0.5},               // rough plastic
        {glm::dvec3(0.95, 0.64, 0.54), 1.0, 0.3},  // copper
        {glm::dvec3(0.2, 0.5, 0.8), 0.5, 0.8},     // half metal, very rough
        {glm::dvec3(1.0, 0.78, 0.34), 1.0, 0.0},   // polished gold: a mirror
        {glm::dvec3(0.7, 0.2, 0.2), 0.0, 0.0},     // a smooth coat over red
        {glm::dvec3(1.0), 0.0, 1.0},               // white, roughest
    });
}

// KHR_materials_clearcoat, KHR_materials_specular and KHR_materials_sheen in the white furnace: the
// coat mixes its lobe over the rest by its Fresnel weight at n.v, the sheen scales the rest by its
// albedo (GltfReference.h integrates the whole BRDF for it), and over a black base without a specular layer
// a smooth coat shows its own Fresnel, clearcoat x (0.04 + 0.96 (1 - n.v)^5), alone. No layer
// makes light: head-on every albedo is at most 1, and at other views a coat or a sheen never raises
// the albedo above 1 or above its base's (Appendix B's dielectric reflects more than it receives at
// grazing views: GltfBrdf.AlbedoIsAtMostOneAndTheSamplerEstimatesIt).
TEST_F(GltfMaterials, FurnaceSpheresWithLayersShowTheirDirectionalAlbedo) {
    auto layered = [](glm::dvec3 base, double metallic, double roughness) {
        GltfParams p;
        p.base = base;
        p.metallic = metallic;
        p.roughness = roughness;
        return p;
    };
    GltfParams coatOverWhite = layered(glm::dvec3(1.0), 0.0, 0.6);
    coatOverWhite.clearcoat = 1.0;  // smooth
    GltfParams roughCoatOverCopper = layered(glm::dvec3(0.95, 0.64, 0.54), 1.0, 0.3);
    roughCoatOverCopper.clearcoat = 0.7;
    roughCoatOverCopper.clearcoatRoughness = 0.35;
    GltfParams tinted = layered(glm::dvec3(0.9), 0.0, 0.4);
    tinted.specularFactor = 0.7;
    tinted.specularColor = glm::dvec3(0.2, 0.6, 1.0);
    GltfParams coatAlone = layered(glm::dvec3(0.0), 0.0, 1.0);
    coatAlone.specularFactor = 0.0;
    coatAlone.clearcoat = 1.0;
    GltfParams velvet = layered(glm::dvec3(0.9, 0.2, 0.4), 0.0, 0.7);
    velvet.sheenColor = glm::dvec3(1.0, 0.9, 0.8);
    velvet.sheenRoughness = 0.5;
    expectFurnaceAlbedo({coatOverWhite, roughCoatOverCopper, tinted, coatAlone, velvet});
    for (double mu : {0.05, 0.3, 1.0}) {
        const glm::dvec3 e = gltfReferenceCoatedAlbedo(coatAlone, mu, 100);
        EXPECT_NEAR(e.x, 0.04 + 0.96 * std::pow(1.0 - mu, 5.0), 1e-9) << mu;
        for (const GltfParams& p : {coatOverWhite, roughCoatOverCopper, tinted, velvet}) {
            GltfParams uncoated = p;
            uncoated.clearcoat = 0.0;
            uncoated.sheenColor = glm::dvec3(0.0);
            const glm::dvec3 e = gltfReferenceCoatedAlbedo(p, mu, 200), base = gltfReferenceCoatedAlbedo(uncoated, mu, 200);
            for (int c = 0; c < 3; ++c) {
                if (mu == 1.0) {
                    EXPECT_LE(e[c], 1.0 + 1e-3);
                }
                EXPECT_LE(e[c], std::max(1.0, base[c]) + 1e-3) << mu;
            }
        }
    }
}

// KHR_materials_transmission on both backends. A smooth white solid (metallic 0, transmission 1)
// in a uniform environment of radiance 1 conserves energy: every interface reflects F and
// transmits 1 - F (ior^2 scaled in and out again), so every pixel is 1 but for the light of paths
// still inside after the last bounce; so does a smooth sphere of thin walls (glTF's transmission
// without a volume: F and 1 - F, unbent). A rough one (single-scattering microfacets lose some) is
// rendered the same by both backends, Whitted and path, and is below 1.
TEST_F(GltfMaterials, TransmissiveSpheresConserveTheFurnaceAndAgreeAcrossBackends) {
    const EnvironmentImage white = makeMap(16, 8, [](glm::vec3) { return glm::vec3(1.0f); });
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.2f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    const int size = 32;
    for (const auto& [roughness, thin] : {std::pair{0.0, false}, {0.4, false}, {0.0, true}, {0.4, true}}) {
        SCOPED_TRACE("roughness " + std::to_string(roughness) + (thin ? ", thin walls" : ""));
        Scene scene;
        const uint32_t glass = addGltfMaterial(scene, GltfParams{glm::dvec3(1.0), 0.0, roughness});
        scene.materials[glass].ior = 1.5f;
        scene.materials[glass].transmission = glm::vec3(1.0f);
        scene.materials[glass].thinWalled = thin;
        addIcosphere(scene, glm::vec3(0.0f), 1.0f, 3, glass);
        scene.environment = environmentThroughFile(white, "white.hdr");
        const Both both = renderBoth(scene, spec, size, size, 16, 24, Integrator::Path, 3);
        expectSamePictures(both.gl, both.cpu, "transmissive sphere");
        for (int backend = 0; backend < 2; ++backend) {
            const RenderOutput& out = backend == 0 ? both.gl : both.cpu;
            const Mean sphere = objectMean(out);
            ASSERT_GT(sphere.n, 300u);
            if (roughness == 0.0)
                EXPECT_NEAR(sphere.mean(), 1.0, 5.0 * sphere.error() + 3e-3) << (backend ? "cpu" : "gl");
            else
                EXPECT_LT(sphere.mean(), 1.0 - 5.0 * sphere.error()) << (backend ? "cpu" : "gl");
        }
        const Both whitted = renderBoth(scene, spec, size, size, 1, 8, Integrator::Whitted);
        expectSamePictures(whitted.gl, whitted.cpu, "transmissive sphere, Whitted");
        EXPECT_GT(whitted.gl.stats.secondaryRays, size_t(size * size / 4));  // refracted rays were traced
    }
}

// The white furnace with KHR_materials_iridescence and KHR_materials_volume, path traced on both
// backends: a white dielectric and a white metal under a film, and a smooth white glass sphere whose
// volume absorbs, stay at or below 1 within the samples' standard error (a film redistributes the
// specular layer's colour but adds no light; absorption only takes it), the film and the volume
// visibly below 1 where they take light; and the same glass with a volume whose attenuation colour
// is white (nothing absorbed) conserves the furnace as clear glass does.
TEST_F(GltfMaterials, FilmsAndVolumesKeepTheFurnaceAtOrBelowOne) {
    const EnvironmentImage white = makeMap(16, 8, [](glm::vec3) { return glm::vec3(1.0f); });
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.2f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    const int size = 32;
    struct Case {
        const char* name;
        GltfParams p;
        glm::vec3 attenuation;  // white: a volume that absorbs nothing (with transmission)
        bool glass;
        bool conserves;  // the furnace stays at 1
    };
    GltfParams dielectricFilm{glm::dvec3(1.0), 0.0, 0.3}, metalFilm{glm::dvec3(1.0), 1.0, 0.3}, clear{glm::dvec3(1.0), 0.0, 0.0};
    dielectricFilm.iridescence = metalFilm.iridescence = 1.0;
    dielectricFilm.iridescenceIor = metalFilm.iridescenceIor = 1.8;
    dielectricFilm.iridescenceThickness = metalFilm.iridescenceThickness = 380.0;
    GltfParams brushed{glm::dvec3(1.0), 1.0, 0.3};  // KHR_materials_anisotropy, around the up axis (no texture coordinates)
    brushed.anisotropy = 0.9;
    for (const Case& c : {Case{"white dielectric under a film", dielectricFilm, glm::vec3(1.0f), false, false},
                          Case{"white metal under a film", metalFilm, glm::vec3(1.0f), false, false},
                          Case{"brushed white metal", brushed, glm::vec3(1.0f), false, false},
                          Case{"absorbing glass", clear, glm::vec3(0.6f, 0.8f, 0.9f), true, false},
                          Case{"glass of a white volume", clear, glm::vec3(1.0f), true, true}}) {
        SCOPED_TRACE(c.name);
        Scene scene;
        const uint32_t material = addGltfMaterial(scene, c.p);
        if (c.glass) {
            Material& m = scene.materials[material];
            m.ior = 1.5f;
            m.transmission = glm::vec3(1.0f);
            m.thickness = 1.0f;
            m.attenuationColor = c.attenuation;
            m.attenuationDistance = 0.5f;
        }
        addIcosphere(scene, glm::vec3(0.0f), 1.0f, 3, material);
        scene.environment = environmentThroughFile(white, "white.hdr");
        const Both both = renderBoth(scene, spec, size, size, 16, 24, Integrator::Path, 3);
        for (int backend = 0; backend < 2; ++backend) {
            const RenderOutput& out = backend == 0 ? both.gl : both.cpu;
            const Mean sphere = objectMean(out);
            ASSERT_GT(sphere.n, 300u);
            if (c.conserves)
                EXPECT_NEAR(sphere.mean(), 1.0, 5.0 * sphere.error() + 3e-3) << (backend ? "cpu" : "gl");
            else
                EXPECT_LT(sphere.mean(), 1.0 - 5.0 * sphere.error()) << (backend ? "cpu" : "gl");
            EXPECT_LE(sphere.mean(), 1.0 + 5.0 * sphere.error() + 3e-3) << (backend ? "cpu" : "gl");
        }
    }
}

// The sRGB transfer function's inverse (IEC 61966-2-1), for 8-bit codes.
double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// A 2 x 2 texture of one colour.
int addFlatTexture(Scene& scene, uint32_t rgba) {
    Texture t;
    t.name = "flat";
    t.image.width = t.image.height = 2;
    t.image.texels.assign(4, rgba);
    scene.textures.push_back(t);
    return int(scene.textures.size() - 1);
}

// A quad in the plane z = 0 (facing +z), texture coordinates (0, 0) at its top-left corner
// (-1, 1) as glTF's (u right, v down), with `material`.
void addTexturedQuad(Scene& scene, uint32_t material, bool mirrored = false) {
    const glm::vec3 a(-1, 1, 0), b(-1, -1, 0), c(1, -1, 0), d(1, 1, 0);
    const float u0 = mirrored ? 1.0f : 0.0f, u1 = 1.0f - u0;
    scene.triangles.push_back({a, b, c});
    scene.triangles.push_back({a, c, d});
    scene.materialIds.insert(scene.materialIds.end(), {material, material});
    scene.texcoords.push_back({{u0, 0.0f}, {u0, 1.0f}, {u1, 1.0f}});
    scene.texcoords.push_back({{u0, 0.0f}, {u1, 1.0f}, {u1, 0.0f}});
}

TEST_F(GltfMaterials, NormalMapBendsTheNormalInTheTangentFrame) {
    // The texel (r, g, b) bytes; the tangent-space normal (2 c - 1), x and y times the scale.
    const uint32_t r = 200, g = 90, b = 230;
    const float scale = 0.8f;
    const glm::dvec3 m(2.0 * r / 255.0 - 1.0, 2.0 * g / 255.0 - 1.0, 2.0 * b / 255.0 - 1.0);
    for (bool mirrored : {false, true}) {
        SCOPED_TRACE(mirrored ? "u mirrored" : "u along +x");
        Scene scene;
        Material mat;
        mat.model = GPURT_MODEL_DEBUG_NORMAL;
        mat.normalScale = scale;
        scene.materials.push_back(mat);
        scene.materials[0].normalTexture = addFlatTexture(scene, r | (g << 8) | (b << 16) | 0xff000000u);
        addTexturedQuad(scene, 0, mirrored);
        // T along increasing u (+x, or -x mirrored), B image up (+y) either way, N = +z.
        const glm::dvec3 t(mirrored ? -1.0 : 1.0, 0.0, 0.0), bt(0.0, 1.0, 0.0), n(0.0, 0.0, 1.0);
        const glm::dvec3 bent = glm::normalize(t * (m.x * scale) + bt * (m.y * scale) + n * m.z);
        for (bool back : {false, true}) {
            SCOPED_TRACE(back ? "seen from behind" : "seen from the front");
            CameraSpec spec;
            spec.eye = {0.0f, 0.0f, back ? -3.0f : 3.0f};
            spec.target = {0.0f, 0.0f, 0.0f};
            spec.fovy = 30.0f;
            const glm::dvec3 shown = back ? -bent : bent;  // the back sees the front's normal flipped
            const UniformGrid grid = buildGrid(scene, GridOptions{});
            const CameraBasis camera = makeCamera(spec, 16, 16);
            RenderSettings settings;
            settings.width = settings.height = 16;
            CpuTracer cpu(scene, grid);
            GpuTracer gl(scene, grid);
            for (const RenderOutput& out : {gl.render(camera, settings), cpu.render(camera, settings)}) {
                size_t hits = 0;
                for (size_t i = 0; i < out.color.size(); ++i) {
                    if (out.prim[i] < 0.0f) continue;
                    ++hits;
                    for (int c = 0; c < 3; ++c) ASSERT_NEAR(out.color[i][c], 0.5 * shown[c] + 0.5, 2e-3) << i;
                }
                EXPECT_GT(hits, 100u);
            }
        }
    }
}

// The debug-normal quad of NormalMapBendsTheNormalInTheTangentFrame (texel (200, 90, 230),
// scale 0.8), with vertex normals +z (as a glTF with NORMAL), for the tangent tests.
Scene tangentQuad() {
    Scene scene;
    Material mat;
    mat.model = GPURT_MODEL_DEBUG_NORMAL;
    mat.normalScale = 0.8f;
    scene.materials.push_back(mat);
    scene.materials[0].normalTexture = addFlatTexture(scene, 200u | (90u << 8) | (230u << 16) | 0xff000000u);
    addTexturedQuad(scene, 0);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    scene.normals.assign(2, TriangleNormals{n, n, n});
    return scene;
}

// The normal the map (texel (200, 90, 230), scale 0.8) gives in the frame (t, b, n).
glm::dvec3 bentIn(glm::dvec3 t, glm::dvec3 b, glm::dvec3 n) {
    const glm::dvec3 m(2.0 * 200 / 255.0 - 1.0, 2.0 * 90 / 255.0 - 1.0, 2.0 * 230 / 255.0 - 1.0);
    return glm::normalize(t * (m.x * 0.8) + b * (m.y * 0.8) + n * m.z);
}

RenderSettings smallImage() {
    RenderSettings settings;
    settings.width = settings.height = 16;
    return settings;
}

CameraSpec quadView(bool back) {
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, back ? -3.0f : 3.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 30.0f;
    return spec;
}

// A normal map bent away from a grazing view (the quad seen 10 degrees above its plane, the map's
// normal leaning 22 degrees away from the camera and a little sideways) would mirror the view into
// the quad: both backends turn it towards the geometric normal until the mirror rises Cycles'
// threshold, as the bisection of LiftedNormal.h finds for each pixel's ray.
TEST_F(GltfMaterials, NormalMapBentAwayFromAGrazingViewIsTurnedUntilItsMirrorRises) {
    const uint32_t r = 150, g = 170, b = 230;
    const glm::dvec3 bent = glm::normalize(glm::dvec3(2.0 * r / 255.0 - 1.0, 2.0 * g / 255.0 - 1.0, 2.0 * b / 255.0 - 1.0));
    Scene scene;
    Material mat;
    mat.model = GPURT_MODEL_DEBUG_NORMAL;
    scene.materials.push_back(mat);
    scene.materials[0].normalTexture = addFlatTexture(scene, r | (g << 8) | (b << 16) | 0xff000000u);
    addTexturedQuad(scene, 0);
    CameraSpec spec;
    const double elevation = 10.0 * M_PI / 180.0;
    spec.eye = glm::vec3(0.0f, float(-100.0 * std::cos(elevation)), float(100.0 * std::sin(elevation)));
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, 1.0f};
    spec.fovy = 0.25f;
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(spec, 16, 16);
    CpuTracer cpu(scene, grid);
    GpuTracer gl(scene, grid);
    for (const RenderOutput& out : {gl.render(camera, smallImage()), cpu.render(camera, smallImage())}) {
        size_t hits = 0;
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) {
                const size_t at = size_t(j * 16 + i);
                if (out.prim[at] < 0.0f) continue;
                ++hits;
                const glm::dvec3 wo = -glm::dvec3(primaryDirection(camera, i, j));
                const glm::dvec3 expected = test::liftedNormalByBisection(bent, {0.0, 0.0, 1.0}, wo);
                ASSERT_GT(glm::length(expected - bent), 0.2) << "the map's own normal mirrors into the quad";
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(out.color[at][c], 0.5 * expected[c] + 0.5, 2e-3) << "pixel " << i << ", " << j;
            }
        EXPECT_GT(hits, 40u);
    }
}

// glTF TANGENT: a quad whose given tangent is the texture's u direction turned 90 degrees about
// the normal (and tilted out of the surface, which Gram-Schmidt removes), with handedness +1 and
// -1, shows the normal map bent in that frame (T = (0, 1, 0), B = cross(N, T) w), not in the
// generated one (T = +x, B = +y), on both backends, from the front and from behind. Triangle 1
// has no tangents (a primitive without TANGENT beside one with): it keeps the generated frame.
TEST_F(GltfMaterials, TangentAttributeFramesTheNormalMap) {
    const glm::dvec3 n(0.0, 0.0, 1.0), given(0.0, 1.0, 0.0);
    const glm::dvec3 generated = bentIn({1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, n);
    for (float w : {1.0f, -1.0f}) {
        SCOPED_TRACE(w > 0.0f ? "w = +1" : "w = -1");
        Scene scene = tangentQuad();
        const glm::vec4 tilted(0.0f, 0.8f, 0.6f, w);  // (0, 1, 0) once orthogonal to N, normalised
        scene.tangents = {TriangleTangents{tilted, tilted, tilted}, TriangleTangents{}};
        const glm::dvec3 expected = bentIn(given, glm::cross(n, given) * double(w), n);
        ASSERT_GT(glm::length(expected - generated), 0.3) << "the test must tell the frames apart";
        const UniformGrid grid = buildGrid(scene, GridOptions{});
        CpuTracer cpu(scene, grid);
        GpuTracer gl(scene, grid);
        for (bool back : {false, true}) {
            SCOPED_TRACE(back ? "seen from behind" : "seen from the front");
            const CameraBasis camera = makeCamera(quadView(back), 16, 16);
            for (const RenderOutput& out : {gl.render(camera, smallImage()), cpu.render(camera, smallImage())}) {
                size_t hits[2] = {0, 0};
                for (size_t i = 0; i < out.color.size(); ++i) {
                    if (out.prim[i] < 0.0f) continue;
                    const int prim = int(out.prim[i]);
                    ++hits[prim];
                    const glm::dvec3 bent = prim == 0 ? expected : generated;
                    const glm::dvec3 shown = back ? -bent : bent;  // the back sees the front's normal flipped
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(out.color[i][c], 0.5 * shown[c] + 0.5, 2e-3) << "pixel " << i << " triangle " << prim;
                }
                EXPECT_GT(hits[0], 40u);
                EXPECT_GT(hits[1], 40u);
            }
        }
    }
}

// Tangents that frame nothing fall back to the generated frame at the hit: zero (the file's zero
// vector), not a number, infinite, or along the normal. Each gives the image of the quad without
// tangents, on both backends.
TEST_F(GltfMaterials, DegenerateTangentsGiveTheGeneratedFrame) {
    const Scene plain = tangentQuad();
    const UniformGrid plainGrid = buildGrid(plain, GridOptions{});
    const CameraBasis camera = makeCamera(quadView(false), 16, 16);
    const RenderOutput plainGl = GpuTracer(plain, plainGrid).render(camera, smallImage());
    const RenderOutput plainCpu = CpuTracer(plain, plainGrid).render(camera, smallImage());
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const glm::vec4 cases[] = {glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec4(nan, 1.0f, 0.0f, 1.0f),
                               glm::vec4(0.0f, inf, 0.0f, -1.0f), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f),
                               glm::vec4(0.0f, 1e-5f, -1.0f, -1.0f)};
    for (const glm::vec4& t : cases) {
        SCOPED_TRACE("tangent (" + std::to_string(t.x) + ", " + std::to_string(t.y) + ", " + std::to_string(t.z) + ", " +
                     std::to_string(t.w) + ")");
        Scene scene = tangentQuad();
        scene.tangents.assign(2, TriangleTangents{t, t, t});
        const UniformGrid grid = buildGrid(scene, GridOptions{});
        const RenderOutput gl = GpuTracer(scene, grid).render(camera, smallImage());
        const RenderOutput cpu = CpuTracer(scene, grid).render(camera, smallImage());
        size_t hits = 0;
        for (size_t i = 0; i < plainCpu.color.size(); ++i) {
            if (plainCpu.prim[i] < 0.0f) continue;
            ++hits;
            ASSERT_NE(plainCpu.color[i].x, 0.5f) << "the map bends the normal";
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(cpu.color[i][c], plainCpu.color[i][c]) << "cpu pixel " << i;
                ASSERT_EQ(gl.color[i][c], plainGl.color[i][c]) << "gl pixel " << i;
            }
        }
        EXPECT_GT(hits, 100u);
    }
}

// The tangent quad, of the glTF model (whose normal map PBRM carries) and lit by the headlight,
// through the packed format (TANG) renders exactly as its source on both backends.
TEST_F(GltfMaterials, PackedTangentsRenderAsTheirSource) {
    LoadedScene source;
    source.scene = tangentQuad();
    source.scene.materials[0].model = GPURT_MODEL_GLTF;
    source.scene.materials[0].roughness = 0.4f;
    const glm::vec4 t(0.0f, 1.0f, 0.0f, -1.0f);
    source.scene.tangents = {TriangleTangents{t, t, t}, TriangleTangents{}};
    const UniformGrid grid = buildGrid(source.scene, GridOptions{});
    const LoadedScene packed = decodePackedScene(encodePackedScene(source, *makeStructure(grid), "tangents"), "tangents.gpscene");
    ASSERT_TRUE(gridOf(packed.accel));
    ASSERT_EQ(packed.scene.tangents.size(), 2u);
    const CameraBasis camera = makeCamera(quadView(false), 16, 16);
    const RenderOutput a = GpuTracer(source.scene, grid).render(camera, smallImage());
    const RenderOutput b = GpuTracer(packed.scene, *gridOf(packed.accel)).render(camera, smallImage());
    const RenderOutput ac = CpuTracer(source.scene, grid).render(camera, smallImage());
    const RenderOutput bc = CpuTracer(packed.scene, *gridOf(packed.accel)).render(camera, smallImage());
    ASSERT_EQ(a.color.size(), b.color.size());
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(ac.color, bc.color);
    // And the tangents were used: triangle 0 differs from what generated tangents give.
    Scene untangented = source.scene;
    untangented.tangents.clear();
    const RenderOutput u = CpuTracer(untangented, grid).render(camera, smallImage());
    EXPECT_NE(u.color, bc.color);
}

// Whitted and path renders of a material whose metallic-roughness, emissive and occlusion maps
// hold one value each equal those of the same material with the values folded into its factors
// (map channels: roughness G, metallic B, occlusion R; emissive sRGB).
TEST_F(GltfMaterials, FlatMapsAreTheirValueTimesTheFactor) {
    const uint32_t mr = (0u) | (128u << 8) | (64u << 16) | 0xff000000u;  // G roughness 128, B metallic 64
    const uint32_t glow = 200u | (100u << 8) | (50u << 16) | 0xff000000u;
    const uint32_t ao = 100u | 0xff000000u;
    for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        SCOPED_TRACE(integrator == Integrator::Path ? "path" : "whitted");
        Scene mapped;
        Material m;
        m.model = GPURT_MODEL_GLTF;
        m.diffuse = glm::vec3(0.7f, 0.5f, 0.3f);
        m.metallic = 0.9f;
        m.roughness = 0.7f;
        m.emission = glm::vec3(0.5f, 0.25f, 1.0f);
        m.occlusionStrength = 0.6f;
        mapped.materials.push_back(m);
        const int mrTexture = addFlatTexture(mapped, mr);
        mapped.materials[0].roughnessTexture = {mrTexture, 1};
        mapped.materials[0].metallicTexture = {mrTexture, 2};
        mapped.materials[0].emissiveTexture = addFlatTexture(mapped, glow);
        mapped.materials[0].occlusionTexture = {addFlatTexture(mapped, ao), 0};
        addTexturedQuad(mapped, 0);
        mapped.lights.push_back({glm::vec3(0.5f, 1.0f, 2.0f), glm::vec3(1.0f), 4.0f});

        Scene folded = mapped;
        Material& f = folded.materials[0];
        f.roughness *= 128.0f / 255.0f;
        f.metallic *= 64.0f / 255.0f;
        f.emission *= glm::vec3(float(srgbToLinear(200.0 / 255.0)), float(srgbToLinear(100.0 / 255.0)), float(srgbToLinear(50.0 / 255.0)));
        f.roughnessTexture = f.metallicTexture = f.occlusionTexture = TextureChannel{};
        f.emissiveTexture = -1;
        // Occlusion only scales the ambient term: 1 + 0.6 (100/255 - 1) of it.
        const double occlusion = 1.0 + 0.6 * (100.0 / 255.0 - 1.0);

        CameraSpec spec;
        spec.eye = {0.3f, 0.2f, 3.0f};
        spec.target = {0.0f, 0.0f, 0.0f};
        spec.fovy = 35.0f;
        const CameraBasis camera = makeCamera(spec, 24, 24);
        RenderSettings settings;
        settings.width = settings.height = 24;
        // Whitted: the pixel centre, so that a pixel on the quad's edge is all quad or all
        // background (the occlusion shift is per covered sample).
        settings.samples = integrator == Integrator::Whitted ? 1 : 8;
        settings.integrator = integrator;
        const UniformGrid gm = buildGrid(mapped, GridOptions{}), gf = buildGrid(folded, GridOptions{});
        const RenderOutput a = GpuTracer(mapped, gm).render(camera, settings), b = GpuTracer(folded, gf).render(camera, settings);
        const RenderOutput ac = CpuTracer(mapped, gm).render(camera, settings), bc = CpuTracer(folded, gf).render(camera, settings);
        // The ambient term of the folded material (Whitted, no environment): 0.1 x the albedo at
        // normal incidence, the part occlusion scales.
        const glm::vec3 ambient = raymath::gltfAmbient(materialRecord(f));
        for (size_t i = 0; i < a.color.size(); ++i) {
            if (a.prim[i] < 0.0f) continue;
            for (int c = 0; c < 3; ++c) {
                const double shift = integrator == Integrator::Whitted ? (occlusion - 1.0) * ambient[c] : 0.0;
                // The emitter with a texture is not sampled as a light, the folded one is: the path
                // integrator's estimate differs in noise only, the pixel's own emission is the same.
                const double tolerance = integrator == Integrator::Path ? 0.05 * (b.color[i][c] + 0.05) : 2e-4;
                EXPECT_NEAR(a.color[i][c], b.color[i][c] + shift, tolerance) << "gl pixel " << i << " channel " << c;
                EXPECT_NEAR(ac.color[i][c], bc.color[i][c] + shift, tolerance) << "cpu pixel " << i << " channel " << c;
            }
        }
    }
}

// KHR_materials_transmission's transmissionTexture on both backends and both integrators. The
// quad of TransmissionQuad.h (read from its glTF: the slot, texCoord 1 and KHR_texture_transform;
// base colour c, metallic 0, roughness 0, ior 1 so F0 = 0 and Fd(x) = (1 - x)^5, transmission
// t = 0.8 x R / 255 in three bands, R = 0, 128, 255, read linearly) stands in front of an emitting
// quad of radiance Le = 2 (classic, black: it reflects nothing) and is lit from the front by a
// point light (intensity I at P), on a black background. At a pixel whose ray d meets the quad at
// X (v = -d, n = +z, l towards P, h = normalize(l + v)):
//   L = c (1 - t) (1 - Fd(v.h)) (n.l) I / |P - X|^2     the opaque dielectric's diffuse, lit
//     + c t (1 - Fd(n.v)) Le                            the transmitted share, ior 1: straight on
//     + 0.1 c (1 - t)                                   Whitted's ambient (its albedo at normal incidence)
// (the smooth coat's mirror, weight Fd(n.v) < 1e-6 here, sees black). Whitted: every pixel within
// 1e-4 relative; path (its transmitted share chosen at random): each band's mean residual within
// 5 standard errors. The two backends make the same pictures.
TEST_F(GltfMaterials, TransmissionTextureScalesTheFactorPerHit) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("gpurt-transmission-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "transmission.bmp", std::ios::binary) << TransmissionQuad::image();
    const double factor = 0.8;
    Scene scene = parseGltf(TransmissionQuad::gltf(factor, "transmission.bmp"), "transmission.gltf", dir);
    fs::remove_all(dir);
    ASSERT_EQ(scene.triangles.size(), 2u);
    ASSERT_TRUE(scene.materials[scene.materialIds[0]].transmissionTexture.given());
    const glm::dvec3 c(TransmissionQuad::kBase[0], TransmissionQuad::kBase[1], TransmissionQuad::kBase[2]);
    const double le = 2.0, intensity = 4.0;
    const glm::dvec3 light(0.5, 1.0, 2.0);
    const uint32_t emitter = addMaterial(scene, glm::vec3(0.0f), glm::vec3(float(le)));
    ASSERT_TRUE(scene.colors.empty() && scene.tangents.empty());
    const glm::vec3 a(-4, -4, -1), b(4, -4, -1), e(4, 4, -1), f(-4, 4, -1);
    scene.triangles.insert(scene.triangles.end(), {Triangle{a, b, e}, Triangle{a, e, f}});
    if (!scene.normals.empty()) scene.normals.resize(scene.triangles.size());  // the emitter: none (its face)
    scene.materialIds.insert(scene.materialIds.end(), {emitter, emitter});
    scene.texcoords.resize(scene.triangles.size());
    scene.lights.push_back({glm::vec3(light), glm::vec3(1.0f), float(intensity)});
    scene.background = glm::vec3(0.0f);

    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    const int size = 40;
    auto schlick = [](double x) { return std::pow(1.0 - x, 5.0); };  // Fd with F0 = 0
    for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const bool path = integrator == Integrator::Path;
        SCOPED_TRACE(path ? "path" : "whitted");
        const Both both = renderBoth(scene, spec, size, size, path ? 64 : 1, 4, integrator, 5);
        // The same pictures; not always the same count of shadow rays: the emitter's points seen
        // through the quad sample the emitter's own plane edge-on (cosine 0), where each backend's
        // rounding decides whether a shadow ray is made (it carries no light either way).
        expectSamePictures(both.gl, both.cpu, "transmission texture", false);
        EXPECT_EQ(both.gl.stats.secondaryRays, both.cpu.stats.secondaryRays);
        for (int backend = 0; backend < 2; ++backend) {
            SCOPED_TRACE(backend == 0 ? "gl" : "cpu");
            const RenderOutput& out = backend == 0 ? both.gl : both.cpu;
            Mean bands[3][3];
            for (int j = 0; j < size; ++j)
                for (int i = 0; i < size; ++i) {
                    const size_t at = size_t(j * size + i);
                    const glm::dvec3 d = pixelRay(spec, size, i, j), eye(spec.eye);
                    const glm::dvec3 x = eye + d * (-eye.z / d.z);
                    // Half a pixel (0.03 in y) and more from a band's edge and the quad's sides.
                    const int band = std::abs(x.x) < 0.95 && std::abs(x.y) < 0.95 ? TransmissionQuad::band(x.y, 0.02) : -1;
                    if (band < 0) continue;
                    ASSERT_LE(out.prim[at], 1.0f) << "pixel " << i << ", " << j << " sees the quad";
                    const double t = factor * TransmissionQuad::kBandR[band] / 255.0;
                    const glm::dvec3 v = -d, l = glm::normalize(light - x), h = glm::normalize(l + v);
                    const double nv = v.z, nl = l.z, vh = std::abs(glm::dot(v, h));
                    const double dist2 = glm::dot(light - x, light - x);
                    glm::dvec3 expected = c * ((1.0 - t) * (1.0 - schlick(vh)) * std::max(nl, 0.0) * intensity / dist2) +
                                          c * (t * (1.0 - schlick(nv)) * le);
                    if (!path) expected += 0.1 * c * (1.0 - t);
                    for (int k = 0; k < 3; ++k) {
                        if (!path) {
                            ASSERT_NEAR(out.color[at][k], expected[k], 1e-4 * expected[k] + 1e-5)
                                << "pixel " << i << ", " << j << " band " << band << " channel " << k;
                        }
                        bands[band][k].add(out.color[at][k] - expected[k]);
                    }
                }
            for (int band = 0; band < 3; ++band)
                for (int k = 0; k < 3; ++k) {
                    const Mean& m = bands[band][k];
                    ASSERT_GT(m.n, 100u) << "band " << band;
                    EXPECT_NEAR(m.mean(), 0.0, 5.0 * m.error() + 1e-3)
                        << "band " << band << " channel " << k << ", standard error " << m.error();
                }
        }
    }
}

// KHR_materials_clearcoat, KHR_materials_specular and KHR_materials_sheen with every map they name
// (the sheen's on a sphere), on both backends,
// path traced and Whitted: a quad whose coat is weighed by a texture's R (half), has its own
// normal map (a constant bend of the coat alone: the base keeps the face's normal) and whose
// specular colour comes from a texture, beside spheres under a smooth and a rough coat, under a
// sky that varies with direction. The backends agree pixel for pixel, and the coat's normal map
// changes the picture.
TEST_F(GltfMaterials, LayersWithTheirMapsAgreeAcrossBackends) {
    const EnvironmentImage sky = makeMap(32, 16, [](glm::vec3 d) {
        return glm::vec3(0.3f, 0.5f, 1.0f) * (0.5f + 0.5f * d.y) + glm::vec3(2.0f * std::max(0.0f, d.x));
    });
    auto scene = [&](bool coatMap) {
        Scene s;
        const uint32_t quad = addGltfMaterial(s, GltfParams{glm::dvec3(0.6, 0.1, 0.05), 0.0, 0.5});
        Material& m = s.materials[quad];
        m.clearcoat = 1.0f;
        m.clearcoatTexture = {addFlatTexture(s, 0xff808080u), 0};  // R 128: a coat of weight 0.5
        if (coatMap) m.clearcoatNormalTexture = addFlatTexture(s, 0xffff80c0u);  // (192, 128, 255): bent along +x
        m.specularColorTexture = addFlatTexture(s, 0xffff4020u);
        m.specularFactor = 0.8f;
        addTexturedQuad(s, quad);
        GltfParams smooth{glm::dvec3(0.1, 0.3, 0.8), 0.0, 0.6}, rough{glm::dvec3(0.9, 0.7, 0.2), 1.0, 0.2};
        smooth.clearcoat = 1.0;
        rough.clearcoat = 0.8;
        rough.clearcoatRoughness = 0.3;
        addIcosphere(s, glm::vec3(-0.55f, 0.4f, 0.4f), 0.3f, 3, addGltfMaterial(s, smooth));
        addIcosphere(s, glm::vec3(0.55f, -0.4f, 0.4f), 0.3f, 3, addGltfMaterial(s, rough));
        GltfParams velvet{glm::dvec3(0.2, 0.05, 0.1), 0.0, 0.8};
        velvet.sheenColor = glm::dvec3(1.0, 0.8, 0.9);
        velvet.sheenRoughness = 0.6;
        const uint32_t cloth = addGltfMaterial(s, velvet);
        s.materials[cloth].sheenColorTexture = addFlatTexture(s, 0xff40c0ffu);   // sRGB (255, 192, 64)
        s.materials[cloth].sheenRoughnessTexture = {addFlatTexture(s, 0x80ffffffu), 3};  // A 128
        addIcosphere(s, glm::vec3(0.55f, 0.45f, 0.4f), 0.3f, 3, cloth);
        s.texcoords.resize(s.triangles.size());  // the spheres at (0, 0) of the flat maps
        s.environment = environmentThroughFile(sky, "sky.hdr");
        return s;
    };
    const Scene withMap = scene(true), without = scene(false);
    const Both path = renderBoth(withMap, quadView(false), 40, 40, 8, 4, Integrator::Path, 5);
    expectSamePictures(path.gl, path.cpu, "layers, path");
    const Both whitted = renderBoth(withMap, quadView(false), 40, 40, 1, 4, Integrator::Whitted);
    expectSamePictures(whitted.gl, whitted.cpu, "layers, Whitted");
    EXPECT_GT(whitted.gl.stats.secondaryRays, 100u);  // the smooth coat's mirror rays
    const Both flat = renderBoth(without, quadView(false), 40, 40, 1, 4, Integrator::Whitted);
    double change = 0.0;
    for (size_t k = 0; k < flat.gl.color.size(); ++k) change += glm::length(flat.gl.color[k] - whitted.gl.color[k]);
    EXPECT_GT(change / double(flat.gl.color.size()), 1e-3);
}

// KHR_materials_iridescence with both its maps, on both backends, path traced and Whitted: a
// quad whose film is weighed by a texture's R (half) and whose thickness is its G between 200 and
// 600 nm (a texel of 64: 300 nm), beside a metal and a dielectric sphere under films of their own,
// under a sky that varies with direction. The backends agree pixel for pixel, and the films change
// the picture.
TEST_F(GltfMaterials, IridescenceWithItsMapsAgreesAcrossBackends) {
    const EnvironmentImage sky = makeMap(32, 16, [](glm::vec3 d) {
        return glm::vec3(0.3f, 0.5f, 1.0f) * (0.5f + 0.5f * d.y) + glm::vec3(2.0f * std::max(0.0f, d.x));
    });
    auto scene = [&](bool films) {
        Scene s;
        const uint32_t quad = addGltfMaterial(s, GltfParams{glm::dvec3(0.05, 0.05, 0.05), 0.0, 0.2});
        Material& m = s.materials[quad];
        m.iridescenceFactor = films ? 1.0f : 0.0f;
        m.iridescenceIor = 1.8f;
        m.iridescenceThicknessMin = 200.0f;
        m.iridescenceThicknessMax = 600.0f;
        const int flat = addFlatTexture(s, 0xff004080u);  // R 128: weight 0.5; G 64: 200 + 400 x 64 / 255 nm
        m.iridescenceTexture = {flat, 0};
        m.iridescenceThicknessTexture = {flat, 1};
        addTexturedQuad(s, quad);
        GltfParams metal{glm::dvec3(0.6, 0.6, 0.6), 1.0, 0.25}, dark{glm::dvec3(0.02, 0.02, 0.02), 0.0, 0.1};
        for (GltfParams* p : {&metal, &dark}) {
            p->iridescence = films ? 1.0 : 0.0;
            p->iridescenceIor = 1.5;
            p->iridescenceThickness = 450.0;
        }
        addIcosphere(s, glm::vec3(-0.55f, 0.4f, 0.4f), 0.3f, 3, addGltfMaterial(s, metal));
        addIcosphere(s, glm::vec3(0.55f, -0.4f, 0.4f), 0.3f, 3, addGltfMaterial(s, dark));
        s.texcoords.resize(s.triangles.size());  // the spheres at (0, 0) of the flat map
        s.environment = environmentThroughFile(sky, "sky.hdr");
        return s;
    };
    const Scene withFilms = scene(true), without = scene(false);
    const Both path = renderBoth(withFilms, quadView(false), 40, 40, 8, 4, Integrator::Path, 5);
    expectSamePictures(path.gl, path.cpu, "films, path");
    const Both whitted = renderBoth(withFilms, quadView(false), 40, 40, 1, 4, Integrator::Whitted);
    expectSamePictures(whitted.gl, whitted.cpu, "films, Whitted");
    const Both plain = renderBoth(without, quadView(false), 40, 40, 1, 4, Integrator::Whitted);
    double change = 0.0;
    for (size_t k = 0; k < plain.gl.color.size(); ++k) change += glm::length(plain.gl.color[k] - whitted.gl.color[k]);
    EXPECT_GT(change / double(plain.gl.color.size()), 1e-3);
}

// The largest difference of two pictures' channels over all pixels, relative where above 1.
double largestDifference(const RenderOutput& a, const RenderOutput& b) {
    double worst = 0.0;
    for (size_t k = 0; k < a.color.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            const double x = a.color[k][c], y = b.color[k][c];
            worst = std::max(worst, std::abs(x - y) / std::max(1.0, std::abs(y)));
        }
    return worst;
}

// KHR_materials_anisotropy in the tangent frame, on both backends, Whitted under a point light (a
// brushed metal quad, its highlight stretched along the direction) and path traced under a sky:
//  - the frame's directions: the texture coordinates' frame (T = +x) turned by a rotation of 90
//    degrees shows the picture of a quad whose vertex tangents are +y (glTF TANGENT) without a
//    rotation, and both differ from the unturned one and from the isotropic lobe;
//  - the map: a texel whose RG points along (1, 0.0039) and whose B is 128/255 shows the picture of
//    the strength times 128/255 and the rotation atan(0.0039) without a map;
//  - the backends agree pixel for pixel, path traced too.
TEST_F(GltfMaterials, AnisotropyFollowsTheTangentFrameAndItsMap) {
    enum class Frame { Generated, Tangents };
    auto scene = [](float strength, float rotation, Frame frame, int texel) {
        Scene s;
        const uint32_t quad = addGltfMaterial(s, GltfParams{glm::dvec3(0.9, 0.8, 0.6), 1.0, 0.25});
        s.materials[quad].anisotropyStrength = strength;
        s.materials[quad].anisotropyRotation = rotation;
        if (texel >= 0) s.materials[quad].anisotropyTexture = addFlatTexture(s, uint32_t(texel) | 0xff000000u);
        addTexturedQuad(s, quad);
        const glm::vec3 n(0.0f, 0.0f, 1.0f);
        s.normals.assign(2, TriangleNormals{n, n, n});
        if (frame == Frame::Tangents) {
            const glm::vec4 y(0.0f, 1.0f, 0.0f, 1.0f);
            s.tangents.assign(2, TriangleTangents{y, y, y});
        }
        s.lights.push_back({glm::vec3(0.6f, -0.4f, 1.2f), glm::vec3(1.0f), 3.0f});
        s.background = glm::vec3(0.0f);
        return s;
    };
    const float quarter = float(gltfref::kPi / 2.0);
    auto whitted = [](const Scene& s, const char* what) {
        const Both both = renderBoth(s, quadView(false), 40, 40, 1, 2, Integrator::Whitted);
        expectSamePictures(both.gl, both.cpu, what);
        EXPECT_LT(largestDifference(both.gl, both.cpu), 2e-3) << what;
        return both.gl;
    };
    const RenderOutput turned = whitted(scene(0.9f, quarter, Frame::Generated, -1), "turned");
    const RenderOutput tangents = whitted(scene(0.9f, 0.0f, Frame::Tangents, -1), "vertex tangents");
    const RenderOutput along = whitted(scene(0.9f, 0.0f, Frame::Generated, -1), "along u");
    const RenderOutput isotropic = whitted(scene(0.0f, 0.0f, Frame::Generated, -1), "isotropic");
    EXPECT_LT(largestDifference(turned, tangents), 2e-3);
    EXPECT_GT(largestDifference(turned, along), 0.05) << "the direction must show";
    EXPECT_GT(largestDifference(along, isotropic), 0.05) << "the anisotropy must show";
    const RenderOutput mapped = whitted(scene(0.9f, 0.0f, Frame::Generated, 255 | (128 << 8) | (128 << 16)), "map");
    const float x = 1.0f, y = 2.0f * 128.0f / 255.0f - 1.0f;
    const RenderOutput folded = whitted(scene(0.9f * 128.0f / 255.0f, std::atan2(y, x), Frame::Generated, -1), "folded");
    EXPECT_LT(largestDifference(mapped, folded), 2e-3);
    EXPECT_GT(largestDifference(mapped, along), 0.02) << "the map's strength must show";

    Scene sky = scene(0.9f, 0.6f, Frame::Tangents, 200 | (90 << 8) | (230 << 16));
    sky.lights.clear();
    sky.environment = environmentThroughFile(makeMap(32, 16, [](glm::vec3 d) {
        return glm::vec3(0.3f, 0.5f, 1.0f) * (0.5f + 0.5f * d.y) + glm::vec3(3.0f * std::max(0.0f, d.x));
    }), "sky.hdr");
    const Both path = renderBoth(sky, quadView(false), 40, 40, 8, 4, Integrator::Path, 5);
    expectSamePictures(path.gl, path.cpu, "anisotropy, path");
}

// KHR_materials_dispersion: a glass sphere of index 1.5 and dispersion 20 (Abbe number 1: the red
// and blue indices 1.35 and 1.85) before a sky whose light comes from behind it, smooth (the
// paths' sampling alone) and of roughness 0.3 (next-event estimation and its weights too), path
// traced on the cpu backend, the wavefront chain and the megakernel. Each channel of each pixel
// has, in expectation, that channel of the sphere rendered without dispersion at the channel's
// index (the extension's formula at 656.3, 587.6 and 486.1 nm): over the sphere's pixels the mean
// of the differences lies within 5 standard errors of 0, where the red and blue indices' spheres
// differ from the d line's by more than that (the test tells the indices apart).
TEST_F(GltfMaterials, DispersionGivesEachChannelTheIndexOfItsWavelength) {
    const EnvironmentImage sky = makeMap(64, 32, [](glm::vec3 d) {
        return glm::vec3(0.1f + 4.0f * std::pow(std::max(0.0f, -d.z), 6.0f) + 0.3f * std::max(0.0f, d.y));
    });
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.2f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    const int size = 24;
    const double nd = 1.5, dispersion = 20.0;
    const double lambdas[3] = {656.3, 587.6, 486.1};
    const CameraBasis camera = makeCamera(spec, size, size);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.samples = 64;
    settings.maxBounces = 8;
    settings.integrator = Integrator::Path;
    for (const double roughness : {0.0, 0.3}) {
        SCOPED_TRACE("roughness " + std::to_string(roughness));
        const auto sphere = [&](double ior, double disperse) {
            Scene scene;
            const uint32_t glass = addGltfMaterial(scene, GltfParams{glm::dvec3(1.0), 0.0, roughness});
            Material& m = scene.materials[glass];
            m.ior = float(ior);
            m.transmission = glm::vec3(1.0f);
            m.thickness = 1.0f;
            m.dispersion = float(disperse);
            addIcosphere(scene, glm::vec3(0.0f), 1.0f, 3, glass);
            scene.environment = environmentThroughFile(sky, "sky.hdr");
            // Before it: a highlight of the rough sphere's reflection, found by next-event estimation.
            scene.lights.push_back({{1.5f, 1.5f, 3.0f}, {1.0f, 1.0f, 1.0f}, 30.0f});
            return scene;
        };
        const Scene dispersed = sphere(nd, dispersion);
        ASSERT_TRUE(dispersed.materials[0].disperses());
        for (int form = 0; form < 3; ++form) {
            SCOPED_TRACE(form == 0 ? "cpu" : form == 1 ? "wavefront" : "megakernel");
            GpuTracerOptions options;
            options.integratorKernel = form == 1 ? IntegratorKernel::Wavefront : IntegratorKernel::Megakernel;
            const auto render = [&](const Scene& scene) {
                const UniformGrid grid = buildGrid(scene, GridOptions{});
                return form == 0 ? CpuTracer(scene, grid).render(camera, settings)
                                 : GpuTracer(scene, grid, options).render(camera, settings);
            };
            const RenderOutput got = render(dispersed);
            const RenderOutput plain = render(sphere(nd, 0.0));
            // The mean over the sphere's pixels of a's channel c less b's, and its standard error.
            const auto difference = [&](const RenderOutput& a, const RenderOutput& b, int c) {
                Mean m;
                for (size_t at = 0; at < a.color.size(); ++at)
                    if (a.prim[at] >= 0.0f) m.add(double(a.color[at][c]) - double(b.color[at][c]));
                return m;
            };
            for (int c = 0; c < 3; ++c) {
                SCOPED_TRACE("channel " + std::to_string(c));
                const RenderOutput reference = render(sphere(gltfref::specDispersedIor(nd, dispersion, lambdas[c]), 0.0));
                const Mean d = difference(got, reference, c);
                ASSERT_GT(d.n, 200u);
                EXPECT_NEAR(d.mean(), 0.0, 5.0 * d.error());
                if (c != 1) {
                    const Mean apart = difference(reference, plain, c);
                    EXPECT_GT(std::abs(apart.mean()), 5.0 * apart.error() + 5.0 * d.error())
                        << "the test must tell the indices apart";
                }
            }
        }
    }
}

// KHR_materials_volume: a smooth slab of thickness L (ior 1: the rays go straight through and
// Schlick's F0 is 0, so nothing is reflected at these angles) of a white transmissive material in
// a uniform sky of radiance 1 shows in each pixel the Beer-Lambert transmittance
// attenuationColor^(l / attenuationDistance), l = L / |d.z| the length of its ray inside (less the
// secondary rays' offset from the surface), path
// traced and Whitted, on the cpu backend, the wavefront chain and the megakernel; the same slab
// with thickness 0 (the extension's thin wall) absorbs nothing.
TEST_F(GltfMaterials, VolumeAbsorbsAsBeerLambertOnEveryBackendAndKernel) {
    const EnvironmentImage white = makeMap(16, 8, [](glm::vec3) { return glm::vec3(1.0f); });
    const glm::dvec3 colour(0.8, 0.5, 0.2);
    const double distance = 0.5, thickness = 1.0;
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 5.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 10.0f;
    const int size = 16;
    for (const bool thin : {false, true}) {
        SCOPED_TRACE(thin ? "thin wall" : "volume");
        Scene scene;
        const uint32_t glass = addGltfMaterial(scene, GltfParams{glm::dvec3(1.0), 0.0, 0.0});
        Material& m = scene.materials[glass];
        m.ior = 1.0f;
        m.transmission = glm::vec3(1.0f);
        m.thickness = thin ? 0.0f : 1.0f;
        m.attenuationColor = glm::vec3(colour);
        m.attenuationDistance = float(distance);
        addBox(scene, glm::vec3(-2.0f, -2.0f, -0.5f * float(thickness)), glm::vec3(2.0f, 2.0f, 0.5f * float(thickness)), glass);
        scene.environment = environmentThroughFile(white, "white.hdr");
        const UniformGrid grid = buildGrid(scene, GridOptions{});
        const CameraBasis camera = makeCamera(spec, size, size);
        for (const Integrator integrator : {Integrator::Path, Integrator::Whitted}) {
            RenderSettings settings;
            settings.width = settings.height = size;
            settings.samples = 1;  // the pixel's centre: pixelRay's direction
            settings.maxBounces = 4;
            settings.integrator = integrator;
            for (int form = 0; form < 3; ++form) {
                SCOPED_TRACE(std::string(integrator.name()) + (form == 0 ? ", cpu" : form == 1 ? ", wavefront" : ", megakernel"));
                GpuTracerOptions options;
                options.integratorKernel = form == 1 ? IntegratorKernel::Wavefront : IntegratorKernel::Megakernel;
                const RenderOutput out = form == 0 ? CpuTracer(scene, grid).render(camera, settings)
                                                   : GpuTracer(scene, grid, options).render(camera, settings);
                for (int j = 0; j < size; ++j)
                    for (int i = 0; i < size; ++i) {
                        const glm::dvec3 d = pixelRay(spec, size, i, j);
                        const double inside = thickness / std::abs(d.z);
                        const glm::dvec3 expected = thin ? glm::dvec3(1.0) : glm::pow(colour, glm::dvec3(inside / distance));
                        // The refracted ray starts rayOffset inside the slab: its length is known
                        // to within twice that, the transmittance to within that times the slope.
                        const double slack = thin ? 0.0 : 2.0 * double(grid.rayOffset()) / std::abs(d.z) / distance;
                        const glm::vec3 got = out.color[size_t(j * size + i)];
                        for (int c = 0; c < 3; ++c)
                            ASSERT_NEAR(got[c], expected[c], expected[c] * (1e-4 - std::log(colour[c]) * slack) + 1e-6)
                                << "pixel " << i << ", " << j << " channel " << c;
                    }
            }
        }
    }
    // A camera inside the glowing solid (Whitted without bounces: the wavefront chain's last-round
    // pass, the megakernel, the cpu) sees the back of its far face through the medium: the three agree.
    Scene inside;
    const uint32_t glow = addGltfMaterial(inside, GltfParams{glm::dvec3(1.0), 0.0, 0.3});
    Material& m = inside.materials[glow];
    m.ior = 1.5f;
    m.transmission = glm::vec3(1.0f);
    m.emission = glm::vec3(0.8f);
    m.emissionIsLight = false;
    m.thickness = 1.0f;
    m.attenuationColor = glm::vec3(colour);
    m.attenuationDistance = float(distance);
    addBox(inside, glm::vec3(-2.0f), glm::vec3(2.0f), glow);
    inside.environment = environmentThroughFile(white, "white.hdr");
    CameraSpec within = spec;
    within.eye = {0.0f, 0.0f, 1.5f};
    within.fovy = 60.0f;
    const UniformGrid grid = buildGrid(inside, GridOptions{});
    const CameraBasis camera = makeCamera(within, size, size);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.samples = 1;
    settings.maxBounces = 0;
    const RenderOutput cpu = CpuTracer(inside, grid).render(camera, settings);
    for (const IntegratorKernel form : {IntegratorKernel::Wavefront, IntegratorKernel::Megakernel}) {
        GpuTracerOptions options;
        options.integratorKernel = form;
        const RenderOutput gl = GpuTracer(inside, grid, options).render(camera, settings);
        expectSamePictures(gl, cpu, "inside the solid", false);  // its own emitter points sampled edge-on
    }
    EXPECT_LT(cpu.color[size_t(size / 2 * size + size / 2)].z, 0.01f);  // blue: 0.2^(3.5 / 0.5) of it arrives
}

// Real files made by others (tests/assets/gltf/khronos, their origins and licences in its
// README.md) render what they say, on both backends, without a "not used" warning but the one
// gpurt documents (KHR_materials_volume's thicknessTexture: the rays measure the distance inside):
//  - Khronos' AttenuationTest (KHR_materials_transmission and _volume): Whitted and path agree
//    across the backends;
//  - glTF-Blender-IO's cube with every factor and map of KHR_materials_clearcoat, _sheen,
//    _specular, _ior, _transmission and _volume: read, and the backends agree;
//  - a KHR_materials_pbrSpecularGlossiness sphere of specularFactor 1 and glossinessFactor 0: its
//    archived BRDF is then F = 1 at every angle over GGX of alpha 1 and no diffuse (diffuse x (1 -
//    max(specular))), the metallic-roughness model's white metal of roughness 1: the same
//    pictures.
TEST_F(GltfMaterials, RealFilesRenderWhatTheySay) {
    const std::filesystem::path dir = "tests/assets/gltf/khronos";
    auto load = [](const std::filesystem::path& file) {
        ::testing::internal::CaptureStderr();
        Scene scene = loadGltf(file);
        const std::string warnings = ::testing::internal::GetCapturedStderr();
        std::istringstream lines(warnings);
        for (std::string line; std::getline(lines, line);) {
            if (line.find("not used") == std::string::npos && line.find("not read") == std::string::npos) continue;
            EXPECT_NE(line.find("thicknessTexture is not used (rays measure the distance inside)"), std::string::npos)
                << file << ": " << line;
        }
        return scene;
    };
    const EnvironmentImage sky = makeMap(32, 16, [](glm::vec3 d) {
        return glm::vec3(0.3f, 0.5f, 1.0f) * (0.5f + 0.5f * d.y) + glm::vec3(2.0f * std::max(0.0f, d.x));
    });

    Scene attenuation = load(dir / "attenuation_test/16_volume.gltf");
    ASSERT_GT(attenuation.triangles.size(), 100u);
    EXPECT_GT(std::count_if(attenuation.materials.begin(), attenuation.materials.end(),
                            [](const Material& m) { return m.hasVolume(); }),
              10);
    attenuation.environment = environmentThroughFile(sky, "sky.hdr");
    CameraSpec front;
    front.eye = {1.0f, 0.0f, 22.0f};
    front.target = {1.0f, 0.0f, 0.0f};
    front.fovy = 45.0f;
    const Both whitted = renderBoth(attenuation, front, 64, 48, 1, 8, Integrator::Whitted);
    expectSamePictures(whitted.gl, whitted.cpu, "AttenuationTest, Whitted");
    const Both path = renderBoth(attenuation, front, 64, 48, 4, 8, Integrator::Path, 5);
    expectSamePictures(path.gl, path.cpu, "AttenuationTest, path", false);

    Scene factors = load(dir / "factors/22_factors.gltf");
    ASSERT_EQ(factors.materials.size(), 2u);
    const Material& every = factors.materials[1];
    EXPECT_TRUE(every.hasClearcoat() && every.hasSheen() && every.hasSpecularLayer() && every.hasVolume() && every.hasAlpha());
    factors.environment = environmentThroughFile(sky, "sky.hdr");
    CameraSpec corner;
    corner.eye = {3.0f, 2.5f, 4.0f};
    corner.target = {0.0f, 0.0f, 0.0f};
    const Both layered = renderBoth(factors, corner, 48, 48, 4, 4, Integrator::Path, 5);
    expectSamePictures(layered.gl, layered.cpu, "every factor, path", false);

    Scene sphere = load(dir / "specular_glossiness_sphere/04_sphere_specular_glossiness.gltf");
    ASSERT_EQ(sphere.materials.size(), 2u);  // the default material and the sphere's
    Scene metal = sphere;
    metal.materials[1] = Material{};
    metal.materials[1].model = GPURT_MODEL_GLTF;
    metal.materials[1].diffuse = glm::vec3(1.0f);
    metal.materials[1].metallic = 1.0f;
    metal.materials[1].roughness = 1.0f;
    CameraSpec view;
    view.eye = {0.0f, 0.5f, 4.0f};
    view.target = {0.0f, 0.0f, 0.0f};
    view.fovy = 40.0f;
    sphere.environment = metal.environment = environmentThroughFile(sky, "sky.hdr");
    for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const bool traced = integrator == Integrator::Path;
        const Both given = renderBoth(sphere, view, 40, 40, traced ? 8 : 1, 4, integrator, 5);
        const Both expected = renderBoth(metal, view, 40, 40, traced ? 8 : 1, 4, integrator, 5);
        expectSamePictures(given.gl, given.cpu, traced ? "specular-glossiness, path" : "specular-glossiness, Whitted");
        EXPECT_LT(largestDifference(given.gl, expected.gl), 2e-3) << (traced ? "path" : "Whitted");
        EXPECT_LT(largestDifference(given.cpu, expected.cpu), 2e-3) << (traced ? "path" : "Whitted");
        EXPECT_GT(objectMean(given.gl).mean(), 0.01);
    }
}

}  // namespace
}  // namespace gpurt::test
