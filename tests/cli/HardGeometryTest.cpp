// Hard but valid geometry through the gpurt program, on both backends: exit 0, no NaN in any
// AOV, a depth for every hit and none for a miss, GL and CPU agreeing with each other and with an
// independent expectation: Embree on the same rays, a formula, or the same scene at unit size.
// The scenes are generated here into a scratch folder.
#include "CliRunner.h"
#include "PngPixels.h"

#include <gtest/gtest.h>
#include <png.h>
#include <nlohmann/json.hpp>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "raytrace/camera/Camera.h"
#include "image/Colour.h"
#include "image/ImageIO.h"
#include "scene/ObjLoader.h"
#include "raytrace/accel/grid/UniformGrid.h"
#ifdef GPURT_HAVE_EMBREE
#include "raytrace/accel/BenchRays.h"
#include "raytrace/accel/EmbreeTracer.h"
#endif

namespace gpurt::test {
namespace {

// Exactly representable in the OBJ text: 9 significant digits round-trip a float.
std::string number(float x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", x);
    return text;
}

std::string vec3Text(glm::vec3 v) { return number(v.x) + "," + number(v.y) + "," + number(v.z); }

// An OBJ file being written: vertices and faces, 1-based as in the file.
class ObjText {
  public:
    int vertex(glm::vec3 v) {
        text_ << "v " << number(v.x) << " " << number(v.y) << " " << number(v.z) << "\n";
        return ++vertices_;
    }
    void face(std::initializer_list<int> indices) { face(std::vector<int>(indices)); }
    void face(const std::vector<int>& indices) {
        text_ << "f";
        for (int i : indices) text_ << " " << i;
        text_ << "\n";
        ++faces_;
    }
    int triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const int i = vertex(a), j = vertex(b), k = vertex(c);
        face({i, j, k});
        return faces_ - 1;  // the triangle's number when every face so far was a triangle
    }
    // An axis-aligned box as 12 triangles facing outwards.
    void box(glm::vec3 lo, glm::vec3 hi) {
        int v[8];
        for (int k = 0; k < 8; ++k)
            v[k] = vertex({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
        const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& q : quads) face({v[q[0]], v[q[1]], v[q[2]], v[q[3]]});
    }
    std::string str() const { return text_.str(); }

  private:
    std::ostringstream text_;
    int vertices_ = 0, faces_ = 0;
};

struct View {
    glm::vec3 eye, target;
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovy = 45.0f;
    int width = 48, height = 40;
};

// What one gpurt render wrote (rows top first, as readPfm returns them).
struct Render {
    int width = 0, height = 0;
    std::vector<float> depth, prim, normal;
    std::string png;
    nlohmann::json stats;
};

class HardGeometry : public GpurtTest {
  protected:
    // Renders `scene` with `view` (none: the scene's or the default camera at `size`).
    Render render(const std::string& scene, const std::optional<View>& view,
                  const std::string& backend, glm::ivec2 size = {48, 40}) {
        const std::string tag = backend + std::to_string(renders_++);
        std::string args = "render " + quoted(scene) + " --backend " + backend + " --stats=json" +
                           " -o " + quoted(tag + ".png");
        for (const char* aov : {"depth", "prim", "normal"})
            args += std::string(" --aov ") + aov + "=" + quoted(tag + aov + ".pfm");
        if (view) {
            args += " --size " + std::to_string(view->width) + "x" + std::to_string(view->height) +
                    " --eye " + vec3Text(view->eye) + " --target " + vec3Text(view->target) +
                    " --up " + vec3Text(view->up) + " --fovy " + number(view->fovy);
        } else {
            args += " --size " + std::to_string(size.x) + "x" + std::to_string(size.y);
        }
        const GpurtRun run = gpurt(args);
        Render r;
        EXPECT_EQ(run.code, 0) << "gpurt " << args << "\n" << run.err;
        EXPECT_EQ(run.err, "") << "gpurt " << args;  // no warning either
        if (run.code != 0) return r;
        int channels = 0;
        r.depth = readPfm(dir / (tag + "depth.pfm"), r.width, r.height, channels);
        r.prim = readPfm(dir / (tag + "prim.pfm"), r.width, r.height, channels);
        r.normal = readPfm(dir / (tag + "normal.pfm"), r.width, r.height, channels);
        r.png = readFile(dir / (tag + ".png"));
        r.stats = nlohmann::json::parse(run.out);
        return r;
    }

