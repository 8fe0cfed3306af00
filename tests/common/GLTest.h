// A fixture for tests that need a GL context: one headless context per test process (ctest runs
// each test in its own process), EGL unless a test asks otherwise.
#pragma once

#include "stream/GLContext.h"
#include "stream/KernelStats.h"
#include "stream/ShaderLibrary.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

namespace gpurt::test {

class GLTest : public ::testing::Test {
  protected:
    // A fresh context per suite: other tests may have made and destroyed contexts of their own.
    static void SetUpTestSuite() {
        context().reset();
        context() = std::make_unique<GLContext>(GLBackend::Egl);
    }
    static void TearDownTestSuite() { context().reset(); }
    void SetUp() override {
        ShaderLibrary::global().setDirectory({});
        KernelStats::global().reset();
    }
    void TearDown() override { ShaderLibrary::global().setDirectory({}); }
    static std::unique_ptr<GLContext>& context() {
        static std::unique_ptr<GLContext> c;
        return c;
    }
};

// n uniform random floats in [lo, hi) from a fixed seed.
inline std::vector<float> randomFloats(size_t n, float lo, float hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    std::vector<float> v(n);
    for (float& x : v) x = dist(rng);
    return v;
}

}  // namespace gpurt::test
