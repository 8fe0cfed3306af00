// GPUFloatArray and GPUPingPongArray: transfers, formats, fill and copy, size checks.
#include "../common/GLTest.h"

#include "stream/GPUFloatArray.h"
#include "stream/StreamErrors.h"

namespace gpurt::test {
namespace {

class StreamArray : public GLTest {};

TEST_F(StreamArray, UploadDownloadRoundTripsEveryFloatWidth) {
    for (int channels : {1, 2, 4}) {
        GPUFloatArray array(37, 19, channels, "roundtrip");
        const auto data = randomFloats(37 * 19 * size_t(channels), -1e6f, 1e6f, 7u + unsigned(channels));
        array.upload(data);
        EXPECT_EQ(array.download(), data) << channels << " channels";
    }
}

TEST_F(StreamArray, IntegerFormatsHoldValuesBeyondFloatPrecision) {
    GPUFloatArray u(8, 8, GPUFormat::RGBA32UI, "uint");
    std::vector<uint32_t> words(8 * 8 * 4);
    for (size_t i = 0; i < words.size(); ++i) words[i] = 0xfffffff0u - uint32_t(i) * 977u;
    u.upload(words);
    EXPECT_EQ(u.downloadUint(), words);

    GPUFloatArray s(5, 3, GPUFormat::R32I, "int");
    std::vector<int32_t> ints(15);
    for (size_t i = 0; i < ints.size(); ++i) ints[i] = (1 << 24) + 1 - int32_t(i) * 3000001;
    s.upload(ints);
    EXPECT_EQ(s.downloadInt(), ints);
}

TEST_F(StreamArray, UploadRowsWritesOnlyThoseRows) {
    GPUFloatArray array(4, 6, 1, "rows");
    array.fill(-1.0f);
    std::vector<float> rows(4 * 2, 5.0f);
    array.uploadRows(3, 2, rows);
    const auto out = array.download();
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(out[size_t(y * 4 + x)], (y == 3 || y == 4) ? 5.0f : -1.0f);
}

TEST_F(StreamArray, FillAndCopyFrom) {
    GPUFloatArray a(16, 16, 4, "a"), b(16, 16, 4, "b");
    a.fill(3.5f);
    b.copyFrom(a);
    for (float v : b.download()) EXPECT_EQ(v, 3.5f);
    GPUFloatArray other(8, 16, 4, "other");
    EXPECT_THROW(other.copyFrom(a), UsageError);
}

TEST_F(StreamArray, WrongSizesAndTypesAreRefused) {
    EXPECT_THROW(GPUFloatArray(0, 4, 1), UsageError);
    EXPECT_THROW(GPUFloatArray(4, -1, 1), UsageError);
    EXPECT_THROW(GPUFloatArray(4, 4, 3), UsageError);
    EXPECT_THROW(GPUFloatArray(1 << 20, 1, 1), EnvironmentError);  // beyond GL_MAX_TEXTURE_SIZE
    GPUFloatArray array(4, 4, 1);
    EXPECT_THROW(array.upload(std::vector<float>(15)), UsageError);
    EXPECT_THROW(array.upload(std::vector<uint32_t>(16)), UsageError);
}

// A buffer table holds the same W x H elements, row after row, in a buffer texture.
TEST_F(StreamArray, BufferTablesTransferFillAndCopyLikeTextures) {
    GPUFloatArray table(37, 19, GPUFormat::RGBA32F, "table", GPUStorage::Buffer);
    EXPECT_EQ(table.storage(), GPUStorage::Buffer);
    const auto data = randomFloats(37 * 19 * 4, -1e6f, 1e6f, 21u);
    table.upload(data);
    EXPECT_EQ(table.download(), data);

    GPUFloatArray words(5, 4, GPUFormat::RG32UI, "words", GPUStorage::Buffer);
    std::vector<uint32_t> w(5 * 4 * 2);
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0xfffffff7u - uint32_t(i) * 65537u;
    words.upload(w);
    EXPECT_EQ(words.downloadUint(), w);
    words.uploadRows(2, 1, std::vector<uint32_t>(5 * 2, 7u));
    const auto rows = words.downloadUint();
    for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i], i / 10 == 2 ? 7u : w[i]) << i;

    GPUFloatArray a(8, 3, GPUFormat::R32F, "a", GPUStorage::Buffer), b(8, 3, GPUFormat::R32F, "b", GPUStorage::Buffer);
    a.fill(-2.25f);
    b.copyFrom(a);
    for (float v : b.download()) EXPECT_EQ(v, -2.25f);
    GPUFloatArray texture(8, 3, GPUFormat::R32F, "texture");
    EXPECT_THROW(texture.copyFrom(a), UsageError);  // another storage
}

TEST_F(StreamArray, PingPongSwapsFrontAndBack) {
    GPUPingPongArray pp(4, 4, 1, "pp");
    const GLuint front = pp.front().texture();
    const GLuint back = pp.back().texture();
    EXPECT_NE(front, back);
    pp.swap();
    EXPECT_EQ(pp.front().texture(), back);
    EXPECT_EQ(pp.back().texture(), front);
}

}  // namespace
}  // namespace gpurt::test