    // Both backends, each checked for well-formed AOVs, and checked against each other.
    std::pair<Render, Render> renderBoth(const std::string& scene, const std::optional<View>& view,
                                         size_t triangles, glm::ivec2 size = {48, 40}) {
        Render gl = render(scene, view, "gl", size), cpu = render(scene, view, "cpu", size);
        {
            SCOPED_TRACE("gl");
            expectWellFormed(gl, triangles);
        }
        {
            SCOPED_TRACE("cpu");
            expectWellFormed(cpu, triangles);
        }
        expectAgree(gl, cpu);
        return {gl, cpu};
    }

    // No NaN anywhere; a hit has a triangle number below `triangles`, a positive finite depth and
    // a unit normal; a miss has prim -1, depth +inf and normal 0; no ray reached the cell limit.
    static void expectWellFormed(const Render& r, size_t triangles) {
        ASSERT_EQ(r.depth.size(), size_t(r.width) * size_t(r.height));
        EXPECT_EQ(r.stats.value("overflow_rays", -1), 0);
        size_t bad = 0;
        for (size_t i = 0; i < r.depth.size(); ++i) {
            const float d = r.depth[i], p = r.prim[i];
            const glm::vec3 n(r.normal[3 * i], r.normal[3 * i + 1], r.normal[3 * i + 2]);
            const bool nan = std::isnan(d) || std::isnan(p) || std::isnan(n.x) || std::isnan(n.y) ||
                             std::isnan(n.z);
            const bool hit = p >= 0.0f;
            const bool ok =
                !nan && (hit ? (p == std::floor(p) && p < float(triangles) && d > 0.0f &&
                                std::isfinite(d) && std::abs(glm::length(n) - 1.0f) < 1e-3f)
                             : (p == -1.0f && std::isinf(d) && d > 0.0f && n == glm::vec3(0.0f)));
            if (!ok && ++bad <= 5)
                ADD_FAILURE() << "pixel " << i << ": depth " << d << " prim " << p << " normal "
                              << n.x << "," << n.y << "," << n.z;
        }
        EXPECT_EQ(bad, 0u);
    }

    // The same algorithm on both: the same triangle almost everywhere, the same depth.
    static void expectAgree(const Render& gl, const Render& cpu) {
        ASSERT_EQ(gl.depth.size(), cpu.depth.size());
        size_t prim = 0, depth = 0;
        for (size_t i = 0; i < gl.depth.size(); ++i) {
            prim += gl.prim[i] == cpu.prim[i];
            depth += sameDepth(gl.depth[i], cpu.depth[i], 1e-4f);
        }
        EXPECT_GE(double(prim) / double(gl.prim.size()), 0.999) << "GL and CPU triangles differ";
        EXPECT_GE(double(depth) / double(gl.prim.size()), 0.999) << "GL and CPU depths differ";
    }

    static bool sameDepth(float a, float b, float relative) {
        if (std::isinf(a) || std::isinf(b)) return a == b;
        return std::abs(a - b) <= relative * std::abs(b);
    }

