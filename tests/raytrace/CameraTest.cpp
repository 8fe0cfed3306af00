// The camera against the contract's formulas evaluated independently in double precision, the
// default camera, and the option errors.
#include "raytrace/camera/Camera.h"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "image/InputError.h"

namespace gpurt {
namespace {

glm::dvec3 normalizeD(glm::dvec3 a) { return a / std::sqrt(glm::dot(a, a)); }

struct DoubleCamera {
    glm::dvec3 forward, right, upOrtho;
    double t, aspect;
    int width, height;

    DoubleCamera(const CameraSpec& s, int w, int h) : width(w), height(h) {
        forward = normalizeD(glm::dvec3(s.target) - glm::dvec3(s.eye));
        right = normalizeD(glm::cross(forward, glm::dvec3(s.up)));
        upOrtho = glm::cross(right, forward);
        t = std::tan(double(s.fovy) * std::numbers::pi / 360.0);
        aspect = double(w) / double(h);
    }
    glm::dvec3 direction(int i, int j) const {
        const double u = ((i + 0.5) / width * 2.0 - 1.0) * t * aspect;
        const double v = (1.0 - (j + 0.5) / height * 2.0) * t;
        return normalizeD(forward + u * right + v * upOrtho);
    }
};

void expectNear(glm::vec3 actual, glm::dvec3 expected, double tol, const std::string& what) {
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(actual[a], expected[a], tol) << what << " component " << a;
}

TEST(CameraTest, MatchesTheContractFormulaInDouble) {
    const CameraSpec specs[] = {
        {{0, 0, 3.43f}, {0, 0, 0}, {0, 1, 0}, 45.0f},
        {{278, 273, -800}, {278, 273, 0}, {0, 1, 0}, 39.3077f},
        {{2.5f, 1.7f, -3.1f}, {-0.2f, 0.4f, 0.9f}, {0.1f, 1.0f, 0.2f}, 70.0f},
        {{1, 2, 3}, {1, 2, -30}, {1, 0, 0}, 12.5f},
    };
    const glm::ivec2 sizes[] = {{256, 256}, {320, 200}, {7, 13}};
    for (const CameraSpec& spec : specs) {
        for (glm::ivec2 size : sizes) {
            const CameraBasis c = makeCamera(spec, size.x, size.y);
            const DoubleCamera ref(spec, size.x, size.y);
            EXPECT_EQ(c.tanHalf, static_cast<float>(ref.t));  // rounded from double, exactly
            EXPECT_EQ(c.aspect, float(size.x) / float(size.y));
            EXPECT_EQ(c.eye, spec.eye);
            expectNear(c.forward, ref.forward, 1e-6, "forward");
            expectNear(c.right, ref.right, 1e-6, "right");
            expectNear(c.upOrtho, ref.upOrtho, 1e-6, "upOrtho");
            for (glm::ivec2 p :
                 {glm::ivec2(0, 0), glm::ivec2(size.x - 1, 0), glm::ivec2(0, size.y - 1),
                  glm::ivec2(size.x - 1, size.y - 1), glm::ivec2(size.x / 2, size.y / 3)}) {
                const glm::vec3 d = primaryDirection(c, p.x, p.y);
                expectNear(d, ref.direction(p.x, p.y), 2e-6, "direction");
                EXPECT_NEAR(glm::dot(d, d), 1.0f, 1e-6f);
            }
        }
    }
}

TEST(CameraTest, RowZeroIsTheTopAndColumnZeroTheLeft) {
    const CameraBasis c = makeCamera({{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60.0f}, 64, 32);
    const glm::vec3 topLeft = primaryDirection(c, 0, 0);
    EXPECT_GT(topLeft.y, 0.0f);
    EXPECT_LT(topLeft.x, 0.0f);
    const glm::vec3 bottomRight = primaryDirection(c, 63, 31);
    EXPECT_LT(bottomRight.y, 0.0f);
    EXPECT_GT(bottomRight.x, 0.0f);
    // The top edge of the image is fovy/2 above the axis: the top row's centre is just below it.
    const double angle =
        std::atan2(double(primaryDirection(c, 32, 0).y), -double(primaryDirection(c, 32, 0).z));
    EXPECT_LT(angle, 30.0 * std::numbers::pi / 180.0);
    EXPECT_GT(angle, 29.0 * std::numbers::pi / 180.0);
}

TEST(CameraTest, DefaultCameraFitsTheBoxFrontFace) {
    Bounds b;
    b.extend({-1, 2, -3});
    b.extend({5, 4, 1});
    for (glm::ivec2 size : {glm::ivec2(512, 512), glm::ivec2(800, 200), glm::ivec2(100, 400)}) {
        const CameraSpec spec = defaultCamera(b, size.x, size.y);
        const double t = std::tan(45.0 * std::numbers::pi / 360.0);
        const double aspect = double(size.x) / double(size.y);
        const double dist = 1.1 * std::max(1.0 / t, 3.0 / (t * aspect)) + 2.0;  // h = (3, 1, 2)
        EXPECT_NEAR(spec.eye.x, 2.0, 1e-6);
        EXPECT_NEAR(spec.eye.y, 3.0, 1e-6);
        EXPECT_NEAR(spec.eye.z, -1.0 + dist, 1e-5);
        EXPECT_EQ(spec.target, glm::vec3(2, 3, -1));
        EXPECT_EQ(spec.up, glm::vec3(0, 1, 0));
        EXPECT_EQ(spec.fovy, 45.0f);
        EXPECT_NO_THROW(makeCamera(spec, size.x, size.y));
    }
    // Nothing to fit: still a valid camera.
    EXPECT_NO_THROW(makeCamera(defaultCamera(Bounds{}, 64, 64), 64, 64));
    Bounds point;
    point.extend({1, 1, 1});
    EXPECT_NO_THROW(makeCamera(defaultCamera(point, 64, 64), 64, 64));
    // A speck: extents of a denormal, which float cannot add to z = 1 (fuzz_gltf found it).
    Bounds speck;
    speck.extend({0, 0, 1});
    speck.extend({1.5e-39f, 1.7e-41f, 1});
    EXPECT_NO_THROW(makeCamera(defaultCamera(speck, 64, 64), 64, 64));
    Bounds far;  // one unit is below float's step at 1e30
    far.extend({0, 0, 1e30f});
    EXPECT_NO_THROW(makeCamera(defaultCamera(far, 64, 64), 64, 64));
}

void expectOptionError(const CameraSpec& spec, int w, int h, const std::string& option) {
    try {
        makeCamera(spec, w, h);
        ADD_FAILURE() << "no error, expected one for " << option;
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(option + ": ", 0), 0u) << e.what();
    }
}

TEST(CameraTest, RejectsBadParameters) {
    const CameraSpec good{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.0f};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (float fovy : {0.0f, 180.0f, -10.0f, 200.0f, nan, inf}) {
        CameraSpec s = good;
        s.fovy = fovy;
        expectOptionError(s, 64, 64, "--fovy");
    }
    CameraSpec same = good;
    same.target = same.eye;
    expectOptionError(same, 64, 64, "--target");
    CameraSpec parallel = good;
    parallel.up = {0, 0, -2};
    expectOptionError(parallel, 64, 64, "--up");
    CameraSpec zeroUp = good;
    zeroUp.up = {0, 0, 0};
    expectOptionError(zeroUp, 64, 64, "--up");
    CameraSpec badEye = good;
    badEye.eye.x = nan;
    expectOptionError(badEye, 64, 64, "--eye");
    CameraSpec badTarget = good;
    badTarget.target.y = inf;
    expectOptionError(badTarget, 64, 64, "--target");
    expectOptionError(good, 0, 64, "--size");
    expectOptionError(good, 64, -1, "--size");
    CameraSpec overflow = good;  // target - eye is not a float
    overflow.eye = {0, 0, 3e38f};
    overflow.target = {0, 0, -3e38f};
    expectOptionError(overflow, 64, 64, "--target");
}

// Where dot(view, view) over- or underflows, the frame is still the one the contract means: the
// same as for the same direction at unit length (exactly, as scaling by 2^k is exact).
TEST(CameraTest, FarAndNearTargetsGiveTheUnitFrame) {
    const CameraSpec unit{{0, 0, 0}, {0.6f, -0.8f, -1.5f}, {0, 1, 0}, 45.0f};
    const CameraBasis reference = makeCamera(unit, 32, 24);
    for (int exponent : {-120, -80, 70, 120}) {
        SCOPED_TRACE(exponent);
        CameraSpec scaled = unit;
        scaled.target =
            glm::vec3(std::ldexp(unit.target.x, exponent), std::ldexp(unit.target.y, exponent),
                      std::ldexp(unit.target.z, exponent));
        const CameraBasis c = makeCamera(scaled, 32, 24);
        EXPECT_EQ(c.forward, reference.forward);
        EXPECT_EQ(c.right, reference.right);
        EXPECT_EQ(c.upOrtho, reference.upOrtho);
    }
    // A huge up vector and a tiny one are directions like any other.
    for (float length : {0x1p100f, 0x1p-100f}) {
        CameraSpec up = unit;
        up.up = glm::vec3(0, length, 0);
        EXPECT_EQ(makeCamera(up, 32, 24).right, reference.right) << length;
    }
}

// --fstop N as Cycles: a 36 mm sensor across the larger side, f the focal length that gives the
// field of view across it, the lens radius f / (2 N). A 50 mm lens on a 36 mm sensor sees
// 2 atan(18 / 50) across it: at f/2 its radius is 12.5 mm, whichever side is the larger.
TEST(CameraTest, AnFStopIsTheRadiusOfA36MillimetreSensorsLens) {
    const double across = 2.0 * std::atan(18.0 / 50.0) * 180.0 / std::numbers::pi;
    CameraSpec spec{{0, 0, 0}, {0, 0, -3}, {0, 1, 0}, float(across)};
    spec.fstop = 2.0f;
    EXPECT_NEAR(makeCamera(spec, 64, 64).lensRadius, 0.0125, 1e-6) << "square";
    EXPECT_NEAR(makeCamera(spec, 48, 64).lensRadius, 0.0125, 1e-6) << "portrait: the height is the larger side";
    // Landscape 2:1: fovy covers the smaller side, the sensor's 36 mm the width, twice as wide.
    const double tanAcross = 2.0 * std::tan(across * std::numbers::pi / 360.0);
    EXPECT_NEAR(makeCamera(spec, 128, 64).lensRadius, 0.018 / tanAcross / 4.0, 1e-6) << "landscape";
    // In a scene whose metre is 2^-3 units (rescaled), the same lens in scene units.
    spec.metre = 0.125f;
    EXPECT_NEAR(makeCamera(spec, 64, 64).lensRadius, 0.0125 / 8.0, 1e-7);
    // The focus distance defaults to the target's; none of it without a lens.
    EXPECT_FLOAT_EQ(makeCamera(spec, 64, 64).focusDistance, 3.0f);
    spec.fstop = 0.0f;
    EXPECT_EQ(makeCamera(spec, 64, 64).lensRadius, 0.0f);
}

TEST(CameraTest, ALensTheContractDoesNotKnowIsRefusedNamingTheOption) {
    const CameraSpec base{{0, 0, 0}, {0, 0, -3}, {0, 1, 0}, 45.0f};
    CameraSpec s = base;
    s.lensRadius = -0.1f;
    expectOptionError(s, 64, 64, "--lens-radius");
    s = base;
    s.fstop = -2.0f;
    expectOptionError(s, 64, 64, "--fstop");
    for (int blades : {1, 2, -3, 65}) {
        s = base;
        s.lensRadius = 0.1f;
        s.blades = blades;
        expectOptionError(s, 64, 64, "--blades");
    }
    s = base;
    s.focusDistance = -1.0f;
    expectOptionError(s, 64, 64, "--focus-distance");
}

}  // namespace
}  // namespace gpurt
