// PLY meshes (PlyLoader.h): one mesh written here in ASCII and in both binary byte orders with
// every property type reads as the same triangles, fanned as the contract says; extra properties
// and elements are skipped; every way a header can disagree with its data is refused, naming the
// file and the place.
#include "scene/PlyLoader.h"

#include <gtest/gtest.h>

#include "../common/Refusal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <bit>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "image/InputError.h"

namespace gpurt {
namespace {

// The test mesh: 5 vertices, a quad (fanned into 2 triangles) and a triangle, with normals.
const float kPositions[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}, {0.25f, -3.5f, 1e-3f}};
const float kNormals[5][3] = {{0, 0, 1}, {0, 0.6f, 0.8f}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
const std::vector<std::vector<int>> kFaces = {{0, 1, 2, 3}, {4, 2, 1}};

std::string asciiPly() {
    std::string s =
        "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 5\nproperty float x\nproperty float y\n"
        "property float z\nproperty float confidence\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    std::ostringstream data;
    data << std::fixed;  // six decimals, as std::to_string
    for (int v = 0; v < 5; ++v)
        data << kPositions[v][0] << ' ' << kPositions[v][1] << ' ' << kPositions[v][2] << " 0.5 " << kNormals[v][0]
             << ' ' << kNormals[v][1] << ' ' << kNormals[v][2] << '\n';
    for (const auto& f : kFaces) {
        data << f.size();
        for (int i : f) data << ' ' << i;
        data << " 7\n";
    }
    s += data.str();
    return s + "0 1\n";
}

// The same mesh in binary, positions as `posType` (float or double), indices as `indexType`
// counted by `countType`, in the given byte order.
std::string binaryPly(bool big, const std::string& posType, const std::string& countType, const std::string& indexType) {
    std::string s = std::string("ply\r\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\r\nelement vertex 5\r\nproperty " + posType + " x\r\nproperty " + posType + " y\r\nproperty " +
                    posType + " z\r\nproperty uchar red\r\nproperty float nx\r\nproperty float ny\r\nproperty float nz\r\n" +
                    "element face 2\r\nproperty list " + countType + " " + indexType + " vertex_index\r\nend_header\r\n";
    auto put = [&](const void* data, size_t n) {
        std::string bytes(static_cast<const char*>(data), n);
        if (big == (std::endian::native == std::endian::little)) std::reverse(bytes.begin(), bytes.end());
        s += bytes;
    };
    auto putInt = [&](const std::string& type, long long v) {
        if (type == "uchar" || type == "char" || type == "uint8" || type == "int8") {
            const int8_t b = int8_t(v);
            put(&b, 1);
        } else if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") {
            const int16_t b = int16_t(v);
            put(&b, 2);
        } else {
            const int32_t b = int32_t(v);
            put(&b, 4);
        }
    };
    for (int v = 0; v < 5; ++v) {
        for (int a = 0; a < 3; ++a) {
            if (posType == "double") {
                const double d = kPositions[v][a];
                put(&d, 8);
            } else {
                put(&kPositions[v][a], 4);
            }
        }
        const uint8_t red = 200;
        put(&red, 1);
        for (int a = 0; a < 3; ++a) put(&kNormals[v][a], 4);
    }
    for (const auto& f : kFaces) {
        putInt(countType, static_cast<long long>(f.size()));
        for (int i : f) putInt(indexType, i);
    }
    return s;
}

void expectTheMesh(const Scene& scene) {
    // Faces in file order, polygons fanned (v0, vi, vi+1).
    std::vector<std::array<int, 3>> expected;
    for (const auto& f : kFaces)
        for (size_t j = 1; j + 1 < f.size(); ++j) expected.push_back({f[0], f[j], f[j + 1]});
    ASSERT_EQ(scene.triangles.size(), expected.size());
    ASSERT_EQ(scene.normals.size(), expected.size());
    ASSERT_EQ(scene.materialIds, std::vector<uint32_t>(expected.size(), 0));
    ASSERT_EQ(scene.materials.size(), 1u);
    auto vec = [](const float (&p)[3]) { return glm::vec3(p[0], p[1], p[2]); };
    for (size_t t = 0; t < expected.size(); ++t) {
        EXPECT_EQ(scene.triangles[t].v0, vec(kPositions[expected[t][0]])) << t;
        EXPECT_EQ(scene.triangles[t].v1, vec(kPositions[expected[t][1]])) << t;
        EXPECT_EQ(scene.triangles[t].v2, vec(kPositions[expected[t][2]])) << t;
        EXPECT_EQ(scene.normals[t].n0, vec(kNormals[expected[t][0]])) << t;
        EXPECT_EQ(scene.normals[t].n2, vec(kNormals[expected[t][2]])) << t;
    }
}

TEST(PlyLoader, AsciiAndBothByteOrdersWithEveryTypeReadTheSameMesh) {
    // std::to_string's 6 decimals hold every value of the mesh exactly enough for float.
    expectTheMesh(parsePly(asciiPly(), "mesh.ply"));
    for (bool big : {false, true})
        for (const char* pos : {"float", "double"})
            for (const char* count : {"uchar", "ushort", "int", "uint8"})
                for (const char* index : {"int", "uint", "short", "ushort", "uchar", "int32", "uint32"}) {
                    SCOPED_TRACE(std::string(big ? "big" : "little") + " " + pos + " " + count + " " + index);
                    expectTheMesh(parsePly(binaryPly(big, pos, count, index), "mesh.ply"));
                }
}

TEST(PlyLoader, WithoutFacesOrNormals) {
    const Scene points = parsePly("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\n1 2 3\n4 5 6\n", "points.ply");
    EXPECT_TRUE(points.triangles.empty());
    const Scene flat = parsePly("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 1\nproperty list uchar uint vertex_indices\n"
                                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n", "flat.ply");
    ASSERT_EQ(flat.triangles.size(), 1u);
    EXPECT_TRUE(flat.normals.empty());
    EXPECT_EQ(flat.triangles[0].v0, glm::vec3(0, 1, 0));
}

// `text` with its first `from` replaced by `to` (std::string::replace draws a false -Wrestrict
// from GCC 12).
std::string replaced(const std::string& text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.substr(0, at) + to + text.substr(at + from.size());
}

// The message of the InputError parsing `bytes` throws (Refusal.h).
std::string refusal(const std::string& bytes) {
    return test::refusalOf([&] { parsePly(bytes, "bad.ply"); }, "bad.ply");
}

TEST(PlyLoader, RefusesHeadersThatDoNotMatchTheirData) {
    const std::string ascii = asciiPly();
    const std::string binary = binaryPly(false, "float", "uchar", "int");
    EXPECT_REFUSED("OFF\n3 1 0\n", "not a PLY file");
    EXPECT_REFUSED("", "not a PLY file");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 1\n", "no end_header");
    EXPECT_REFUSED("ply\nformat ascii 2.0\nend_header\n", "bad.ply:2: unknown PLY version");
    EXPECT_REFUSED("ply\nformat utf8 1.0\nend_header\n", "unknown format");
    EXPECT_REFUSED("ply\nelement vertex 1\nend_header\n", "bad.ply:2: element before the format line");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", "bad.ply:4: unknown type 'quad'");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "not a whole number");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nend_header\n0 0\n",
                   "no property x");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                   "property float nx\nend_header\n0 0 0 1\n", "nx, ny, nz but not all three");
    EXPECT_REFUSED("ply\nformat ascii 1.0\nbogus line\nend_header\n", "unknown header line 'bogus'");
    // Data shorter or longer than the header says.
    EXPECT_REFUSED(ascii.substr(0, ascii.size() - 4), "does not match the data");
    EXPECT_REFUSED(ascii.substr(0, ascii.size() - 12), "ends early");
    EXPECT_REFUSED(ascii + "3 0 1 2\n", "data after the last element");
    EXPECT_REFUSED(binary.substr(0, binary.size() - 1), "ends early");
    EXPECT_REFUSED(binary + std::string(3, '\0'), "3 bytes after the last element");
    // A count the file cannot hold is refused before anything is allocated for it.
    const std::string huge = replaced(binary, "element vertex 5", "element vertex 4000000000");
    EXPECT_REFUSED(huge, "4000000000 vertex elements of at least 25 bytes, but only");
    const std::string hugeAscii = replaced(ascii, "element face 2", "element face 99999999999");
    EXPECT_REFUSED(hugeAscii, "bad.ply:12: 99999999999 face elements");
    // Values.
    const std::string outOfRange = replaced(ascii, "\n4 0 1 2 3 7\n", "\n4 0 1 2 5 7\n");
    EXPECT_REFUSED(outOfRange, "face 0: vertex index 5 is out of range (5 vertices)");
    const std::string negative = replaced(ascii, "\n3 4 2 1 7\n", "\n3 4 -2 1 7\n");
    EXPECT_REFUSED(negative, "vertex index -2");
    const std::string twoVertices = replaced(ascii, "\n3 4 2 1 7\n", "\n2 4 2 7\n");
    EXPECT_REFUSED(twoVertices, "a face of 2 vertices");
    const std::string notANumber = replaced(ascii, "1.000000 1.000000 0.000000", "nan 1.000000 0.000000");
    EXPECT_REFUSED(notANumber, "not a finite float");
    const std::string word = replaced(ascii, " 7\n", " x\n");
    EXPECT_REFUSED(word, "'x' is not an integer");
    const std::string tooBig = replaced(ascii, " 7\n", " 256\n");
    EXPECT_REFUSED(tooBig, "256 does not fit");
    const std::string floatIndices = replaced(ascii, "uchar int vertex_indices", "uchar float vertex_indices");
    EXPECT_REFUSED(floatIndices, "not a list of integers");
    EXPECT_REFUSED(std::string("ply\nformat ascii 1.0\n\x01\nend_header\n"), "binary data in the header");
}

// The sRGB transfer function's inverse (IEC 61966-2-1), in double: PLY colours are display colours.
double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST(PlyLoader, VertexColoursAreDecodedFromSrgbToLinearPerCorner) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nproperty TYPE red\nproperty TYPE green\nproperty TYPE blue\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const int bytes[4][3] = {{255, 0, 10}, {128, 64, 200}, {1, 254, 33}, {0, 0, 0}};
    for (const char* type : {"uchar", "ushort", "float"}) {
        SCOPED_TRACE(type);
        const std::string t = type;
        std::ostringstream text;
        text << replaced(replaced(replaced(header, "TYPE", type), "TYPE", type), "TYPE", type);
        text.precision(9);
        for (int v = 0; v < 4; ++v) {
            text << v << " " << v % 2 << " 0";
            for (int c = 0; c < 3; ++c) {  // the same encoded value, byte / 255, in each type
                if (t == "float") text << " " << bytes[v][c] / 255.0;
                else text << " " << bytes[v][c] * (t == "ushort" ? 257 : 1);  // 65535 = 255 x 257
            }
            text << "\n";
        }
        text << "4 0 1 2 3\n";  // a quad: triangles (0, 1, 2) and (0, 2, 3)
        const Scene scene = parsePly(text.str(), "colours.ply");
        ASSERT_EQ(scene.triangles.size(), 2u);
        ASSERT_EQ(scene.colors.size(), 2u);
        auto expected = [&](int v) {
            glm::dvec3 e;
            for (int c = 0; c < 3; ++c) e[c] = srgbToLinear(bytes[v][c] / 255.0);
            return e;
        };
        const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
        for (int t = 0; t < 2; ++t) {
            const glm::vec3 got[3] = {scene.colors[size_t(t)].c0, scene.colors[size_t(t)].c1, scene.colors[size_t(t)].c2};
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[k][c], expected(corners[t][k])[c], 1e-6) << "triangle " << t << " corner " << k;
        }
    }
}