    // Pixels where `expected` (t, or +inf for a miss; prim, or -1 for unknown) and the render
    // agree, over the pixels `expected` has an opinion on (prim < -1: no opinion).
    struct Expected {
        std::vector<float> depth;
        std::vector<int> prim;
    };
    static void expectMatches(const Render& r, const Expected& e, double share = 0.995,
                              float relative = 1e-4f) {
        size_t considered = 0, hitMiss = 0, hits = 0, prim = 0, depth = 0;
        for (size_t i = 0; i < r.depth.size(); ++i) {
            if (e.prim[i] < -1) continue;
            ++considered;
            const bool expectHit = std::isfinite(e.depth[i]);
            if (expectHit != (r.prim[i] >= 0.0f)) continue;
            ++hitMiss;
            if (!expectHit) continue;
            ++hits;
            prim += e.prim[i] == -1 || float(e.prim[i]) == r.prim[i];
            depth += sameDepth(r.depth[i], e.depth[i], relative);
        }
        ASSERT_GT(considered, r.depth.size() / 2);
        EXPECT_GE(double(hitMiss) / double(considered), share) << "hit or miss differs";
        if (hits == 0) return;
        EXPECT_GE(double(prim) / double(hits), share) << "triangle differs";
        EXPECT_GE(double(depth) / double(hits), share) << "depth differs";
    }

#ifdef GPURT_HAVE_EMBREE
    // Embree's first hits for the contract camera of `view` (the default camera when none).
    static Expected embree(const fs::path& scenePath, const std::optional<View>& view,
                           glm::ivec2 size = {48, 40}) {
        const Scene scene = loadObj(scenePath);
        CameraSpec spec;
        if (view) {
            spec = {view->eye, view->target, view->up, view->fovy};
            size = {view->width, view->height};
        } else {
            spec = defaultCamera(scene.bounds(), size.x, size.y);
        }
        const RayStream rays = primaryRays(makeCamera(spec, size.x, size.y));
        std::vector<glm::vec4> hits;
        EmbreeTracer(scene, 1).trace(rays, false, EmbreeMode::Single, hits);
        Expected e;
        for (const glm::vec4& h : hits) {
            e.depth.push_back(h.w >= 0.0f ? h.x : INFINITY);
            e.prim.push_back(h.w >= 0.0f ? int(h.w) : -1);
        }
        return e;
    }
#endif

    // Both backends against Embree (where built with it) for each view.
    void renderAndCompare(const std::string& scene, size_t triangles,
                          std::initializer_list<View> views) {
        for (const View& view : views) {
            SCOPED_TRACE("eye " + vec3Text(view.eye) + " target " + vec3Text(view.target));
            const auto [gl, cpu] = renderBoth(scene, view, triangles);
            size_t hits = 0;
            for (float p : cpu.prim) hits += p >= 0.0f;
            EXPECT_GT(hits, cpu.prim.size() / 20) << "the view shows too little";
#ifdef GPURT_HAVE_EMBREE
            const Expected reference = embree(dir / scene, view);
            expectMatches(gl, reference);
            expectMatches(cpu, reference);
#endif
        }
    }

