// The CPU layout of the scene textures (SceneTextureLayout.h) against glsl/common/scene_layout.h,
// with the texel addresses worked out here from the header's description: cell c at (c % width,
// c / width) of the voxel index, list entry k at (k % width, k / width), triangle t's texels at
// row t / TRIANGLES_PER_ROW, columns 3 * (t % TRIANGLES_PER_ROW) + 0..2; every other texel 0.
#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/bvh/BvhTexels.h"
#include "raytrace/accel/grid/GridTexels.h"

#include <algorithm>
#include <gtest/gtest.h>

#include <random>

namespace gpurt {
namespace {

using namespace glm;
#include "../../glsl/common/scene_layout.h"

// More triangles than one texture row holds, and more cells and list entries than one row.
Scene scatteredTriangles(int n) {
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> pos(-5.0f, 5.0f), offset(-0.3f, 0.3f);
    Scene scene;
    for (int m = 0; m < 3; ++m) {
        Material material;
        material.diffuse = vec3(0.1f * float(m), 0.2f, 0.3f);
        material.specular = vec3(0.4f, 0.5f * float(m), 0.6f);
        material.shininess = 10.0f + float(m);
        material.reflectivity = vec3(0.05f * float(m));
        material.doubleSided = m == 0;  // 1 and 2 cull their back faces
        material.alphaMode = m == 2 ? 1 : 0;  // 2 has alpha (MASK)
        scene.materials.push_back(material);
    }
    for (int t = 0; t < n; ++t) {
        const vec3 c(pos(rng), pos(rng), pos(rng));
        scene.triangles.push_back({c, c + vec3(offset(rng), offset(rng), offset(rng)),
                                   c + vec3(offset(rng), offset(rng), offset(rng))});
        scene.materialIds.push_back(uint32_t(t % 3));
    }
    return scene;
}

TEST(SceneTextureLayoutTest, TexelsAreWhereSceneLayoutSays) {
    const Scene scene = scatteredTriangles(2500);
    GridOptions options;
    options.resolution = ivec3(40, 30, 20);  // 24000 cells: several index rows
    const UniformGrid grid = buildGrid(scene, options);
    ASSERT_GT(grid.cellTriangles.size(), size_t(GPURT_REFS_PER_ROW));

    const TextureTexels index = voxelIndexTexels(grid);
    EXPECT_EQ(index.name, "voxelIndex");
    EXPECT_EQ(std::string(index.formatName()), "RG32UI");
    EXPECT_EQ(index.width, GPURT_INDEX_WIDTH);
    EXPECT_EQ(index.rows, (24000 + GPURT_INDEX_WIDTH - 1) / GPURT_INDEX_WIDTH);
    for (size_t c = 0; c < index.texels(); ++c) {
        const size_t x = c % GPURT_INDEX_WIDTH, y = c / GPURT_INDEX_WIDTH;
        const uint32_t* texel = &index.uints[(y * GPURT_INDEX_WIDTH + x) * 2];
        const bool cell = c < grid.cells();
        const bool empty = cell && grid.cellStart[c + 1] == grid.cellStart[c];
        ASSERT_EQ(texel[0], !cell ? 0u : empty ? uint32_t(std::max<int>(1, grid.skip[c])) : grid.cellStart[c]) << c;
        ASSERT_EQ(texel[1], cell ? grid.cellStart[c + 1] - grid.cellStart[c] : 0u) << c;
    }

    const TextureTexels list = cellTriangleTexels(scene, grid);
    EXPECT_EQ(std::string(list.formatName()), "RGBA32F");
    EXPECT_EQ(list.width, 3 * GPURT_REFS_PER_ROW);
    EXPECT_EQ(size_t(list.rows), (grid.cellTriangles.size() + GPURT_REFS_PER_ROW - 1) / GPURT_REFS_PER_ROW);
    for (size_t k = 0; k < size_t(list.rows) * GPURT_REFS_PER_ROW; ++k) {
        const size_t row = k / GPURT_REFS_PER_ROW, column = 3 * (k % GPURT_REFS_PER_ROW);
        const float* texel = &list.floats[(row * size_t(list.width) + column) * 4];
        if (k >= grid.cellTriangles.size()) {
            for (int c = 0; c < 12; ++c) ASSERT_EQ(texel[c], 0.0f) << k;
            continue;
        }
        const uint32_t id = grid.cellTriangles[k];
        const Triangle& tri = scene.triangles[id];
        // The vertices themselves (the watertight test needs a shared edge's vertices exactly).
        // The second texel's w: the coverage flags, culling 1 + alpha 2 (material id % 3: 0, 1, 3).
        const float flags[3] = {0.0f, 1.0f, 3.0f};
        const float expected[12] = {tri.v0.x, tri.v0.y, tri.v0.z, float(id),    tri.v1.x, tri.v1.y,
                                    tri.v1.z, flags[id % 3],      tri.v2.x, tri.v2.y, tri.v2.z, 0.0f};
        for (int c = 0; c < 12; ++c) ASSERT_EQ(texel[c], expected[c]) << "entry " << k << " value " << c;
    }
    // The BVH's leaves carry the same entries in leaf order.
    const Bvh bvh = buildBvh(scene, BvhOptions{});
    const TextureTexels leaves = bvhTriangleTexels(scene, bvh);
    for (size_t k = 0; k < bvh.triangles.size(); ++k) {
        const size_t row = k / GPURT_REFS_PER_ROW, column = 3 * (k % GPURT_REFS_PER_ROW);
        const float* texel = &leaves.floats[(row * size_t(leaves.width) + column) * 4];
        ASSERT_EQ(texel[3], float(bvh.triangles[k])) << k;
        ASSERT_EQ(texel[7], float(bvh.triangles[k] % 3 == 0 ? 0 : bvh.triangles[k] % 3 == 1 ? 1 : 3)) << k;
    }

    const TextureTexels triangles = triangleTexels(scene);
    EXPECT_EQ(std::string(triangles.formatName()), "RGBA32F");
    EXPECT_EQ(triangles.width, 3 * GPURT_TRIANGLES_PER_ROW);
    EXPECT_EQ(triangles.rows, 3);  // 2500 triangles, 1024 a row
    for (size_t t = 0; t < 3 * GPURT_TRIANGLES_PER_ROW; ++t) {
        const size_t row = t / GPURT_TRIANGLES_PER_ROW, column = 3 * (t % GPURT_TRIANGLES_PER_ROW);
        const float* texel = &triangles.floats[(row * size_t(triangles.width) + column) * 4];
        if (t >= scene.triangles.size()) {
            for (int k = 0; k < 12; ++k) ASSERT_EQ(texel[k], 0.0f) << t;
            continue;
        }
        const Triangle& tri = scene.triangles[t];
        const vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
        const float expected[12] = {tri.v0.x, tri.v0.y, tri.v0.z, float(t % 3), e1.x, e1.y,
                                    e1.z,     0.0f,     e2.x,     e2.y,         e2.z, 0.0f};
        for (int k = 0; k < 12; ++k) ASSERT_EQ(texel[k], expected[k]) << t << " " << k;
    }

    const TextureTexels materials = materialTexels(scene);
    EXPECT_EQ(materials.width, 3 * GPURT_MATERIAL_TEXELS);
    EXPECT_EQ(materials.rows, 1);
    for (size_t m = 0; m < 3; ++m) {
        const Material& mat = scene.materials[m];
        // scene_layout.h: a channel is 4 texture + channel, -1 none (these materials have none).
        const float expected[4 * GPURT_MATERIAL_TEXELS] = {
            mat.diffuse.x,      mat.diffuse.y,      mat.diffuse.z,      mat.shininess,
            mat.specular.x,     mat.specular.y,     mat.specular.z,     float(mat.diffuseTexture),
            mat.reflectivity.x, mat.reflectivity.y, mat.reflectivity.z, 0.0f,
            mat.emission.x,     mat.emission.y,     mat.emission.z,     -1.0f,
            mat.transmission.x, mat.transmission.y, mat.transmission.z, mat.ior,
            mat.metallic,       mat.roughness,      mat.normalScale,    mat.occlusionStrength,
            -1.0f,              -1.0f,              -1.0f,              -1.0f,
            float(mat.alphaMode), 1.0f,             0.5f,               -1.0f,
            -1.0f,              -1.0f,              -1.0f,              1.0f,  // no specular maps, factor 1
            1.0f,               1.0f,               1.0f,               0.0f,  // specular colour, no clearcoat
            0.0f,               -1.0f,              -1.0f,              -1.0f,
            1.0f,               0.0f,               -1.0f,              -1.0f,  // no sheen
            0.0f,               0.0f,               0.0f,               -1.0f,  // no iridescence map
            0.0f,               0.0f,               0.0f,               -1.0f,  // no volume, no thickness map
            0.0f,               1.3f,               100.0f,             400.0f,  // no film, the extension's defaults
            0.0f,               1.0f,               0.0f,               -1.0f,  // no anisotropy: rotation 0, no map
            0.0f,               0.0f,               0.0f,               0.0f};  // no dispersion
        for (int k = 0; k < 4 * GPURT_MATERIAL_TEXELS; ++k)
            EXPECT_EQ(materials.floats[m * 4 * GPURT_MATERIAL_TEXELS + size_t(k)], expected[k]) << m << " " << k;
    }

    // Sizes as SceneTextures allocates them: texels x channels x 4 bytes.
    EXPECT_EQ(index.bytes(), size_t(index.width) * size_t(index.rows) * 2 * 4);
    EXPECT_EQ(triangles.bytes(), size_t(3 * GPURT_TRIANGLES_PER_ROW) * 3 * 4 * 4);
}

// The emitter table: the emitting triangles of non-zero area, by id, with the cumulative share
// of their areas (computed here from the triangles' areas), as the GL table.
TEST(SceneTextureLayoutTest, EmitterTableSharesAreTheAreas) {
    Scene scene;
    scene.materials = {Material{}, Material{}};
    scene.materials[1].emission = vec3(2.0f);
    // Areas 0.5, (emitting) 2, (emitting, zero area) 0, (emitting) 0.5 * 3 * 2 = 3.
    scene.triangles = {{vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)},
                       {vec3(0), vec3(2, 0, 0), vec3(0, 2, 0)},
                       {vec3(0), vec3(1, 0, 0), vec3(2, 0, 0)},
                       {vec3(0), vec3(0, 3, 0), vec3(0, 0, 2)}};
    scene.materialIds = {0, 1, 1, 1};
    const EmitterTable table = buildEmitterTable(scene);
    ASSERT_EQ(table.triangles, (std::vector<uint32_t>{1, 3}));
    EXPECT_FLOAT_EQ(table.totalArea, 5.0f);
    EXPECT_FLOAT_EQ(table.cdf[0], 0.4f);
    EXPECT_EQ(table.cdf[1], 1.0f);
    EXPECT_EQ(table.pick(0.0f), 0u);
    EXPECT_EQ(table.pick(0.39f), 0u);
    EXPECT_EQ(table.pick(0.4f), 1u);
    EXPECT_EQ(table.pick(0.99999994f), 1u);
    const TextureTexels texels = emitterTexels(table);
    EXPECT_EQ(std::string(texels.formatName()), "RG32F");
    EXPECT_EQ(texels.floats, (LargeArray<float>{table.cdf[0], 1.0f, 1.0f, 3.0f}));
    EXPECT_EQ(emitterTexels(EmitterTable{}).floats, (LargeArray<float>{1.0f, -1.0f}));
}

// Texture coordinates as the triangles (two texels each); the images one after another with
// their first texel, size and wrap modes in the table.
TEST(SceneTextureLayoutTest, TexturesAreWhereSceneLayoutSays) {
    Scene scene;
    const size_t n = GPURT_TRIANGLES_PER_ROW + 5;  // a second row
    for (size_t t = 0; t < n; ++t)
        scene.texcoords.push_back({vec2(float(t), 1.0f), vec2(2.0f, float(t)), vec2(-float(t), 0.5f)});
    const TextureTexels texcoords = texcoordTexels(scene);
    EXPECT_EQ(texcoords.width, GPURT_TEXCOORD_TEXELS * GPURT_TRIANGLES_PER_ROW);
    EXPECT_EQ(texcoords.rows, 2);
    for (size_t t = 0; t < n; ++t) {
        const size_t at = (t / GPURT_TRIANGLES_PER_ROW) * size_t(texcoords.width) + 2 * (t % GPURT_TRIANGLES_PER_ROW);
        const float* texel = &texcoords.floats[at * 4];
        const TriangleTexcoords& c = scene.texcoords[t];
        const float expected[8] = {c.t0.x, c.t0.y, c.t1.x, c.t1.y, c.t2.x, c.t2.y, 0.0f, 0.0f};
        for (int k = 0; k < 8; ++k) ASSERT_EQ(texel[k], expected[k]) << t << " " << k;
    }
    for (int k = 0; k < 2; ++k) {
        Texture texture;
        texture.image.width = 2 + k;
        texture.image.height = 3;
        for (int i = 0; i < texture.image.width * texture.image.height; ++i) texture.image.texels.push_back(uint32_t(100 * k + i));
        texture.wrapS = kWrapClamp;
        texture.wrapT = uint32_t(k == 0 ? kWrapMirror : kWrapRepeat);
        scene.textures.push_back(texture);
    }
    const TextureTexels texels = textureImageTexels(scene);
    EXPECT_EQ(texels.width, GPURT_INDEX_WIDTH);
    EXPECT_EQ(std::vector<uint32_t>(texels.uints.begin(), texels.uints.begin() + 15),
              (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 100, 101, 102, 103, 104, 105, 106, 107, 108}));
    EXPECT_EQ(textureTableTexels(scene).uints, (LargeArray<uint32_t>{0, 2, 3, 1 | 2 << 8, 6, 3, 3, 1}));
    EXPECT_EQ(textureTableTexels(Scene{}).uints, (LargeArray<uint32_t>{0, 1, 1, 0}));
    const TextureTexels srgb = srgbTableTexels();
    EXPECT_EQ(srgb.floats.front(), 0.0f);
    EXPECT_NEAR(srgb.floats.back(), 1.0f, 1e-6f);
    EXPECT_NEAR(srgb.floats[188], 0.5f, 0.003f);  // sRGB 188/255 is about half the light
}

