// The watertight triangle test (common/raymath.h intersectTriangle; Woop, Benthin and Wald 2013)
// in every traversal that runs it: rays aimed exactly at the shared edges and vertices of closed
// meshes (a finely tessellated UV sphere, as a glTF sphere is, and a subdivided box, built here
// with shared vertices) never pass between two triangles. From outside each ray hits the near
// surface at the aimed point's distance, and a shadow ray that ends just past that point is
// blocked; from inside each ray hits the mesh at the aimed point. On both backends (gl: the grid's
// fused and split kernels, the BVH; cpu: the grid, the BVH), closest hit and any hit. The
// expectation is geometry (the distance to the aimed point), not another tracer's answer.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/accel/GlRegistry.h"
#include "raytrace/render/Renderer.h"
#include "raytrace/accel/Acceleration.h"

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace gpurt::test {
namespace {

class Watertight : public GLTest {};

// A closed mesh with shared vertices: every triangle names its vertices by index.
struct Mesh {
    std::string name;
    glm::vec3 centre{0.0f};
    std::vector<glm::vec3> vertices;
    std::vector<glm::ivec3> triangles;

    // Adds the triangle (a, b, c), wound so that it faces away from the centre.
    void add(int a, int b, int c) {
        const glm::vec3 pa = vertices[size_t(a)], pb = vertices[size_t(b)], pc = vertices[size_t(c)];
        if (glm::dot(glm::cross(pb - pa, pc - pa), pa + pb + pc - 3.0f * centre) < 0.0f) std::swap(b, c);
        triangles.push_back({a, b, c});
    }
};

// A UV sphere (the usual glTF sphere): `stacks` rings of quads, split into two triangles each, and
// a fan at each pole; the seam's vertices are shared.
Mesh uvSphere(glm::vec3 centre, float radius, int stacks, int slices) {
    Mesh m{"uv sphere", centre, {}, {}};
    m.vertices.push_back(centre + glm::vec3(0.0f, radius, 0.0f));
    for (int i = 1; i < stacks; ++i) {
        const double theta = M_PI * double(i) / double(stacks);
        for (int j = 0; j < slices; ++j) {
            const double phi = 2.0 * M_PI * double(j) / double(slices);
            m.vertices.push_back(centre + radius * glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                                             float(std::sin(theta) * std::sin(phi))));
        }
    }
    m.vertices.push_back(centre - glm::vec3(0.0f, radius, 0.0f));
    const int south = int(m.vertices.size()) - 1;
    auto ring = [&](int i, int j) { return 1 + (i - 1) * slices + (j % slices); };
    for (int j = 0; j < slices; ++j) {
        m.add(0, ring(1, j), ring(1, j + 1));
        m.add(south, ring(stacks - 1, j + 1), ring(stacks - 1, j));
        for (int i = 1; i + 1 < stacks; ++i) {
            m.add(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
            m.add(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
        }
    }
    return m;
}

// The box [lo, hi] with each face an n x n grid of quads split into two triangles; the lattice
// point (i, j, k) is computed once, so the faces meeting at an edge share its vertices.
Mesh subdividedBox(glm::vec3 lo, glm::vec3 hi, int n) {
    Mesh m{"box", 0.5f * (lo + hi), {}, {}};
    std::map<std::array<int, 3>, int> index;
    auto at = [&](int i, int j, int k) {
        const std::array<int, 3> key{i, j, k};
        auto it = index.find(key);
        if (it != index.end()) return it->second;
        m.vertices.push_back(lo + (hi - lo) * glm::vec3(float(i), float(j), float(k)) / float(n));
        return index[key] = int(m.vertices.size()) - 1;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side : {0, n})
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    auto corner = [&](int da, int db) {
                        std::array<int, 3> c{};
                        c[size_t(axis)] = side;
                        c[size_t((axis + 1) % 3)] = a + da;
                        c[size_t((axis + 2) % 3)] = b + db;
                        return at(c[0], c[1], c[2]);
                    };
                    // Alternate the diagonal, so both directions of shared diagonals are tested.
                    if ((a + b) % 2 == 0) {
                        m.add(corner(0, 0), corner(1, 0), corner(1, 1));
                        m.add(corner(0, 0), corner(1, 1), corner(0, 1));
                    } else {
                        m.add(corner(0, 0), corner(1, 0), corner(0, 1));
                        m.add(corner(1, 0), corner(1, 1), corner(0, 1));
                    }
                }
    return m;
}

// A point on the mesh to aim at (a vertex, or a point of a shared edge) and the outward unit
// normals of the triangles that share it.
struct Target {
    glm::vec3 p;
    std::vector<glm::vec3> normals;
};

std::vector<Target> targets(const Mesh& m) {
    std::vector<std::vector<glm::vec3>> vertexNormals(m.vertices.size());
    std::map<std::pair<int, int>, std::vector<glm::vec3>> edges;
    for (const glm::ivec3& t : m.triangles) {
        const glm::vec3 a = m.vertices[size_t(t.x)], b = m.vertices[size_t(t.y)], c = m.vertices[size_t(t.z)];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            vertexNormals[size_t(t[k])].push_back(n);
            const int i = t[k], j = t[(k + 1) % 3];
            edges[{std::min(i, j), std::max(i, j)}].push_back(n);
        }
    }
    std::vector<Target> out;
    for (size_t v = 0; v < m.vertices.size(); ++v) out.push_back({m.vertices[v], vertexNormals[v]});
    for (const auto& [edge, normals] : edges) {
        EXPECT_EQ(normals.size(), 2u) << m.name << ": an edge not shared by two triangles (not closed)";
        const glm::vec3 a = m.vertices[size_t(edge.first)], b = m.vertices[size_t(edge.second)];
        for (float s : {0.5f, 0.25f, 0.8f}) out.push_back({a + s * (b - a), normals});
    }
    return out;
}

// The rays of one check, with the distance from each origin to its aimed point.
struct Rays {
    RayStream stream;
    std::vector<float> distance;
    std::vector<std::string> what;  // each ray described, for the failures
};

void addRay(Rays& r, glm::vec3 o, glm::vec3 p, const std::string& what) {
    r.stream.origin.push_back(o);
    r.stream.direction.push_back(raymath::contractNormalize(p - o));
    r.stream.tLimit.push_back(GPURT_FAR);
    r.distance.push_back(glm::length(p - o));
    r.what.push_back(what);
}

std::string text(glm::vec3 v) {
    std::ostringstream s;
    s.precision(9);
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

// Whether every triangle at the target faces the origin o (outside: front faces) clearly, not
// grazing: the ray then meets the surface there and nowhere nearer (the meshes are convex).
bool seesClearly(const Target& t, glm::vec3 o, bool inside) {
    const glm::vec3 toOrigin = glm::normalize(o - t.p);
    for (const glm::vec3& n : t.normals)
        if ((inside ? -1.0f : 1.0f) * glm::dot(n, toOrigin) < 0.2f) return false;
    return true;
}

// From outside: from eyes around the mesh (on the axes, and off them), and from points straight
// above each target along each axis (axis-aligned rays).
Rays outsideRays(const Mesh& m, const std::vector<Target>& ts) {
    Rays r;
    std::vector<glm::vec3> dirs = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                                   glm::normalize(glm::vec3(-1, 0.4f, 0.8f)), glm::normalize(glm::vec3(0.3f, -1, -0.6f))};
    for (float x : {-1.0f, 1.0f})  // towards the corners (the box's edges and corners face these)
        for (float y : {-1.0f, 1.0f})
            for (float z : {-1.0f, 1.0f}) dirs.push_back(glm::normalize(glm::vec3(x, y, z)));
    for (const Target& t : ts) {
        for (const glm::vec3& dir : dirs) {
            const glm::vec3 eye = m.centre + 3.5f * dir;
            if (seesClearly(t, eye, false)) addRay(r, eye, t.p, "from eye " + text(eye) + " at " + text(t.p));
        }
        for (int axis = 0; axis < 3; ++axis)
            for (float side : {-1.0f, 1.0f}) {
                glm::vec3 eye = t.p;
                eye[axis] += side * 3.0f;
                if (seesClearly(t, eye, false)) addRay(r, eye, t.p, "axis-aligned from " + text(eye) + " at " + text(t.p));
            }
    }
    return r;
}

// From inside, near the centre: every ray must leave through the mesh.
Rays insideRays(const Mesh& m, const std::vector<Target>& ts) {
    Rays r;
    const glm::vec3 o = m.centre + glm::vec3(0.013f, -0.021f, 0.017f);
    for (const Target& t : ts)
        if (seesClearly(t, o, true)) addRay(r, o, t.p, "from inside at " + text(t.p));
    return r;
}

void layOut(Rays& r) {
    const size_t n = r.stream.origin.size();
    r.stream.width = 256;
    r.stream.height = int((n + 255) / 256);
    const size_t all = size_t(r.stream.width) * size_t(r.stream.height);
    r.stream.origin.resize(all, glm::vec3(0.0f));
    r.stream.direction.resize(all, glm::vec3(0.0f, 0.0f, 1.0f));
    r.stream.tLimit.resize(all, -1.0f);
}

// Shadow rays along the same lines that end just past the aimed point: only the near surface can
// block them.
Rays shadowRays(const Rays& closest) {
    Rays r = closest;
    for (size_t i = 0; i < r.distance.size(); ++i) r.stream.tLimit[i] = r.distance[i] * 1.001f + 1e-4f;
    return r;
}

// The rays whose hit is not the aimed point (closest hit: a miss, or t off by more than a
// millionth-ish of the distance; any hit: not blocked), with the first few described.
size_t failures(const Rays& r, const std::vector<glm::vec4>& hits, bool anyHit, std::string& examples) {
    size_t bad = 0;
    for (size_t i = 0; i < r.distance.size(); ++i) {
        const glm::vec4 h = hits[i];
        const bool ok = h.w >= 0.0f && (anyHit || std::abs(h.x - r.distance[i]) <= 1e-4f * r.distance[i]);
        if (ok) continue;
        if (++bad <= 3) {
            std::ostringstream s;
            s << "  " << r.what[i] << ": prim " << h.w << " t " << h.x << ", expected t " << r.distance[i] << "\n";
            examples += s.str();
        }
    }
    return bad;
}

struct Tracer {
    std::string name;
    Backend backend;
    const char* accel;
    TraceKernel kernel = TraceKernel::Fused;
};

std::vector<glm::vec4> trace(const Scene& scene, const Acceleration& accel, const Tracer& how, const Rays& rays,
                             bool anyHit) {
    std::vector<glm::vec4> hits;
    if (how.backend == Backend::Cpu) {
        CpuTracer(scene, makeCpuAccelerator(scene, accel), accel.rayOffset()).traceStream(rays.stream, anyHit, 0, hits);
        return hits;
    }
    GpuTracerOptions options;
    options.kernel = how.kernel;
    GpuTracer tracer(scene, makeGlAccelerator(scene, accel, options), accel.rayOffset(), options);
    tracer.setRays(rays.stream);
    tracer.traceRays(anyHit);
    return tracer.hits();
}

TEST_F(Watertight, RaysAtSharedEdgesAndVerticesNeverPassThrough) {
    const std::vector<Mesh> meshes = {uvSphere(glm::vec3(0.11f, -0.07f, 0.05f), 1.0f, 48, 96),
                                      subdividedBox({-0.7f, -0.45f, -0.9f}, {0.8f, 0.65f, 0.55f}, 7)};
    const std::vector<Tracer> tracers = {{"gl grid (fused kernel)", Backend::Gl, "grid", TraceKernel::Fused},
                                         {"gl grid (split kernels)", Backend::Gl, "grid", TraceKernel::Split},
                                         {"gl bvh", Backend::Gl, "bvh"},
                                         {"cpu grid", Backend::Cpu, "grid"},
                                         {"cpu bvh", Backend::Cpu, "bvh"}};
    for (const Mesh& m : meshes) {
        Scene scene;
        const uint32_t material = addMaterial(scene, glm::vec3(0.8f));
        for (const glm::ivec3& t : m.triangles) {
            scene.triangles.push_back({m.vertices[size_t(t.x)], m.vertices[size_t(t.y)], m.vertices[size_t(t.z)]});
            scene.materialIds.push_back(material);
        }
        const std::vector<Target> ts = targets(m);
        Rays outside = outsideRays(m, ts), inside = insideRays(m, ts);
        ASSERT_GT(outside.distance.size(), 2 * ts.size()) << m.name;
        ASSERT_GT(inside.distance.size(), ts.size() * 9 / 10) << m.name;
        layOut(outside);
        layOut(inside);
        const Rays shadow = shadowRays(outside);
        const CameraBasis camera = makeCamera(defaultCamera(scene.bounds(), 64, 64), 64, 64);
        for (const Tracer& how : tracers) {
            const Acceleration accel = chooseAcceleration(scene, how.accel, nullptr, {}, camera);
            const struct {
                const char* what;
                const Rays& rays;
                bool anyHit;
            } checks[] = {{"closest hit from outside", outside, false},
                          {"closest hit from inside", inside, false},
                          {"any hit (shadow rays ending past the point)", shadow, true}};
            for (const auto& c : checks) {
                std::string examples;
                const size_t bad = failures(c.rays, trace(scene, accel, how, c.rays, c.anyHit), c.anyHit, examples);
                EXPECT_EQ(bad, 0u) << m.name << ", " << how.name << ", " << c.what << ": " << bad << " of "
                                   << c.rays.distance.size() << " rays missed the aimed point\n"
                                   << examples;
            }
        }
    }
}

}  // namespace
}  // namespace gpurt::test