  private:
    int renders_ = 0;
};

// The contract's ray through pixel i of a view where it meets the plane z = zPlane: t and the
// point, computed in double from the float ray (an independent evaluation of the hit).
struct PlaneHit {
    double t;
    glm::dvec3 p;
};
PlaneHit hitPlaneZ(const View& view, size_t pixel, double zPlane) {
    CameraSpec spec{view.eye, view.target, view.up, view.fovy};
    const CameraBasis camera = makeCamera(spec, view.width, view.height);
    const glm::dvec3 d(
        primaryDirection(camera, int(pixel % size_t(view.width)), int(pixel / size_t(view.width))));
    const glm::dvec3 o(view.eye);
    const double t = (zPlane - o.z) / d.z;
    return {t, o + t * d};
}

TEST_F(HardGeometry, DegenerateZeroAreaTriangles) {
    // A square [-1, 1]^2 at z = 0 as two triangles among zero-area ones: a repeated vertex, a
    // single point, three collinear points on the square's diagonal and three collinear points
    // in front of it, and a polygon with a repeated vertex (whose fan has one zero-area part).
    ObjText obj;
    const int a = obj.vertex({-1, -1, 0}), b = obj.vertex({1, -1, 0}), c = obj.vertex({1, 1, 0}),
              d = obj.vertex({-1, 1, 0}), centre = obj.vertex({0, 0, 0});
    const int p = obj.vertex({0.3f, 0.2f, 0.5f});
    const int l0 = obj.vertex({0.1f, 0.2f, 0.3f}), l1 = obj.vertex({0.4f, 0.5f, 0.6f}),
              l2 = obj.vertex({0.7f, 0.8f, 0.9f});
    obj.face({a, a, b});             // 0: repeated vertex
    obj.face({a, b, c});             // 1: the square's first half
    obj.face({p, p, p});             // 2: a point
    obj.face({a, c, centre});        // 3: collinear, in the square's plane
    obj.face({l0, l1, l2});          // 4: collinear, in front of the square
    obj.face({a, c, d});             // 5: the square's second half
    obj.face({a, b, b, c});          // 6, 7: (a, b, b) zero area, then (a, b, c) again
    obj.face({l2, l0, l1, l1, l2});  // 8, 9, 10: all collinear
    write("degenerate.obj", obj.str());
    const std::vector<int> good = {1, 5, 7};

    const View views[] = {{{0.3f, -0.4f, 2.5f}, {0, 0, 0}},
                          {{-2.0f, 1.5f, 0.7f}, {0.2f, 0.1f, 0}, {0, 0, 1}, 60}};
    for (const View& view : views) {
        SCOPED_TRACE("eye " + vec3Text(view.eye));
        const auto [gl, cpu] = renderBoth("degenerate.obj", view, 11);
        for (const Render* r : {&gl, &cpu}) {
            size_t hits = 0, wrong = 0;
            for (size_t i = 0; i < r->prim.size(); ++i) {
                const PlaneHit h = hitPlaneZ(view, i, 0.0);
                const double edge = std::max(std::abs(h.p.x), std::abs(h.p.y));
                if (h.t > 0 && std::abs(edge - 1.0) < 1e-3) continue;  // on the square's edge
                const bool expectHit = h.t > 0 && edge < 1.0;
                const bool isHit = r->prim[i] >= 0.0f;
                const bool goodPrim =
                    std::find(good.begin(), good.end(), int(r->prim[i])) != good.end();
                if (isHit != expectHit ||
                    (isHit && (!goodPrim || std::abs(r->depth[i] - h.t) > 1e-5 * h.t)))
                    ++wrong;
                hits += isHit;
            }
            EXPECT_GT(hits, r->prim.size() / 10);
            EXPECT_EQ(wrong, 0u) << "pixels that miss the square, hit a zero-area triangle, or "
                                    "have the wrong depth";
        }
    }
}

TEST_F(HardGeometry, NoTrianglesAtAll) {
    write("empty.obj", "");
    write("vertices.obj", "# only vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n");
    write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\np 1\n");
    write("empty.json", R"({"meshes": [], "background": [0.2, 0.4, 0.6]})");
    write("empty-mesh.json",
          R"({"meshes": [{"file": "empty.obj"}], "background": [0.2, 0.4, 0.6]})");
    const glm::vec3 defaultBackground = Scene{}.background, background(0.2f, 0.4f, 0.6f);
    const std::pair<const char*, glm::vec3> scenes[] = {{"empty.obj", defaultBackground},
                                                        {"vertices.obj", defaultBackground},
                                                        {"lines.obj", defaultBackground},
                                                        {"empty.json", background},
                                                        {"empty-mesh.json", background}};
    for (const auto& [scene, colour] : scenes) {
        SCOPED_TRACE(scene);
        for (const std::optional<View>& view :
             {std::optional<View>(), std::optional<View>(View{{0, 0, 5}, {0, 0, 0}})}) {
            const auto [gl, cpu] = renderBoth(scene, view, 0);
            for (const Render* r : {&gl, &cpu}) {
                int width = 0, height = 0;
                const std::vector<unsigned char> pixels = pngPixels(r->png, width, height);
                ASSERT_EQ(pixels.size(), size_t(r->width) * size_t(r->height) * 3);
                // The PNG is the background through the default tone map, then sRGB.
                const glm::vec3 display = toneMapImage({colour}, ColourSettings{})[0];
                size_t other = 0;
                for (size_t k = 0; k < pixels.size(); ++k)
                    other += pixels[k] != linearToSrgb8(display[int(k % 3)]);
                EXPECT_EQ(other, 0u) << "pixels that are not the background";
                size_t hits = 0;
                for (float p : r->prim) hits += p >= 0.0f;
                EXPECT_EQ(hits, 0u);
            }
        }
    }
}

TEST_F(HardGeometry, AllTrianglesOnACellBoundary) {
    // A 12 x 12 grid of squares (288 triangles) in one plane z = zb, and two small triangles at
    // z = -1 and z = 1 that fix the grid's box. The plane is placed exactly on a boundary between
    // two layers of cells of the grid the renderer builds (the same buildGrid, the same options).
    const int n = 12;
    auto scene = [&](float zb) {
        ObjText obj;
        obj.triangle({-1, -1, -1}, {-0.9f, -1, -1}, {-1, -0.9f, -1});
        obj.triangle({1, 1, 1}, {0.9f, 1, 1}, {1, 0.9f, 1});
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const float x0 = -1 + 2.0f * i / n, x1 = -1 + 2.0f * (i + 1) / n;
                const float y0 = -1 + 2.0f * j / n, y1 = -1 + 2.0f * (j + 1) / n;
                obj.triangle({x0, y0, zb}, {x1, y0, zb}, {x1, y1, zb});
                obj.triangle({x0, y0, zb}, {x1, y1, zb}, {x0, y1, zb});
            }
        return obj.str();
    };
    const UniformGrid before = buildGrid(loadObj(write("plane.obj", scene(0.0f))), GridOptions{});
    ASSERT_GE(before.resolution.z, 2);
    // The boundary after cell layer k - 1, as the traversal computes it (raymath.h ddaBoundary).
    const int k = before.resolution.z / 2;
    const float zb = before.min.z + float(k) * before.cellSize.z;
    const fs::path path = write("plane.obj", scene(zb));
    const UniformGrid grid = buildGrid(loadObj(path), GridOptions{});
    ASSERT_EQ(grid.resolution, before.resolution);
    ASSERT_EQ(grid.min, before.min);
    ASSERT_EQ(grid.cellSize, before.cellSize);
    const size_t triangles = 2 + 2 * n * n;

