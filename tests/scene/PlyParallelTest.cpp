// The ASCII PLY reader on many threads (PlyLoader.h, PlyReadOptions) against the serial reader:
// generated files with normals, colours, unused properties and elements, faces of 3 to 6
// vertices, CRLF and tab-separated lines and numbers in every form std::from_chars reads, cut
// into chunks of 1 byte to 4 KiB on 1 to 5 threads, must give the same triangles, normals and
// colours bit for bit; files the parallel reader cannot take as one element a line (blank lines,
// an element over two lines, bad values, indices out of range) must give the serial reader's
// error word for word. And the decimal parser (DecimalNumber.h) against std::from_chars.
#include "scene/DecimalNumber.h"
#include "scene/PlyLoader.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "image/InputError.h"

namespace gpurt {
namespace {

// A number written one of many ways: fixed or scientific, few or many digits, signs, zeros.
std::string number(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    char text[64];
    const double v = unit(rng) * std::pow(10.0, double(int(rng() % 9) - 4));
    switch (rng() % 8) {
        case 0: std::snprintf(text, sizeof text, "%.6f", v); break;
        case 1: std::snprintf(text, sizeof text, "%.9g", v); break;
        case 2: std::snprintf(text, sizeof text, "%.17g", v); break;
        case 3: std::snprintf(text, sizeof text, "%.3e", v); break;
        case 4: std::snprintf(text, sizeof text, "%d", int(rng() % 2000) - 1000); break;
        case 5: std::snprintf(text, sizeof text, "%.25f", v); break;  // more digits than 19
        case 6: std::snprintf(text, sizeof text, "%.1f", std::round(v)); break;  // -0.0 among them
        default: std::snprintf(text, sizeof text, "%.12E", v * 1e20); break;
    }
    return text;
}

// An ASCII PLY of `vertices` vertices with x y z, an unused confidence, nx ny nz and red green
// blue, a face element with a flags property after the list, and an unused edge element.
std::string asciiFile(std::mt19937& rng, size_t vertices, size_t faces) {
    std::string s = "ply\r\nformat ascii 1.0\ncomment generated\nelement vertex " + std::to_string(vertices) +
                    "\nproperty float x\nproperty float y\nproperty double z\nproperty float confidence\n"
                    "property float nx\nproperty float ny\nproperty float nz\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                    "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\n"
                    "property short flags\nelement edge 2\nproperty int a\nproperty list uchar float b\nend_header\n";
    auto sep = [&] { return std::string(rng() % 5 == 0 ? "\t " : " "); };
    auto end = [&] { return std::string(rng() % 4 == 0 ? " \r\n" : "\n"); };
    for (size_t v = 0; v < vertices; ++v) {
        if (rng() % 7 == 0) s += "  ";
        for (int k = 0; k < 7; ++k) s += number(rng) + sep();
        for (int c = 0; c < 3; ++c) s += std::to_string(rng() % 256) + (c < 2 ? sep() : "");
        s += end();
    }
    for (size_t f = 0; f < faces; ++f) {
        const size_t n = 3 + rng() % 4;
        s += std::to_string(n);
        for (size_t j = 0; j < n; ++j) s += sep() + std::to_string(rng() % vertices);
        s += sep() + std::to_string(int(rng() % 100) - 50) + end();
    }
    s += "1 2 0.5 1.5\n7 0\n";
    return s;
}

bool sameBytes(const void* a, const void* b, size_t n) { return std::memcmp(a, b, n) == 0; }

template <typename T>
bool sameVector(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || sameBytes(a.data(), b.data(), a.size() * sizeof(T)));
}

void expectSameScene(const Scene& got, const Scene& expected, const std::string& what) {
    EXPECT_TRUE(sameVector(got.triangles, expected.triangles)) << what;
    EXPECT_TRUE(sameVector(got.normals, expected.normals)) << what;
    EXPECT_TRUE(sameVector(got.colors, expected.colors)) << what;
    EXPECT_EQ(got.materialIds, expected.materialIds) << what;
    EXPECT_EQ(got.materials.size(), expected.materials.size()) << what;
}

const PlyReadOptions kSerial{false, 1, 0};

TEST(PlyParallel, ChunksCutAnywhereReadAsTheSerialReaderDoes) {
    std::mt19937 rng(24);
    const std::string file = asciiFile(rng, 300, 500);
    ::testing::internal::CaptureStderr();  // the unused properties' warnings
    const Scene expected = parsePly(file, "mesh.ply", kSerial);
    ASSERT_EQ(expected.triangles.size() > 500, true);
    ASSERT_EQ(expected.colors.size(), expected.triangles.size());
    for (const size_t chunk : {size_t(1), size_t(2), size_t(7), size_t(61), size_t(4096), size_t(1) << 20})
        for (const int threads : {1, 2, 5})
            expectSameScene(parsePly(file, "mesh.ply", PlyReadOptions{true, threads, chunk}), expected,
                            "chunks of " + std::to_string(chunk) + " bytes, " + std::to_string(threads) + " threads");
    // Without a line end after the last element, and with blank lines after it.
    const std::string bare = file.substr(0, file.size() - 1);
    expectSameScene(parsePly(bare, "mesh.ply", PlyReadOptions{true, 2, 13}), parsePly(bare, "mesh.ply", kSerial), "bare");
    const std::string trailing = file + "\n \t\r\n\n";
    expectSameScene(parsePly(trailing, "mesh.ply", PlyReadOptions{true, 2, 13}), parsePly(trailing, "mesh.ply", kSerial),
                    "trailing");
    ::testing::internal::GetCapturedStderr();
}

// The message of the InputError that parsing throws, "" if none.
std::string errorOf(const std::string& bytes, const PlyReadOptions& options) {
    try {
        parsePly(bytes, "bad.ply", options);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(PlyParallel, FilesItCannotTakeGiveTheSerialReadersResultOrError) {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string good = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    const std::vector<std::string> bodies = {
        good,
        "0 0 0\n\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",  // a blank line: read, serially
        "0 0 0 1 0\n0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",   // elements across lines: read, serially
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 9\n",   // an index out of range
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 -1\n",  // a negative index
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n2 0 2\n",     // a face of 2
        "0 0 0\n1 0 0\n1 x 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",   // not a number
        "0 0 0\n1 0 0\n1 1e99 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",  // not a finite float
        "0 0 0\n1 0 0\n1 1e999 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",  // out of range
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3.5\n",   // not an integer
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n300 0 1 2\n3 0 2 3\n",   // a count too big for uchar
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n",               // ends early
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n1\n",   // data after the last element
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 7\n3 0 2 3\n",   // a value too many on a line
        std::string("0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\0\n", 41),  // a NUL
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3 \n  \r\n",  // blank lines at the end: fine
    };
    for (size_t b = 0; b < bodies.size(); ++b) {
        const std::string file = head + bodies[b];
        const std::string serial = errorOf(file, kSerial);
        for (const size_t chunk : {size_t(1), size_t(5), size_t(1) << 20}) {
            EXPECT_EQ(errorOf(file, PlyReadOptions{true, 3, chunk}), serial) << "body " << b << ", chunk " << chunk;
            if (serial.empty())
                expectSameScene(parsePly(file, "bad.ply", PlyReadOptions{true, 3, chunk}), parsePly(file, "bad.ply", kSerial),
                                "body " + std::to_string(b));
        }
        if (b == 0 || b == 1 || b == 2 || b == 15) EXPECT_EQ(serial, "") << "body " << b;
        else EXPECT_NE(serial, "") << "body " << b;
    }
    // More elements than bytes: refused before anything is sized by the count.
    const std::string huge = "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                             "property float z\nend_header\n0 0 0\n";
    EXPECT_EQ(errorOf(huge, PlyReadOptions{true, 2, 4}), errorOf(huge, kSerial));
}

TEST(PlyParallel, DecimalNumbersReadAsFromChars) {
    std::mt19937 rng(5);
    std::vector<std::string> texts = {"0", "-0", "0.0", "-0.0", ".5", "-.5", "5.", "1e5", "1E5", "1e+5", "1e-5",
                                      "1e", "1e+", "e5", "-", ".", "", "1.5.", "inf", "-inf", "nan", "+1", "1x",
                                      "9007199254740993", "9007199254740992", "123456789012345678901234",
                                      "0.1", "0.2", "0.3", "3.4028235e38", "1e22", "1e23", "1e-22", "1e-23",
                                      "00000000000000000000000001.5", "0.000000000000000000000000001",
                                      "1e000005", "1e0000000005", "2.2250738585072014e-308", "4.9e-324", "1e400"};
    for (int i = 0; i < 200000; ++i) texts.push_back(number(rng));
    for (int i = 0; i < 20000; ++i) {  // random digit strings, dots and exponents
        std::string t;
        const char alphabet[] = "0123456789.e-+";
        for (size_t n = rng() % 24; n > 0; --n) t += alphabet[rng() % (sizeof alphabet - 1)];
        texts.push_back(t);
    }
    size_t differ = 0;
    for (const std::string& t : texts) {
        double expected = 12345.0, got = 12345.0;
        const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), expected);
        const bool expectedOk = ec == std::errc() && p == t.data() + t.size();
        const bool ok = parseDecimal(t.data(), t.data() + t.size(), got);
        if (ok != expectedOk || (ok && !sameBytes(&got, &expected, sizeof got))) {
            if (++differ < 10) ADD_FAILURE() << "'" << t << "': " << got << " vs from_chars " << expected;
        }
    }
    EXPECT_EQ(differ, 0u);
}

}  // namespace
}  // namespace gpurt