TEST(SceneTextureLayoutTest, AnEmptySceneStillHasOneRowOfEach) {
    Scene empty;
    empty.materials.push_back(Material{});
    const std::vector<TextureTexels> all = sceneTextureTexels(empty, buildGrid(empty, {}));
    ASSERT_EQ(all.size(), 11u);
    for (const TextureTexels& t : all) {
        EXPECT_EQ(t.rows, 1) << t.name;
        EXPECT_EQ(t.isFloat ? t.floats.size() : t.uints.size(), t.texels() * size_t(t.channels))
            << t.name;
    }
}

// Materials wrap onto a new row every GPURT_MATERIALS_PER_ROW (scene_layout.h): 1100 materials
// make three rows as wide as that many materials, and material m's first texel, (diffuse,
// shininess), is at row m / GPURT_MATERIALS_PER_ROW, texel GPURT_MATERIAL_TEXELS times the rest.
TEST(SceneTextureLayoutTest, MaterialsWrapOntoRowsOfAFixedCount) {
    Scene scene;
    for (int m = 0; m < 1100; ++m) {
        Material mat;
        mat.diffuse = vec3(float(m), 0.5f, 0.25f);
        scene.materials.push_back(mat);
    }
    const TextureTexels t = materialTexels(scene);
    EXPECT_EQ(t.width, GPURT_MATERIALS_PER_ROW * GPURT_MATERIAL_TEXELS);
    EXPECT_EQ(t.rows, 3);
    for (int m : {0, 511, 512, 700, 1023, 1024, 1099}) {
        const size_t at = size_t(m / GPURT_MATERIALS_PER_ROW) * size_t(t.width) +
                          size_t(m % GPURT_MATERIALS_PER_ROW) * GPURT_MATERIAL_TEXELS;
        EXPECT_EQ(t.floats[4 * at], float(m)) << m;
        EXPECT_EQ(t.floats[4 * at + 1], 0.5f) << m;
    }
}

}  // namespace
}  // namespace gpurt
