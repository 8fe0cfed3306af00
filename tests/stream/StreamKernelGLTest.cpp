// GPUKernel: occlusion counts, outputs, MRT, ping-pong, in-place, sub-rectangles, primitives,
// integer streams, conditional rendering, statistics, loop limits, OSMesa.
#include "../common/GLTest.h"

#include "stream/GPUKernel.h"
#include "stream/StreamErrors.h"

#include <algorithm>

namespace gpurt::test {
namespace {

class StreamKernel : public GLTest {};

// CPU reference of test/threshold.frag.
uint64_t countAtOrAbove(const std::vector<float>& values, float threshold) {
    return uint64_t(std::count_if(values.begin(), values.end(), [&](float v) { return v >= threshold; }));
}

TEST_F(StreamKernel, ExecuteCountsFragmentsOfDiscardPatterns) {
    const int w = 61, h = 33;
    const auto values = randomFloats(size_t(w * h), 0.0f, 1.0f, 11);
    GPUFloatArray input(w, h, 1, "values"), output(w, h, 1, "result");
    input.upload(values);
    GPUKernel kernel("threshold", "test/threshold.frag");
    kernel.addInput(input, "values").addOutput(output);
    for (float threshold : {0.0f, 0.25f, 0.5f, 0.9f, 2.0f}) {
        output.fill(-7.0f);
        kernel.setUniform("threshold", threshold);
        EXPECT_EQ(kernel.execute(), countAtOrAbove(values, threshold)) << threshold;
        const auto out = output.download();
        for (size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(out[i], values[i] >= threshold ? 2.0f * values[i] : -7.0f) << i;
    }
}

TEST_F(StreamKernel, CheckerboardAndStripeDiscardsCountExactly) {
    // Patterns finer than llvmpipe's 4x2 blocks: counts must still be per element.
    const int w = 64, h = 16;
    std::vector<float> values(size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) values[size_t(y * w + x)] = ((x + y) % 2 == 0 || x % 7 == 3) ? 1.0f : 0.0f;
    GPUFloatArray input(w, h, 1), output(w, h, 1);
    input.upload(values);
    GPUKernel kernel("threshold", "test/threshold.frag");
    kernel.addInput(input, "values").addOutput(output).setUniform("threshold", 0.5f);
    EXPECT_EQ(kernel.execute(), countAtOrAbove(values, 0.5f));
}

TEST_F(StreamKernel, MultipleRenderTargets) {
    const int w = 20, h = 10;
    const auto a = randomFloats(size_t(w * h) * 4, -2.0f, 2.0f, 1);
    const auto b = randomFloats(size_t(w * h) * 4, -2.0f, 2.0f, 2);
    GPUFloatArray inA(w, h, 4), inB(w, h, 4), sum(w, h, 4), product(w, h, 1), pair(w, h, 2);
    inA.upload(a);
    inB.upload(b);
    GPUKernel kernel("mrt", "test/mrt.frag");
    kernel.addInput(inA, "a").addInput(inB, "b").addOutput(sum).addOutput(product).addOutput(pair);
    EXPECT_EQ(kernel.execute(), uint64_t(w * h));
    const auto s = sum.download(), p = product.download(), q = pair.download();
    for (size_t i = 0; i < size_t(w * h); ++i) {
        for (int c = 0; c < 4; ++c) ASSERT_EQ(s[i * 4 + c], a[i * 4 + c] + b[i * 4 + c]);
        ASSERT_EQ(p[i], a[i * 4] * b[i * 4]);
        ASSERT_EQ(q[i * 2], a[i * 4 + 1]);
        ASSERT_EQ(q[i * 2 + 1], b[i * 4 + 1]);
    }
}

TEST_F(StreamKernel, OutputsMustMatchAndAreLimitedToEight) {
    GPUFloatArray a(8, 8, 1), other(4, 8, 1);
    GPUKernel kernel("affine", "test/affine.frag");
    kernel.addOutput(a);
    EXPECT_THROW(kernel.addOutput(other), UsageError);
    std::vector<GPUFloatArray> many;
    for (int i = 0; i < 8; ++i) many.emplace_back(8, 8, 1);
    GPUKernel wide("affine", "test/affine.frag");
    for (int i = 0; i < 8; ++i) wide.addOutput(many[size_t(i)]);
    EXPECT_THROW(wide.addOutput(a), UsageError);
    GPUKernel feedback("affine", "test/affine.frag");
    feedback.addInput(a, "values");
    EXPECT_THROW(feedback.addOutput(a), UsageError);
}

// CPU reference of the seed's example: adds 0.01f until >= 1; the number of loop() calls is the
// largest number of additions any element needs, plus the final pass that writes nothing.
struct AddStepReference {
    std::vector<float> finals;
    int calls = 0;
};
AddStepReference addStepReference(const std::vector<float>& start) {
    AddStepReference ref;
    int most = 0;
    for (float v : start) {
        int n = 0;
        while (v < 1.0f) {
            v = v + 0.01f;
            ++n;
        }
        ref.finals.push_back(v);
        most = std::max(most, n);
    }
    ref.calls = most + 1;
    return ref;
}

std::vector<float> channel(const std::vector<float>& rgba, int c) {
    std::vector<float> out;
    for (size_t i = size_t(c); i < rgba.size(); i += 4) out.push_back(rgba[i]);
    return out;
}

TEST_F(StreamKernel, LoopOnTheSeedExampleWithPingPong) {
    const int w = 32, h = 24;
    const auto start = randomFloats(size_t(w * h), -0.5f, 1.2f, 3);
    std::vector<float> rgba(size_t(w * h) * 4, 0.0f);
    for (size_t i = 0; i < start.size(); ++i) rgba[i * 4] = start[i];
    GPUPingPongArray values(w, h, 4, "values");
    values.front().upload(rgba);
    GPUKernel add("addStep", "test/add_step.frag");
    add.addInput(values, "values").addOutput(values);
    const AddStepReference ref = addStepReference(start);
    EXPECT_EQ(add.loop(1000), ref.calls);
    EXPECT_EQ(channel(values.front().download(), 0), ref.finals);
}

TEST_F(StreamKernel, LoopInPlaceWithTextureBarrier) {
    const int w = 40, h = 8;
    const auto start = randomFloats(size_t(w * h), 0.0f, 1.0f, 4);
    std::vector<float> rgba(size_t(w * h) * 4, 0.0f);
    for (size_t i = 0; i < start.size(); ++i) rgba[i * 4] = start[i];
    GPUFloatArray values(w, h, 4, "values");
    values.upload(rgba);
    GPUKernel add("addStep", "test/add_step.frag");
    add.addInOut(values, "values");
    const AddStepReference ref = addStepReference(start);
    EXPECT_EQ(add.loop(1000), ref.calls);
    EXPECT_EQ(channel(values.download(), 0), ref.finals);
}

TEST_F(StreamKernel, PingPongKeepsElementsAPassDoesNotWrite) {
    const int w = 16, h = 16;
    const auto start = randomFloats(size_t(w * h), 0.0f, 1.0f, 5);
    GPUPingPongArray values(w, h, 1, "values");
    values.front().upload(start);
    values.back().fill(-100.0f);  // stale data that must never show through
    GPUKernel kernel("threshold", "test/threshold.frag");
    kernel.addInput(values, "values").addOutput(values).setUniform("threshold", 0.5f);
    kernel.execute();
    const auto out = values.front().download();
    for (size_t i = 0; i < start.size(); ++i)
        ASSERT_EQ(out[i], start[i] >= 0.5f ? 2.0f * start[i] : start[i]);
}

TEST_F(StreamKernel, LoopPastMaxCallsFailsCleanly) {
    GPUFloatArray values(8, 8, 4, "values");
    values.fill(0.0f);  // needs 100 additions of 0.01 to reach 1
    GPUKernel add("addStep", "test/add_step.frag");
    add.addInOut(values, "values");
    try {
        add.loop(10);
        FAIL() << "loop(10) should have thrown";
    } catch (const LoopLimitError& e) {
        EXPECT_NE(std::string(e.what()).find("addStep"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("10 calls"), std::string::npos) << e.what();
    }
    EXPECT_EQ(add.calls(), 10);
}

TEST_F(StreamKernel, SubRectangleWritesOnlyInside) {
    const int w = 30, h = 20;
    GPUFloatArray out(w, h, 2, "index");
    out.fill(-1.0f);
    GPUKernel kernel("coordinates", "test/coordinates.frag");
    kernel.addOutput(out).setRect(StreamRect{5, 3, 11, 7});
    EXPECT_EQ(kernel.execute(), uint64_t(11 * 7));
    const auto v = out.download();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool inside = x >= 5 && x < 16 && y >= 3 && y < 10;
            ASSERT_EQ(v[size_t(y * w + x) * 2], inside ? float(x) : -1.0f);
            ASSERT_EQ(v[size_t(y * w + x) * 2 + 1], inside ? float(y) : -1.0f);
        }
}

TEST_F(StreamKernel, TriangleAndQuadCoverEveryElementOnce) {
    for (StreamPrimitive primitive : {StreamPrimitive::Triangle, StreamPrimitive::Quad}) {
        const int w = 67, h = 45;
        GPUFloatArray out(w, h, 2, "index");
        GPUKernel kernel("coordinates", "test/coordinates.frag");
        kernel.addOutput(out).setPrimitive(primitive);
        EXPECT_EQ(kernel.execute(), uint64_t(w * h));
        const auto v = out.download();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                ASSERT_EQ(v[size_t(y * w + x) * 2], float(x));
                ASSERT_EQ(v[size_t(y * w + x) * 2 + 1], float(y));
            }
    }
}

TEST_F(StreamKernel, IntegerStreamsAreExact) {
    const int w = 9, h = 7;
    std::vector<uint32_t> words(size_t(w * h) * 4), indices(size_t(w * h) * 4);
    std::mt19937 rng(8);
    for (uint32_t& x : words) x = uint32_t(rng());
    for (size_t i = 0; i < size_t(w * h); ++i) {
        indices[i * 4] = uint32_t(rng() % unsigned(w));
        indices[i * 4 + 1] = uint32_t(rng() % unsigned(h));
    }
    GPUFloatArray in(w, h, GPUFormat::RGBA32UI), idx(w, h, GPUFormat::RGBA32UI), out(w, h, GPUFormat::RGBA32UI);
    in.upload(words);
    idx.upload(indices);
    const uint32_t salt = 0x9e3779b9u;
    GPUKernel kernel("uintMix", "test/uint_mix.frag");
    kernel.addInput(in, "words").addInput(idx, "indices").addOutput(out).setUniform("salt", unsigned(salt));
    kernel.execute();
    const auto r = out.downloadUint();
    for (size_t i = 0; i < size_t(w * h); ++i) {
        const size_t g = size_t(indices[i * 4 + 1] * unsigned(w) + indices[i * 4]);
        ASSERT_EQ(r[i * 4], words[i * 4] ^ salt);
        ASSERT_EQ(r[i * 4 + 1], words[i * 4 + 1] + words[g * 4]);
        ASSERT_EQ(r[i * 4 + 2], words[i * 4 + 2] * 3u);
        ASSERT_EQ(r[i * 4 + 3], words[g * 4 + 3]);
    }
}

// Kernels gather from buffer tables with 1D indices (element x + W * y) and never write them.
TEST_F(StreamKernel, BufferTablesAreGatheredIn1DAndNeverWritten) {
    const int tw = 300, th = 7, w = 11, h = 5;  // the table has more texels than a row holds
    const auto floats = randomFloats(size_t(tw * th) * 4, -1e3f, 1e3f, 31u);
    std::vector<uint32_t> words(size_t(tw * th) * 2);
    std::vector<int32_t> indices(size_t(w * h) * 4, 0);
    std::mt19937 rng(5);
    for (uint32_t& x : words) x = uint32_t(rng());
    for (size_t i = 0; i < size_t(w * h); ++i) indices[i * 4] = int32_t(rng() % unsigned(tw * th));
    GPUFloatArray floatTable(tw, th, GPUFormat::RGBA32F, "floats", GPUStorage::Buffer);
    GPUFloatArray wordTable(tw, th, GPUFormat::RG32UI, "words", GPUStorage::Buffer);
    GPUFloatArray idx(w, h, GPUFormat::RGBA32I), out(w, h, 4), outWords(w, h, GPUFormat::RGBA32UI);
    floatTable.upload(floats);
    wordTable.upload(words);
    idx.upload(indices);
    GPUKernel kernel("gatherTable", "test/gather_table.frag");
    kernel.addInput(floatTable, "floats").addInput(wordTable, "words").addInput(idx, "indices");
    kernel.addOutput(out).addOutput(outWords);
    EXPECT_EQ(kernel.execute(), uint64_t(w * h));
    const auto r = out.download();
    const auto rw = outWords.downloadUint();
    for (size_t i = 0; i < size_t(w * h); ++i) {
        const size_t at = size_t(indices[i * 4]);
        for (size_t c = 0; c < 4; ++c) ASSERT_EQ(r[i * 4 + c], floats[at * 4 + c]) << i;
        ASSERT_EQ(rw[i * 4], words[at * 2]) << i;
        ASSERT_EQ(rw[i * 4 + 1], words[at * 2 + 1]) << i;
    }
    GPUKernel writer("gatherTable", "test/gather_table.frag");
    EXPECT_THROW(writer.addOutput(floatTable), UsageError);
    EXPECT_THROW(writer.addInOut(floatTable, "floats"), UsageError);
}

TEST_F(StreamKernel, ConditionalRenderSkipsPassWhenConditionWroteNothing) {
    const int w = 16, h = 16;
    const auto values = randomFloats(size_t(w * h), 0.0f, 1.0f, 9);
    GPUFloatArray input(w, h, 1), flags(w, h, 1), output(w, h, 1);
    input.upload(values);
    GPUKernel condition("countAbove", "test/count_above.frag");
    condition.addInput(input, "values").addOutput(flags);
    GPUKernel body("affine", "test/affine.frag");
    body.addInput(input, "values").addOutput(output).setUniform("scale", 2.0f).setUniform("offset", 1.0f);

    output.fill(-1.0f);
    condition.setUniform("limit", 5.0f);  // nothing above: the body must not run
    condition.dispatch();
    body.dispatchIf(condition);
    EXPECT_EQ(body.lastCount(), 0u);
    for (float v : output.download()) ASSERT_EQ(v, -1.0f);

    condition.setUniform("limit", 0.5f);
    condition.dispatch();
    body.dispatchIf(condition);
    EXPECT_EQ(body.lastCount(), uint64_t(w * h));
    const auto out = output.download();
    for (size_t i = 0; i < values.size(); ++i) ASSERT_EQ(out[i], values[i] * 2.0f + 1.0f);
}

TEST_F(StreamKernel, StatisticsPerKernelName) {
    const int w = 10, h = 10;
    const auto values = randomFloats(size_t(w * h), 0.0f, 1.0f, 10);
    GPUFloatArray input(w, h, 1), output(w, h, 1);
    input.upload(values);
    KernelStats::global().setTiming(true);
    GPUKernel kernel("threshold", "test/threshold.frag");
    kernel.addInput(input, "values").addOutput(output);
    uint64_t expected = 0;
    for (float t : {0.1f, 0.6f, 0.3f}) {
        kernel.setUniform("threshold", t);
        kernel.execute();
        expected += countAtOrAbove(values, t);
    }
    KernelStats::global().setTiming(false);
    const PassStats& stats = KernelStats::global().passes().at("threshold");
    EXPECT_EQ(stats.calls, 3u);
    EXPECT_EQ(stats.fragments, expected);
    EXPECT_GE(stats.gpuMs, 0.0);
}

TEST(StreamContext, OSMesaRunsTheSameKernelWithTheSameCounts) {
    GLContext context(GLBackend::OSMesa);
    EXPECT_EQ(context.platform(), "OSMesa");
    const int w = 25, h = 13;
    const auto values = randomFloats(size_t(w * h), 0.0f, 1.0f, 12);
    GPUFloatArray input(w, h, 1), output(w, h, 1);
    input.upload(values);
    GPUKernel kernel("threshold", "test/threshold.frag");
    kernel.addInput(input, "values").addOutput(output).setUniform("threshold", 0.3f);
    EXPECT_EQ(kernel.execute(), countAtOrAbove(values, 0.3f));
}

TEST(StreamContext, EglContextReportsRendererAndLimits) {
    GLContext context(GLBackend::Egl);
    EXPECT_EQ(context.platform().rfind("EGL", 0), 0u) << context.platform();
    bool sawRenderer = false;
    for (const auto& [name, value] : glInfo()) {
        if (name == "renderer") sawRenderer = !value.empty() && value != "?";
        if (name == "max_draw_buffers") {
            EXPECT_GE(std::stoi(value), 8);
        }
    }
    EXPECT_TRUE(sawRenderer);
}

}  // namespace
}  // namespace gpurt::test
