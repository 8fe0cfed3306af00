// Masking: each mode leaves masked elements untouched and counts exactly the active ones, for
// scattered and block-coherent masks, with plain, ping-pong and in-place outputs.
#include "../common/GLTest.h"

#include "stream/GPUKernel.h"
#include "stream/GPUMask.h"

namespace gpurt::test {
namespace {

class Masking : public GLTest, public ::testing::WithParamInterface<MaskMode> {};

// States 0..3; the mask selects state 2 (or [lo, hi]).
std::vector<float> randomStates(int w, int h, unsigned seed, bool blocky) {
    std::mt19937 rng(seed);
    std::vector<float> s(size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const unsigned key = blocky ? unsigned((x / 8) * 131 + (y / 4) * 71) : unsigned(rng());
            s[size_t(y * w + x)] = float((key * 2654435761u >> 7) % 4u);
        }
    return s;
}

void checkMasked(const std::vector<float>& values, const std::vector<float>& states,
                 const std::vector<float>& out, float lo, float hi) {
    for (size_t i = 0; i < values.size(); ++i) {
        const bool active = states[i] >= lo && states[i] <= hi;
        ASSERT_EQ(out[i], active ? values[i] + 1.0f : values[i]) << "element " << i;
    }
}

uint64_t countActive(const std::vector<float>& states, float lo, float hi) {
    uint64_t n = 0;
    for (float s : states) n += (s >= lo && s <= hi) ? 1 : 0;
    return n;
}

TEST_P(Masking, LeavesMaskedElementsUntouchedAndCountsExactly) {
    const int w = 53, h = 29;
    for (bool blocky : {false, true}) {
        const auto states = randomStates(w, h, 31, blocky);
        const auto values = randomFloats(size_t(w * h), -5.0f, 5.0f, 32);
        GPUFloatArray stateStream(w, h, 1, "state"), input(w, h, 1, "in"), output(w, h, 1, "out");
        stateStream.upload(states);
        input.upload(values);
        output.upload(values);
        GPUMask mask("state2", GetParam(), stateStream, 0, 2.0f, 2.0f);
        GPUKernel kernel("increment", "test/increment.frag");
        kernel.addInput(input, "values").addOutput(output).setMask(&mask);
        EXPECT_EQ(kernel.execute(), countActive(states, 2.0f, 2.0f));
        checkMasked(values, states, output.download(), 2.0f, 2.0f);

        // A range of states, and a changed state stream: the mask follows.
        mask.setRange(1.0f, 2.0f);
        output.upload(values);
        EXPECT_EQ(kernel.execute(), countActive(states, 1.0f, 2.0f));
        checkMasked(values, states, output.download(), 1.0f, 2.0f);
    }
}

TEST_P(Masking, InPlaceLoopUnderMask) {
    // Channel 0 of a 4-channel stream is the state; only state-3 elements run add_step.
    const int w = 24, h = 16;
    const auto states = randomStates(w, h, 33, false);
    const auto start = randomFloats(size_t(w * h), 0.0f, 1.0f, 34);
    std::vector<float> rgba(size_t(w * h) * 4, 0.0f);
    for (size_t i = 0; i < start.size(); ++i) rgba[i * 4] = start[i];
    GPUFloatArray stateStream(w, h, 1, "state"), values(w, h, 4, "values");
    stateStream.upload(states);
    values.upload(rgba);
    GPUMask mask("state3", GetParam(), stateStream, 0, 3.0f, 3.0f);
    GPUKernel add("addStep", "test/add_step.frag");
    add.addInOut(values, "values").setMask(&mask);
    int most = 0;
    std::vector<float> expected(start);
    for (size_t i = 0; i < start.size(); ++i) {
        if (states[i] != 3.0f) continue;
        int n = 0;
        for (; expected[i] < 1.0f; ++n) expected[i] = expected[i] + 0.01f;
        most = std::max(most, n);
    }
    EXPECT_EQ(add.loop(1000), most + 1);
    const auto out = values.download();
    for (size_t i = 0; i < start.size(); ++i) ASSERT_EQ(out[i * 4], expected[i]);
}

TEST_P(Masking, PingPongOutputUnderMask) {
    const int w = 19, h = 11;
    const auto states = randomStates(w, h, 35, false);
    const auto values = randomFloats(size_t(w * h), -1.0f, 1.0f, 36);
    GPUPingPongArray stream(w, h, 1, "values");
    GPUFloatArray stateStream(w, h, 1, "state");
    stateStream.upload(states);
    stream.front().upload(values);
    GPUMask mask("state0", GetParam(), stateStream, 0, 0.0f, 0.0f);
    GPUKernel kernel("increment", "test/increment.frag");
    kernel.addInput(stream, "values").addOutput(stream).setMask(&mask);
    EXPECT_EQ(kernel.execute(), countActive(states, 0.0f, 0.0f));
    checkMasked(values, states, stream.front().download(), 0.0f, 0.0f);
}

INSTANTIATE_TEST_SUITE_P(Modes, Masking,
                         ::testing::Values(MaskMode::EarlyZ, MaskMode::Stencil, MaskMode::EarlyExit),
                         [](const ::testing::TestParamInfo<MaskMode>& info) {
                             switch (info.param) {
                                 case MaskMode::EarlyZ: return std::string("EarlyZ");
                                 case MaskMode::Stencil: return std::string("Stencil");
                                 case MaskMode::EarlyExit: return std::string("EarlyExit");
                                 default: return std::string("None");
                             }
                         });

}  // namespace
}  // namespace gpurt::test
