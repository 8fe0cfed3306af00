// The thin lens (CONTRACT.md, depth of field) against closed forms, on both backends. A small
// emitting sphere at distance d seen through a lens of radius R focused at F: every pixel whose
// focus point sees it through some part of the lens is lit, by the fraction of the lens that sees
// it. The image is the emitter's sharp image spread over the circle of confusion, a disc of radius
// r = R |d - F| / d on the focus plane, so that (the flux being the same as the sharp image's)
// the sum of the pixels over the level inside the disc is its area, pi r^2; on the focus plane
// (d = F) every lens point sees what the pinhole sees. A 6-blade aperture makes a hexagon whose
// corners point as the blade rotation says (the phase of the image's 6-fold angular moment).
#include "../common/GLTest.h"
#include "TestScenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace gpurt {
namespace {

using test::addIcosphere;
using test::addMaterial;

constexpr int kSize = 128;
constexpr float kFocus = 4.0f;   // the target's distance: the default focus distance
constexpr float kRadius = 0.1f;  // the lens radius
constexpr float kFovy = 3.0f;    // the focus plane is 2 F t wide: about 5 pixels to a millimetre
constexpr float kEmitter = 0.02f;

class Lens : public test::GLTest {};

// The camera at the origin looking down -z; the emitting sphere of radius `size` at distance d.
test::Both renderEmitter(float d, float size, CameraSpec spec, uint32_t samples) {
    Scene scene;
    scene.background = glm::vec3(0.0f);
    addIcosphere(scene, {0.0f, 0.0f, -d}, size, 3, addMaterial(scene, glm::vec3(0.0f), glm::vec3(1.0f)));
    return test::renderBoth(scene, spec, kSize, kSize, samples);
}

CameraSpec lensCamera(float radius, int blades = 0, float rotation = 0.0f) {
    CameraSpec spec{{0, 0, 0}, {0, 0, -kFocus}, {0, 1, 0}, kFovy};
    spec.lensRadius = radius;
    spec.blades = blades;
    spec.bladeRotation = rotation;
    return spec;
}

// Pixels per scene unit on the focus plane (the camera convention: the image is 2 F t high).
double pixelsPerUnit() { return kSize / (2.0 * kFocus * std::tan(double(kFovy) * std::numbers::pi / 360.0)); }

struct Blur {
    double sum = 0.0, level = 0.0, levelPixels = 0.0;
    std::complex<double> moment6{0.0}, moment0{0.0};  // the 6-fold angular moment and its norm
};

// The image's sum, its mean level within `inner` pixels of the centre, and its angular moments
// (angles counter-clockwise from the right, as the blade rotation's).
Blur measure(const RenderOutput& out, double inner) {
    Blur b;
    const double c = kSize / 2.0;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const double v = out.color[size_t(j) * kSize + size_t(i)].x;
            const double x = i + 0.5 - c, y = c - (j + 0.5);
            const double rho = std::hypot(x, y);
            b.sum += v;
            if (rho < inner) {
                b.level += v;
                b.levelPixels += 1.0;
            }
            const double w = v * std::pow(rho, 6.0);
            b.moment6 += w * std::polar(1.0, -6.0 * std::atan2(y, x));
            b.moment0 += w;
        }
    b.level /= b.levelPixels;
    return b;
}

