// Vertex colours (Scene::colors, PLY red/green/blue, glTF COLOR_0) on both backends and both
// integrators: a PLY triangle facing the camera with three corner colours. The expected colour of
// a pixel comes from the camera ray through its centre, intersected with the triangle here in
// double (the contract's camera, written out), its barycentrics interpolating the corners' colours
// after the sRGB decoding of their bytes (IEC 61966-2-1, written out). Under a uniform sky of
// radiance 1 the path integrator shows a diffuse convex object's albedo exactly (PathGLTest), here
// kd times the colour; Whitted's picture is linear in kd (no specular), so it is the picture of the
// same triangle without colours times the colour.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "scene/PlyLoader.h"

#include <cmath>
#include <string>

namespace gpurt::test {
namespace {

class VertexColors : public GLTest {};

constexpr int kSize = 48;
const int kBytes[3][3] = {{255, 20, 0}, {0, 200, 60}, {90, 40, 250}};  // red, green, blue of the corners

// A triangle in the plane z = 0 with colours kBytes at its corners (uchar, sRGB-encoded).
std::string colouredTrianglePly() {
    std::string s = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n";
    const char* corners[3] = {"-1.2 -1 0", "1.3 -0.9 0", "0.1 1.2 0"};
    for (int v = 0; v < 3; ++v)
        s += std::string(corners[v]) + " " + std::to_string(kBytes[v][0]) + " " + std::to_string(kBytes[v][1]) + " " +
             std::to_string(kBytes[v][2]) + "\n";
    return s + "3 0 1 2\n";
}

double srgbToLinear(int byte) {
    const double c = byte / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

CameraSpec camera() {
    CameraSpec spec;
    spec.eye = {0.1f, 0.05f, 3.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 50.0f;
    return spec;
}

// The colour at the hit of pixel (i, j)'s centre ray, or false when the ray misses the triangle
// or passes within `margin` (in barycentrics) of its edges.
bool expectedColour(const Triangle& t, int i, int j, double margin, glm::dvec3& colour) {
    const CameraSpec spec = camera();
    const glm::dvec3 eye(spec.eye), forward = glm::normalize(glm::dvec3(spec.target) - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(spec.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tanHalf = std::tan(double(spec.fovy) * 3.14159265358979323846 / 360.0);
    const double u = ((i + 0.5) / kSize * 2.0 - 1.0) * tanHalf, v = (1.0 - (j + 0.5) / kSize * 2.0) * tanHalf;
    const glm::dvec3 d = forward + u * right + v * up;
    const glm::dvec3 p = eye + (-eye.z / d.z) * d;  // on z = 0
    // Barycentrics of p in the triangle's plane (2D: the plane is z = 0).
    const glm::dvec2 a(t.v0), b(t.v1), c(t.v2), q(p);
    const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    const double wb = ((q.x - a.x) * (c.y - a.y) - (c.x - a.x) * (q.y - a.y)) / area;
    const double wc = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / area;
    const double wa = 1.0 - wb - wc;
    if (wa < margin || wb < margin || wc < margin) return false;
    for (int k = 0; k < 3; ++k)
        colour[k] = wa * srgbToLinear(kBytes[0][k]) + wb * srgbToLinear(kBytes[1][k]) + wc * srgbToLinear(kBytes[2][k]);
    return true;
}

TEST_F(VertexColors, PlyCornerColoursAreInterpolatedOnBothBackendsAndIntegrators) {
    Scene coloured = parsePly(colouredTrianglePly(), "corners.ply");
    ASSERT_EQ(coloured.colors.size(), 1u);
    const glm::vec3 kd(0.9f, 0.7f, 0.8f);
    coloured.materials[0].diffuse = kd;
    Scene plain = coloured;
    plain.colors.clear();

    for (Integrator integrator : {Integrator::Path, Integrator::Whitted}) {
        const bool path = integrator == Integrator::Path;
        SCOPED_TRACE(path ? "path" : "whitted");
        Scene c = coloured, p = plain;
        if (path) c.background = p.background = glm::vec3(1.0f);  // a uniform sky, the only light
        const Both withColours = renderBoth(c, camera(), kSize, kSize, 1, 3, integrator);
        const Both without = renderBoth(p, camera(), kSize, kSize, 1, 3, integrator);
        expectSamePictures(withColours.gl, withColours.cpu, "coloured");
        size_t checked = 0;
        for (int j = 0; j < kSize; ++j)
            for (int i = 0; i < kSize; ++i) {
                glm::dvec3 colour;
                if (!expectedColour(c.triangles[0], i, j, 0.02, colour)) continue;
                const size_t at = size_t(j) * kSize + size_t(i);
                for (const RenderOutput* out : {&withColours.gl, &withColours.cpu}) {
                    const RenderOutput& base = out == &withColours.gl ? without.gl : without.cpu;
                    ASSERT_GE(out->prim[at], 0.0f) << i << ", " << j;
                    for (int k = 0; k < 3; ++k) {
                        const double expected = path ? double(kd[k]) * colour[k] : double(base.color[at][k]) * colour[k];
                        ASSERT_NEAR(out->color[at][k], expected, 1e-4 + 1e-4 * expected)
                            << (out == &withColours.gl ? "gl" : "cpu") << " pixel " << i << ", " << j << " channel " << k;
                    }
                }
                ++checked;
            }
        EXPECT_GT(checked, 300u);
    }
}

// Triangles without colours in a scene that has some are white: the same picture as without any.
TEST_F(VertexColors, WhiteColoursChangeNothing) {
    Scene plain = parsePly(colouredTrianglePly(), "corners.ply");
    plain.colors.clear();
    Scene white = plain;
    white.colors.assign(plain.triangles.size(), TriangleColors{});
    const Both a = renderBoth(plain, camera(), kSize, kSize, 1);
    const Both b = renderBoth(white, camera(), kSize, kSize, 1);
    EXPECT_EQ(a.gl.color, b.gl.color);
    EXPECT_EQ(a.cpu.color, b.cpu.color);
}

}  // namespace
}  // namespace gpurt::test