    const View above{{0.3f, 0.2f, 3.0f}, {0, 0, zb}};
    const View grazing{{-1.5f, 0.1f, zb + 0.3f}, {0.3f, 0, zb}, {0, 1, 0}, 60};
    renderAndCompare("plane.obj", triangles, {above, grazing});
    // The depth of the plane where the rays cross it, an independent formula.
    for (const View& view : {above, grazing}) {
        const auto [gl, cpu] = renderBoth("plane.obj", view, triangles);
        EXPECT_EQ(cpu.stats["grid"],
                  nlohmann::json({grid.resolution.x, grid.resolution.y, grid.resolution.z}));
        Expected plane;
        for (size_t i = 0; i < cpu.depth.size(); ++i) {
            const PlaneHit h = hitPlaneZ(view, i, double(zb));
            const double edge = std::max(std::abs(h.p.x), std::abs(h.p.y));
            const bool unsure = h.t <= 0 || std::abs(edge - 1.0) < 1e-2;  // edges, anchors
            plane.depth.push_back(h.t > 0 && edge < 1.0 ? float(h.t) : INFINITY);
            plane.prim.push_back(unsure ? -2 : -1);
        }
        expectMatches(gl, plane, 0.999, 1e-5f);
        expectMatches(cpu, plane, 0.999, 1e-5f);
    }
    // Looking along the plane from inside it: the squares are edge-on (the middle column of
    // rays lies in the plane) and only the anchors can be hit.
    const View edgeOn{{-3.0f, 0.2f, zb}, {0, 0.2f, zb}, {0, 1, 0}, 90, 49, 41};
    const auto [gl, cpu] = renderBoth("plane.obj", edgeOn, triangles);
    for (const Render* r : {&gl, &cpu})
        for (size_t i = size_t(edgeOn.width / 2); i < r->prim.size(); i += size_t(edgeOn.width))
            EXPECT_LT(r->prim[i], 2.0f) << "a square hit edge-on at pixel " << i;
}

TEST_F(HardGeometry, ThousandsOfTinyTrianglesInOneCellBesideOneFarAway) {
    // 5000 triangles about 1e-3 across in a 1e-2 cube at the origin, one triangle 10 across at
    // x = 1000: the grid's cells are far larger than the cluster, which lands in one cell.
    ObjText obj;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> inCube(0.0f, 0.01f), offset(-0.001f, 0.001f);
    const int tiny = 5000;
    for (int t = 0; t < tiny; ++t) {
        const glm::vec3 c(inCube(rng), inCube(rng), inCube(rng));
        obj.triangle(c, c + glm::vec3(offset(rng), offset(rng), offset(rng)),
                     c + glm::vec3(offset(rng), offset(rng), offset(rng)));
    }
    obj.triangle({1000, -5, -5}, {1000, 5, -5}, {1000, 0, 5});
    const fs::path path = write("cluster.obj", obj.str());
    const UniformGrid grid = buildGrid(loadObj(path), GridOptions{});
    const glm::ivec3 cell = glm::ivec3((glm::vec3(0.005f) - grid.min) / grid.cellSize);
    const size_t c = size_t(grid.cellIndex(cell));
    ASSERT_EQ(grid.cellStart[c + 1] - grid.cellStart[c], uint32_t(tiny))
        << "the cluster should be in one cell";

    renderAndCompare("cluster.obj", tiny + 1,
                     {View{{0.005f, 0.006f, 0.03f}, {0.005f, 0.005f, 0.005f}, {0, 1, 0}, 40},
                      View{{-0.02f, 0.004f, 0.006f}, {0.005f, 0.005f, 0.005f}, {0, 0, 1}, 50},
                      View{{990, 1, 2}, {1000, 0, 0}, {0, 1, 0}, 90},
                      View{{0.005f, 0.005f, 0.005f}, {1000, 0, 0}, {0, 1, 0}, 1.5f}});
}

TEST_F(HardGeometry, PolygonsWithManyVertices) {
    // A regular 1000-gon of radius 1 at z = 0 and a 300-gon of radius 0.5 at z = 0.5 (more than
    // the 255 vertices tinyobjloader counts in a byte), each one face, fanned from its vertex 0.
    ObjText obj;
    auto polygon = [&](int count, float radius, float z) {
        std::vector<int> face;
        for (int k = 0; k < count; ++k) {
            const double angle = 2.0 * std::numbers::pi * k / count;
            face.push_back(
                obj.vertex({float(radius * std::cos(angle)), float(radius * std::sin(angle)), z}));
        }
        obj.face(face);
    };
    polygon(1000, 1.0f, 0.0f);
    polygon(300, 0.5f, 0.5f);
    write("polygons.obj", obj.str());
    const size_t triangles = 998 + 298;
    const View view{{0.2f, -0.3f, 3.0f}, {0, 0, 0}};
    renderAndCompare("polygons.obj", triangles, {view, View{{1.5f, 0.4f, 0.25f}, {0, 0, 0.2f}}});

    // From above: inside the big disc but outside the small one, the depth of the plane z = 0.
    const auto [gl, cpu] = renderBoth("polygons.obj", view, triangles);
    Expected disc;
    for (size_t i = 0; i < cpu.depth.size(); ++i) {
        const PlaneHit low = hitPlaneZ(view, i, 0.0), high = hitPlaneZ(view, i, 0.5);
        const double r = std::hypot(low.p.x, low.p.y), rHigh = std::hypot(high.p.x, high.p.y);
        const bool sure = (r < 0.999 || r > 1.0) && (rHigh > 0.5 || rHigh < 0.499);
        disc.depth.push_back(rHigh < 0.5 ? float(high.t) : r < 1.0 ? float(low.t) : INFINITY);
        disc.prim.push_back(sure ? -1 : -2);
    }
    // Relative 1e-4: the fan's triangles are slivers, Moller-Trumbore's t loses digits on them.
    expectMatches(gl, disc, 0.999, 1e-4f);
    expectMatches(cpu, disc, 0.999, 1e-4f);
}

// The shared teapot scaled by `scale` about the origin (exactly when scale is a power of two).
std::string scaledTeapot(double scale) {
    std::istringstream in(readFile("../shared/models/teapot.obj"));
    std::ostringstream out;
    for (std::string line; std::getline(in, line);) {
        double x, y, z;
        if (line.rfind("v ", 0) == 0 && std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3)
            out << "v " << number(float(float(x) * scale)) << " " << number(float(float(y) * scale))
                << " " << number(float(float(z) * scale)) << "\n";
        else
            out << line << "\n";
    }
    return out.str();
}

TEST_F(HardGeometry, HugeAndTinyCoordinates) {
    // The teapot at unit size is the reference (checked against Embree); scaled by 2^k it must
    // give the same picture, triangles and normals and depths 2^k times as large, with the
    // default camera and with an explicit one scaled alike. 1e30 and 1e-30 are not powers of
    // two: the vertices round differently, so nearly the same picture.
    write("teapot.obj", scaledTeapot(1.0));
    const View view{{30, 25, 40}, {0, 2, 0}};
    renderAndCompare("teapot.obj", 992, {view});
    const auto [glUnit, cpuUnit] = renderBoth("teapot.obj", std::nullopt, 992);
    const auto [glView, cpuView] = renderBoth("teapot.obj", view, 992);

    for (int exponent : {100, -100, 60, -60}) {
        SCOPED_TRACE("2^" + std::to_string(exponent));
        const std::string name = "teapot" + std::to_string(exponent) + ".obj";
        write(name, scaledTeapot(std::ldexp(1.0, exponent)));
        View scaled = view;
        scaled.eye = glm::vec3(glm::dvec3(view.eye) * std::ldexp(1.0, exponent));
        scaled.target = glm::vec3(glm::dvec3(view.target) * std::ldexp(1.0, exponent));
        const auto [gl, cpu] = renderBoth(name, std::nullopt, 992);
        const auto [glV, cpuV] = renderBoth(name, scaled, 992);
        for (const auto& [r, unit] :
             {std::pair{&gl, &glUnit}, {&cpu, &cpuUnit}, {&glV, &glView}, {&cpuV, &cpuView}}) {
            EXPECT_EQ(r->prim, unit->prim);
            EXPECT_EQ(r->normal, unit->normal);
            EXPECT_EQ(r->png, unit->png);
            size_t exact = 0;
            for (size_t i = 0; i < r->depth.size(); ++i)
                exact += r->depth[i] == std::ldexp(unit->depth[i], exponent);
            EXPECT_EQ(exact, r->depth.size()) << "depths are not the unit depths times 2^k";
        }
    }
    for (double scale : {1e30, 1e-30, 1e15, 1e-15}) {
        SCOPED_TRACE("scale " + number(float(scale)));
        const std::string name = "teapot" + number(float(scale)) + ".obj";
        write(name, scaledTeapot(scale));
        const auto [gl, cpu] = renderBoth(name, std::nullopt, 992);
        Expected unit;
        for (size_t i = 0; i < cpuUnit.depth.size(); ++i) {
            unit.depth.push_back(float(double(cpuUnit.depth[i]) * scale));
            unit.prim.push_back(int(cpuUnit.prim[i]));
        }
        expectMatches(gl, unit, 0.99);
        expectMatches(cpu, unit, 0.99);
    }
}

TEST_F(HardGeometry, CoordinatesNearTheLargestFloat) {
    // A box from -2e38 to 2e38: its extent overflows float, but each coordinate is a float.
    // The same box at unit size, seen from the same place, is the reference. With the wide view
    // the farthest hits are beyond the largest float; their depth is the largest float.
    for (const auto& [name, s] : {std::pair{"unit.obj", 2.0f}, {"huge.obj", 2e38f}}) {
        ObjText obj;
        obj.box(glm::vec3(-s), glm::vec3(s));
        obj.box(glm::vec3(-s / 3, -s / 3, -s / 2), glm::vec3(s / 4, s / 5, -s / 4));
        write(name, obj.str());
    }
    for (float fovy : {60.0f, 150.0f}) {
        SCOPED_TRACE("fovy " + number(fovy));
        const View unitView{{0.1f, 0.2f, 0.2f}, {0, 0, -1}, {0, 1, 0}, fovy};
        const View hugeView{unitView.eye * 1e38f, unitView.target * 1e38f, {0, 1, 0}, fovy};
        const auto [glUnit, cpuUnit] = renderBoth("unit.obj", unitView, 24);
        const auto [gl, cpu] = renderBoth("huge.obj", hugeView, 24);
        Expected unit;
        size_t beyond = 0;
        for (size_t i = 0; i < cpuUnit.depth.size(); ++i) {
            const double depth = double(cpuUnit.depth[i]) * 1e38;
            beyond += std::isfinite(depth) && depth > FLT_MAX;
            unit.depth.push_back(std::isfinite(depth) ? float(std::min(depth, double(FLT_MAX)))
                                                      : INFINITY);
            unit.prim.push_back(int(cpuUnit.prim[i]));
        }
        EXPECT_EQ(beyond > 0, fovy > 90.0f);
        expectMatches(gl, unit, 0.99);
        expectMatches(cpu, unit, 0.99);
    }
}

TEST_F(HardGeometry, RaysParallelToAxes) {
    // A closed room [0, 4]^3 with a box inside. The eye sits on cell boundaries in two axes and
    // looks along the third, with an odd image: the middle row and column of rays have exactly
    // zero components and run along cell boundaries; the middle ray is parallel to an axis.
    ObjText obj;
    obj.box({0, 0, 0}, {4, 4, 4});
    obj.box({1, 1, 0.5f}, {2.5f, 2.5f, 2});
    const fs::path path = write("room.obj", obj.str());
    const UniformGrid grid = buildGrid(loadObj(path), GridOptions{});
    auto boundary = [&](int axis, float near) {
        const int k = int(std::lround((near - grid.min[axis]) / grid.cellSize[axis]));
        return grid.min[axis] + float(k) * grid.cellSize[axis];
    };
    const float x = boundary(0, 1.6f), y = boundary(1, 1.9f), z = boundary(2, 1.2f);
    ASSERT_TRUE(x > 1 && x < 2.5f && y > 1 && y < 2.5f);
    const View down{{x, y, 3.5f}, {x, y, 0}, {0, 1, 0}, 60, 41, 41};
    const View along{{0.5f, y, z}, {3, y, z}, {0, 0, 1}, 60, 41, 41};
    const View back{{x, 3.7f, z}, {x, 0, z}, {1, 0, 0}, 60, 41, 41};
    renderAndCompare("room.obj", 24, {down, along, back});

    // The middle ray of each: straight down onto the inner box's top at z = 2, along +x into
    // its side at x = 1 (z = 1.2 is within its height), along -y onto the inner box at y = 2.5.
    const struct {
        View view;
        float depth;
    } axisRays[] = {{down, 3.5f - 2.0f}, {along, 1.0f - 0.5f}, {back, 3.7f - 2.5f}};
    for (const auto& [view, depth] : axisRays) {
        const auto [gl, cpu] = renderBoth("room.obj", view, 24);
        const size_t middle = size_t(view.height / 2) * size_t(view.width) + size_t(view.width / 2);
        for (const Render* r : {&gl, &cpu}) {
            EXPECT_GE(r->prim[middle], 12.0f) << "the middle ray should hit the inner box";
            EXPECT_NEAR(r->depth[middle], depth, 1e-6f * depth);
        }
    }
}

TEST_F(HardGeometry, CameraInsideTheGridAndInACellWithTriangles) {
    // A room with 400 small triangles scattered in it; the eye is inside the grid, in a cell
    // that holds triangles, 1e-3 in front of one of them.
    ObjText obj;
    obj.box({-4, -4, -4}, {4, 4, 4});
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> inRoom(-3.5f, 3.5f), edge(-0.4f, 0.4f);
    glm::vec3 first[3] = {};
    for (int t = 0; t < 400; ++t) {
        const glm::vec3 c(inRoom(rng), inRoom(rng), inRoom(rng));
        const glm::vec3 v[3] = {c, c + glm::vec3(edge(rng), edge(rng), edge(rng)),
                                c + glm::vec3(edge(rng), edge(rng), edge(rng))};
        obj.triangle(v[0], v[1], v[2]);
        if (t == 0) std::copy(v, v + 3, first);
    }
    const fs::path path = write("scatter.obj", obj.str());
    const glm::vec3 centroid = (first[0] + first[1] + first[2]) / 3.0f;
    const glm::vec3 normal = glm::normalize(glm::cross(first[1] - first[0], first[2] - first[0]));
    const glm::vec3 eye = centroid + 1e-3f * normal;
    const UniformGrid grid = buildGrid(loadObj(path), GridOptions{});
    const size_t cell = size_t(grid.cellIndex(glm::ivec3((eye - grid.min) / grid.cellSize)));
    ASSERT_GT(grid.cellStart[cell + 1], grid.cellStart[cell]) << "the eye's cell is empty";

    renderAndCompare("scatter.obj", 412,
                     {View{eye, eye + normal, {0, 1, 0}, 90},  // onto its triangle's back
                      View{eye, eye - normal, {0, 1, 0}, 90},  // away from it
                      View{eye, eye + glm::vec3(1, 0, 0), {0, 1, 0}, 100},
                      View{eye, eye + glm::vec3(0, -1, 0.001f), {1, 0, 0}, 70},
                      View{{0.1f, 0.2f, 0.3f}, {2, 1, -3}, {0, 1, 0}, 80}});
}

}  // namespace
}  // namespace gpurt::test
