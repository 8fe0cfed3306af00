// Kernel chains (Christen 2005, 4.3): sequence, for, while over one kernel, while over several
// kernels, nested while. Each ends with the state and call counts of a CPU simulation of the same
// float operations on the same random inputs.
#include "../common/GLTest.h"

#include "stream/GPUKernel.h"
#include "stream/KernelChain.h"
#include "stream/StreamErrors.h"

#include <algorithm>

namespace gpurt::test {
namespace {

class KernelChain : public GLTest {};

TEST_F(KernelChain, Sequence) {
    const int w = 24, h = 12;
    const auto start = randomFloats(size_t(w * h), -1.0f, 1.0f, 21);
    GPUFloatArray a(w, h, 1, "a"), b(w, h, 1, "b"), c(w, h, 1, "c");
    a.upload(start);
    GPUKernel first("scaleA", "test/affine.frag"), second("scaleB", "test/affine.frag");
    first.addInput(a, "values").addOutput(b).setUniform("scale", 3.0f).setUniform("offset", 0.5f);
    second.addInput(b, "values").addOutput(c).setUniform("scale", -0.25f).setUniform("offset", 2.0f);
    const auto counts = sequence({&first, &second});
    ASSERT_EQ(counts.size(), 2u);
    EXPECT_EQ(counts[0], uint64_t(w * h));
    EXPECT_EQ(counts[1], uint64_t(w * h));
    const auto out = c.download();
    for (size_t i = 0; i < start.size(); ++i) {
        const float mid = start[i] * 3.0f + 0.5f;
        ASSERT_EQ(out[i], mid * -0.25f + 2.0f);
    }
    EXPECT_EQ(KernelStats::global().passes().at("scaleA").calls, 1u);
    EXPECT_EQ(KernelStats::global().passes().at("scaleB").calls, 1u);
}

TEST_F(KernelChain, ForLoop) {
    const int w = 16, h = 9, n = 13;
    const auto start = randomFloats(size_t(w * h), -1.0f, 1.0f, 22);
    GPUPingPongArray values(w, h, 1, "values");
    values.front().upload(start);
    GPUKernel step("affine", "test/affine.frag");
    step.addInput(values, "values").addOutput(values).setPreserveUnwritten(false);
    forLoop(n, [&](int i) {
        step.setUniform("scale", 0.5f + 0.125f * float(i)).setUniform("offset", float(i));
        step.dispatch();
    });
    std::vector<float> expected = start;
    for (int i = 0; i < n; ++i)
        for (float& v : expected) v = v * (0.5f + 0.125f * float(i)) + float(i);
    EXPECT_EQ(values.front().download(), expected);
    EXPECT_EQ(step.calls(), n);
}

TEST_F(KernelChain, WhileLoop) {
    // While over one kernel: the seed's add-0.01-until-1 loop, ended by its own count.
    const int w = 20, h = 20;
    const auto start = randomFloats(size_t(w * h), 0.2f, 1.1f, 23);
    std::vector<float> rgba(size_t(w * h) * 4, 0.0f);
    for (size_t i = 0; i < start.size(); ++i) rgba[i * 4] = start[i];
    GPUFloatArray values(w, h, 4, "values");
    values.upload(rgba);
    GPUKernel add("addStep", "test/add_step.frag");
    add.addInOut(values, "values");
    int most = 0;
    std::vector<float> expected;
    for (float v : start) {
        int n = 0;
        for (; v < 1.0f; ++n) v = v + 0.01f;
        most = std::max(most, n);
        expected.push_back(v);
    }
    const int calls = whileLoop("addStep", 1000, [&] { return add.execute(); });
    EXPECT_EQ(calls, most + 1);
    const auto out = values.download();
    for (size_t i = 0; i < start.size(); ++i) ASSERT_EQ(out[i * 4], expected[i]);
}

TEST_F(KernelChain, WhileMulti) {
    // While over two kernels: decay multiplies values above the limit, countAbove's count of
    // values still above it ends the loop (decay's count is never read).
    const int w = 32, h = 16;
    const float limit = 0.05f, factor = 0.75f;
    const auto start = randomFloats(size_t(w * h), 0.0f, 10.0f, 24);
    GPUFloatArray values(w, h, 1, "values"), flags(w, h, 1, "flags");
    values.upload(start);
    GPUKernel decay("decay", "test/decay.frag");
    decay.addInOut(values, "values").setUniform("limit", limit).setUniform("factor", factor);
    GPUKernel count("countAbove", "test/count_above.frag");
    count.addInput(values, "values").addOutput(flags).setUniform("limit", limit);
    const int iterations = whileLoop("decay", 1000, {&decay, &count});

    std::vector<float> expected = start;
    int cpuIterations = 0;
    for (;;) {
        ++cpuIterations;
        for (float& v : expected)
            if (v > limit) v = v * factor;
        if (std::none_of(expected.begin(), expected.end(), [&](float v) { return v > limit; })) break;
    }
    EXPECT_EQ(iterations, cpuIterations);
    EXPECT_EQ(decay.calls(), cpuIterations);
    EXPECT_EQ(count.calls(), cpuIterations);
    EXPECT_EQ(values.download(), expected);
}

TEST_F(KernelChain, NestedWhile) {
    // Outer while: wrap subtracts 1 from the value and counts a round until each element has done
    // its target number of rounds; inner while: add 0.01 until the value reaches 1.
    const int w = 12, h = 10;
    const auto start = randomFloats(size_t(w * h), 0.0f, 1.0f, 25);
    const auto targetsF = randomFloats(size_t(w * h), 0.0f, 4.0f, 26);
    std::vector<float> rgba(size_t(w * h) * 4, 0.0f), targets(size_t(w * h));
    for (size_t i = 0; i < start.size(); ++i) {
        rgba[i * 4] = start[i];
        targets[i] = std::floor(targetsF[i]);
    }
    GPUFloatArray values(w, h, 4, "values"), targetStream(w, h, 1, "targets");
    values.upload(rgba);
    targetStream.upload(targets);
    GPUKernel add("addStep", "test/add_step.frag");
    add.addInOut(values, "values");
    GPUKernel wrap("wrap", "test/wrap.frag");
    wrap.addInOut(values, "values").addInput(targetStream, "targets");
    std::vector<int> innerCalls;
    const int outer = whileLoop("rounds", 100, [&] {
        innerCalls.push_back(add.loop(1000));
        return wrap.execute();
    });

    // CPU simulation of the same loops.
    std::vector<float> x = start, rounds(start.size(), 0.0f);
    std::vector<int> cpuInner;
    int cpuOuter = 0;
    for (;;) {
        ++cpuOuter;
        int most = 0;
        for (float& v : x) {
            int n = 0;
            for (; v < 1.0f; ++n) v = v + 0.01f;
            most = std::max(most, n);
        }
        cpuInner.push_back(most + 1);
        uint64_t wrapped = 0;
        for (size_t i = 0; i < x.size(); ++i)
            if (rounds[i] < targets[i]) {
                x[i] = x[i] - 1.0f;
                rounds[i] = rounds[i] + 1.0f;
                ++wrapped;
            }
        if (wrapped == 0) break;
    }
    EXPECT_EQ(outer, cpuOuter);
    EXPECT_EQ(innerCalls, cpuInner);
    const auto out = values.download();
    for (size_t i = 0; i < x.size(); ++i) {
        ASSERT_EQ(out[i * 4], x[i]) << i;
        ASSERT_EQ(out[i * 4 + 1], rounds[i]) << i;
    }
}

TEST_F(KernelChain, WhileLoopPastItsLimitFailsCleanly) {
    GPUFloatArray values(4, 4, 1, "values"), flags(4, 4, 1, "flags");
    values.fill(1000.0f);
    GPUKernel decay("decay", "test/decay.frag");
    decay.addInOut(values, "values").setUniform("limit", 0.0f).setUniform("factor", 0.999f);
    GPUKernel count("countAbove", "test/count_above.frag");
    count.addInput(values, "values").addOutput(flags).setUniform("limit", 0.0f);
    EXPECT_THROW(whileLoop("forever", 7, {&decay, &count}), LoopLimitError);
    EXPECT_EQ(decay.calls(), 7);
}

}  // namespace
}  // namespace gpurt::test