TEST_F(Lens, APointOffTheFocusPlaneMakesADiscOfTheCircleOfConfusion) {
    constexpr uint32_t kSamples = 128;
    for (const float d : {8.0f, 2.5f}) {
        const double r = kRadius * std::abs(d - kFocus) / d * pixelsPerUnit();  // in pixels
        const test::Both both = renderEmitter(d, kEmitter, lensCamera(kRadius), kSamples);
        // The lit fraction of the lens inside the disc: the emitter's disc over the lens's; a
        // sample is 0 or 1, so the level's and the sum's relative errors follow from it.
        const double fraction = std::pow(kEmitter / (kRadius * std::abs(1.0 - d / kFocus)), 2.0);
        const double inner = r / 3.0;
        const double levelError = std::sqrt((1.0 - fraction) / (fraction * kSamples * std::numbers::pi * inner * inner));
        const double sumError = std::sqrt((1.0 - fraction) / (fraction * kSamples * std::numbers::pi * r * r));
        for (const RenderOutput* out : {&both.gl, &both.cpu}) {
            SCOPED_TRACE(std::string(out == &both.gl ? "gl" : "cpu") + ", d = " + std::to_string(d));
            const Blur b = measure(*out, inner);
            // (The faceted sphere's outline is an inscribed polygon: 0.3% less area.)
            EXPECT_NEAR(b.level, fraction, (4.0 * levelError + 0.01) * fraction);
            const double measured = std::sqrt(b.sum / (b.level * std::numbers::pi));
            // Half the relative error of the ratio; a pixel's width for the edge's pixels.
            EXPECT_NEAR(measured, r, r * 2.0 * (levelError + sumError) + 0.5) << "r = " << r;
        }
    }
}

TEST_F(Lens, APointOnTheFocusPlaneStaysAsSharpAsThePinholeSeesIt) {
    // An emitter of a third of a pixel on the focus plane: lit pixels only where its own jittered
    // footprint falls, the same samples as the pinhole camera's.
    const float size = float(0.33 / pixelsPerUnit());
    const test::Both lens = renderEmitter(kFocus, size, lensCamera(kRadius), 64);
    const test::Both pinhole = renderEmitter(kFocus, size, lensCamera(0.0f), 64);
    for (const auto& [out, sharp] : {std::pair{&lens.gl, &pinhole.gl}, std::pair{&lens.cpu, &pinhole.cpu}}) {
        SCOPED_TRACE(out == &lens.gl ? "gl" : "cpu");
        int lit = 0;
        double difference = 0.0, sum = 0.0;
        for (size_t p = 0; p < out->color.size(); ++p) {
            lit += out->color[p].x > 0.0f;
            difference += std::abs(out->color[p].x - sharp->color[p].x);
            sum += sharp->color[p].x;
        }
        EXPECT_GE(lit, 1);
        EXPECT_LE(lit, 4);  // a footprint under a pixel wide covers at most 2 x 2 pixels
        EXPECT_GT(sum, 0.0);
        EXPECT_LE(difference, 0.02 * sum);  // rounding at the footprint's edge only
    }
}

TEST_F(Lens, SixBladesMakeAHexagonTurnedByTheBladeRotation) {
    constexpr float kRotation = 20.0f;  // degrees: the corners at 20 + 60 k
    const test::Both hexagon = renderEmitter(8.0f, 0.01f, lensCamera(kRadius, 6, kRotation), 128);
    const test::Both disc = renderEmitter(8.0f, 0.01f, lensCamera(kRadius), 128);
    for (const auto& [hex, round] : {std::pair{&hexagon.gl, &disc.gl}, std::pair{&hexagon.cpu, &disc.cpu}}) {
        SCOPED_TRACE(hex == &hexagon.gl ? "gl" : "cpu");
        const Blur h = measure(*hex, 5.0), c = measure(*round, 5.0);
        const double strength = std::abs(h.moment6) / h.moment0.real();
        // A regular hexagon's 6-fold moment points at its corners: phase 6 x the rotation.
        const double angle = std::arg(h.moment6 * std::polar(1.0, 6.0 * double(kRotation) * std::numbers::pi / 180.0));
        EXPECT_NEAR(angle / 6.0 * 180.0 / std::numbers::pi, 0.0, 2.0) << "degrees off the blade rotation";
        EXPECT_GT(strength, 5.0 * std::abs(c.moment6) / c.moment0.real()) << "the disc's 6-fold moment is noise";
    }
}

}  // namespace
}  // namespace gpurt