TEST(PlyLoader, PartialColoursAndOtherPropertiesAreNamedInOneWarning) {
    ::testing::internal::CaptureStderr();
    const Scene scene = parsePly(binaryPly(false, "float", "uchar", "int"), "red.ply");
    std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_TRUE(scene.colors.empty()) << "red without green and blue is no colour";
    EXPECT_EQ(err, "red.ply: warning: not used: vertex red\n");
    ::testing::internal::CaptureStderr();
    parsePly(asciiPly(), "mesh.ply");
    err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, "mesh.ply: warning: not used: vertex confidence, face flags, element edge\n");
    ::testing::internal::CaptureStderr();
    parsePly("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "property float s\nproperty float t\nproperty uchar alpha\nelement face 1\n"
             "property list uchar uint vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
             "quiet.ply");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "s, t and alpha are not named";
}

// A strip written as tristrips gives the triangles of the same mesh written as faces: OpenGL's
// alternating order, -1 restarting a strip, the triangles a strip makes to turn (a vertex twice)
// skipped but counted for the alternation, strips and faces in the order of their elements.
TEST(PlyLoader, TriangleStripsGiveTheTrianglesOfTheSameMeshWrittenAsFaces) {
    const std::string vertices =
        "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n";
    std::string points;
    for (int v = 0; v < 8; ++v)
        points += std::to_string(v % 4) + " " + std::to_string(v / 4) + " " + std::to_string(v * 0.125) + " 0 " +
                  std::to_string(v % 3) + " 1\n";
    // Strip 0 1 4 5 5 2 2 6 3 7 (a jump: (4, 5, 5), (5, 5, 2), (5, 2, 2), (2, 2, 6) are skipped but
    // counted), -1, then 7 6 5; a second list 0 2 1. The triangles by hand: the strip's k-th
    // (a, b, c) for even k, (b, a, c) for odd k.
    const std::string strips = "element tristrips 2\nproperty list int int vertex_indices\n";
    const std::string stripData = "14 0 1 4 5 5 2 2 6 3 7 -1 7 6 5\n3 0 2 1\n";
    const std::string faceData = "3 0 1 4\n3 4 1 5\n3 2 6 3\n3 3 6 7\n3 7 6 5\n3 0 2 1\n";
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 8\n" + vertices;
    // Faces first, then strips: the faces' triangles come first.
    const std::string both = head + "element face 1\nproperty list uchar int vertex_indices\n" + strips + "end_header\n" +
                             points + "3 0 1 2\n" + stripData;
    const std::string asFaces = head + "element face 7\nproperty list uchar int vertex_indices\nend_header\n" + points +
                                "3 0 1 2\n" + faceData;
    const Scene a = parsePly(both, "strips.ply"), b = parsePly(asFaces, "faces.ply");
    ASSERT_EQ(a.triangles.size(), 7u);
    ASSERT_EQ(b.triangles.size(), 7u);
    for (size_t t = 0; t < a.triangles.size(); ++t) {
        EXPECT_EQ(a.triangles[t].v0, b.triangles[t].v0) << t;
        EXPECT_EQ(a.triangles[t].v1, b.triangles[t].v1) << t;
        EXPECT_EQ(a.triangles[t].v2, b.triangles[t].v2) << t;
        EXPECT_EQ(a.normals[t].n1, b.normals[t].n1) << t;
    }
    // Only strips: the file has triangles (it once read as none).
    const std::string only = head + strips + "end_header\n" + points + stripData;
    EXPECT_EQ(parsePly(only, "only.ply").triangles.size(), 6u);
    // Winding: every triangle of one strip faces the same way.
    const Scene flat = parsePly("ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                                "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                                "0 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n2 1 0\n6 0 1 2 3 4 5\n", "flat.ply");
    ASSERT_EQ(flat.triangles.size(), 4u);
    for (const Triangle& t : flat.triangles) EXPECT_LT(glm::cross(t.v1 - t.v0, t.v2 - t.v0).z, 0.0f);
    EXPECT_REFUSED(replaced(only, "-1 7 6 5", "-2 7 6 5"), "triangle strip 0: vertex index -2 is out of range");
    EXPECT_REFUSED(replaced(only, "3 0 2 1", "3 0 2 8"), "triangle strip 2: vertex index 8 is out of range");
}

TEST(PlyLoader, AFileWithoutTrianglesIsAWarningNamingIt) {
    ::testing::internal::CaptureStderr();
    const Scene points = parsePly("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\n1 2 3\n4 5 6\n", "points.ply");
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_TRUE(points.triangles.empty());
    EXPECT_NE(err.find("points.ply: warning: no triangles"), std::string::npos) << err;
}

TEST(PlyLoader, LooksLikePly) {
    EXPECT_TRUE(looksLikePly("ply\nformat"));
    EXPECT_TRUE(looksLikePly("ply\r\nformat"));
    EXPECT_FALSE(looksLikePly("plywood\n"));
    EXPECT_FALSE(looksLikePly("# ply\n"));
}

}  // namespace
}  // namespace gpurt
