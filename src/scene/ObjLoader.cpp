// OBJ loading: tinyobjloader parses, after a light pre-scan of the lines has rejected what it
// would accept silently (a NaN read as 0, a zero or out-of-range index, a two-vertex face, a
// vertex with two coordinates, binary data). The pre-scan also records each face's vertex count,
// because tinyobjloader stores that count in an unsigned char, and the vertex positions, read
// with strtof: tinyobjloader's own number parser loses values with very long mantissas or
// exponents.
#include "scene/ObjLoader.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include <tiny_obj_loader.h>

#include "image/InputError.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

// 'text', built by appending (GCC 12 warns falsely on "'" + std::string).
std::string quote(std::string_view text) {
    std::string out(1, '\'');
    out.append(text);
    out += '\'';
    return out;
}

// What the pre-scan learns about the file.
struct ObjPreScan {
    size_t vertices = 0, normals = 0, texcoords = 0;
    std::vector<uint32_t> faceSizes;   // vertex count of each `f` line, in file order
    std::vector<glm::vec3> positions;  // x y z of each `v` line, in file order
    size_t statements = 0;              // lines with an OBJ keyword
    std::vector<std::pair<size_t, std::string>> unknown;  // lines with another first word, and it
};

// Every keyword of the OBJ format (Wavefront's Appendix B1, including free-form geometry, which
// gpurt ignores): any other first word of a line is not OBJ.
bool isObjKeyword(std::string_view k) {
    static const char* const kKeywords[] = {
        "v",     "vt",   "vn",    "vp",       "f",        "l",    "p",        "g",      "o",       "s",
        "mg",    "usemtl", "mtllib", "cstype", "deg",     "bmat", "step",     "curv",   "curv2",   "surf",
        "parm",  "trim", "hole",  "scrv",     "sp",       "end",  "con",      "bevel",  "c_interp", "d_interp",
        "lod",   "shadow_obj", "trace_obj", "ctech", "stech", "maplib", "usemap", "call", "csh", "res"};
    for (const char* keyword : kKeywords)
        if (k == keyword) return true;
    return false;
}

// An index that refers forward (OBJ allows that for positive indices); checked at the end of
// the file when the counts are known.
struct ForwardReference {
    size_t line;
    long long index;
    int kind;  // 0 vertex, 1 texcoord, 2 normal
};

class ObjScanner {
  public:
    explicit ObjScanner(std::string fileName) : fileName_(std::move(fileName)) {}

    [[noreturn]] void fail(size_t line, const std::string& what) const {
        failAt(FileLoc{fileName_, line}, what);
    }

    // The text of the file, split into lines the way tinyobjloader does (\n, \r\n or \r). Lines
    // that tinyobjloader should not see are blanked (kept as spaces, so line numbers hold).
    ObjPreScan scan(std::string& text) {
        ObjPreScan result;
        std::vector<ForwardReference> forward;
        size_t line = 0;
        size_t pos = 0;
        while (pos < text.size()) {
            size_t end = text.find_first_of("\r\n", pos);
            if (end == std::string_view::npos) end = text.size();
            ++line;
            if (!scanLine(std::string_view(text).substr(pos, end - pos), line, result, forward))
                std::fill(text.begin() + std::ptrdiff_t(pos), text.begin() + std::ptrdiff_t(end),
                          ' ');
            pos = end;
            if (pos < text.size() && text[pos] == '\r') {
                ++pos;
                if (pos < text.size() && text[pos] == '\n') ++pos;
            } else if (pos < text.size()) {
                ++pos;  // '\n'
            }
        }
        const size_t counts[3] = {result.vertices, result.texcoords, result.normals};
        for (const ForwardReference& ref : forward)
            if (static_cast<size_t>(ref.index) > counts[ref.kind])
                fail(ref.line, std::string(kindName(ref.kind)) + " index " +
                                   std::to_string(ref.index) + " is out of range (the file has " +
                                   std::to_string(counts[ref.kind]) + " " + kindPlural(ref.kind) +
                                   ")");
        return result;
    }

  private:
    static const char* kindName(int kind) {
        return kind == 0 ? "vertex" : kind == 1 ? "texture coordinate" : "normal";
    }
    static const char* kindPlural(int kind) {
        return kind == 0 ? "vertices" : kind == 1 ? "texture coordinates" : "normals";
    }

    static std::vector<std::string_view> tokens(std::string_view s) {
        std::vector<std::string_view> out;
        size_t i = 0;
        while (i < s.size()) {
            while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
            size_t start = i;
            while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
            if (i > start) out.push_back(s.substr(start, i - start));
        }
        return out;
    }

    // [+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)? -- what tinyobjloader reads as a
    // whole number; it would silently read a prefix of anything else ("1.5abc") or 0 ("nan").
    static bool isDecimal(std::string_view s) {
        size_t i = 0;
        auto digits = [&] {
            size_t start = i;
            while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
            return i - start;
        };
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        size_t mantissaDigits = digits();
        if (i < s.size() && s[i] == '.') {
            ++i;
            mantissaDigits += digits();
        }
        if (mantissaDigits == 0) return false;
        if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
            ++i;
            if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
            if (digits() == 0) return false;
        }
        return i == s.size();
    }

    // The value of a number token, which must be a decimal that fits in a float.
    float checkNumber(std::string_view token, size_t line) const {
        if (!isDecimal(token)) {
            std::string lower(token);
            for (char& c : lower)
                c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            size_t skip = (!lower.empty() && (lower[0] == '+' || lower[0] == '-')) ? 1 : 0;
            if (lower.compare(skip, 3, "nan") == 0 || lower.compare(skip, 3, "inf") == 0)
                fail(line, quote(token) + " is not a finite number");
            fail(line, quote(token) + " is not a number");
        }
        // tinyobjloader accumulates the exponent in an int (signed overflow from 2^31 on).
        const size_t e = token.find_first_of("eE");
        if (e != std::string_view::npos) {
            std::string_view digits = token.substr(e + 1);
            if (digits[0] == '+' || digits[0] == '-') digits.remove_prefix(1);
            while (digits.size() > 1 && digits[0] == '0') digits.remove_prefix(1);
            if (digits.size() > 9) fail(line, quote(token) + ": exponent out of range");
        }
        const std::string text(token);
        // Doubles at or above 2^128 - 2^103 round to float infinity.
        const double value = std::strtod(text.c_str(), nullptr);
        if (!(std::fabs(value) < 0x1.ffffffp127))
            fail(line, quote(token) + " does not fit in a 32-bit float");
        return std::strtof(text.c_str(), nullptr);
    }

    // Parses one index of a face element and checks 0 and range; `count` is how many elements of
    // that kind precede this line (negative indices are relative to it).
    void checkIndex(std::string_view token, std::string_view element, int kind, size_t count,
                    size_t line, std::vector<ForwardReference>& forward) const {
        long long value = 0;
        std::string_view digits = token;
        if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
        auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || ec != std::errc() || ptr != digits.data() + digits.size() ||
            value < INT_MIN || value > INT_MAX) {
            if (ec == std::errc::result_out_of_range ||
                (ec == std::errc() && ptr == digits.data() + digits.size()))
                fail(line, std::string(kindName(kind)) + " index " + std::string(token) +
                               " is out of range");
            fail(line, quote(element) +
                           " is not a valid vertex reference (expected v, v/vt, v//vn or v/vt/vn)");
        }
        if (value == 0)
            fail(line,
                 std::string(kindName(kind)) + " index 0 is invalid (OBJ indices start at 1)");
        if (value < 0 && static_cast<unsigned long long>(-value) > count)
            fail(line, std::string(kindName(kind)) + " index " + std::to_string(value) +
                           " is out of range (" + std::to_string(count) + " " + kindPlural(kind) +
                           " defined before this line)");
        if (value > 0 && static_cast<size_t>(value) > count) forward.push_back({line, value, kind});
    }

    // Checks one line; returns whether tinyobjloader should read it. It reads only what the
    // renderer uses: vertices (v, and vt and vn, which faces refer to), faces, groups and
    // materials. Its extensions are not for hostile input: "vw" converts any float to int, and
    // each "t" tag line allocates up to 3 x 8192 values, 300 KB from 19 bytes.
    bool scanLine(std::string_view text, size_t line, ObjPreScan& result,
                  std::vector<ForwardReference>& forward) {
        // Text files have no control characters besides tab and line ends (the caller split those
        // off).
        for (unsigned char c : text) {
            if ((c < 0x20 && c != '\t') || c == 0x7f) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "0x%02x", c);
                fail(line, std::string("binary data (byte ") + hex + "): not a text OBJ file");
            }
        }
        std::vector<std::string_view> tok = tokens(text);
        if (tok.empty() || tok[0][0] == '#') return true;
        const std::string_view keyword = tok[0];
        if (isObjKeyword(keyword))
            ++result.statements;
        else
            result.unknown.emplace_back(line, std::string(keyword.substr(0, 24)));
        if (keyword == "v" || keyword == "vn" || keyword == "vt") {
            float values[3] = {};
            for (size_t i = 1; i < tok.size(); ++i) {
                const float value = checkNumber(tok[i], line);
                if (i <= 3) values[i - 1] = value;
            }
            const size_t have = tok.size() - 1;
            if (keyword == "v") {
                if (have < 3)
                    fail(line, "vertex has " + std::to_string(have) + " coordinates; needs x y z");
                ++result.vertices;
                result.positions.emplace_back(values[0], values[1], values[2]);
            } else if (keyword == "vn") {
                if (have < 3)
                    fail(line, "normal has " + std::to_string(have) + " coordinates; needs x y z");
                ++result.normals;
            } else {
                if (have < 1) fail(line, "texture coordinate has no values");
                ++result.texcoords;
            }
            if (result.vertices > INT_MAX || result.normals > INT_MAX || result.texcoords > INT_MAX)
                fail(line, "too many vertices for 32-bit indices");
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            const size_t elements = tok.size() - 1;
            if (keyword == "f" && elements < 3)
                fail(line,
                     "face has " + std::to_string(elements) + " vertices; a face needs at least 3");
            if (elements < 1) fail(line, quote(keyword) + " without vertices");
            for (size_t i = 1; i < tok.size(); ++i) {
                // v, v/vt, v//vn or v/vt/vn
                std::string_view element = tok[i];
                std::string_view parts[3];
                int partCount = 0;
                size_t start = 0;
                while (true) {
                    size_t slash = element.find('/', start);
                    if (partCount == 3)
                        fail(line, quote(element) +
                                       " is not a valid vertex reference (expected v, v/vt, v//vn "
                                       "or v/vt/vn)");
                    parts[partCount++] = element.substr(
                        start, slash == std::string_view::npos ? slash : slash - start);
                    if (slash == std::string_view::npos) break;
                    start = slash + 1;
                }
                const size_t counts[3] = {result.vertices, result.texcoords, result.normals};
                for (int k = 0; k < partCount; ++k) {
                    if (parts[k].empty() && k == 1 && partCount == 3) continue;  // v//vn
                    checkIndex(parts[k], element, k, counts[k], line, forward);
                }
            }
            if (keyword == "f") result.faceSizes.push_back(static_cast<uint32_t>(elements));
        }
        return keyword == "v" || keyword == "vt" || keyword == "vn" || keyword == "f" ||
               keyword == "g" || keyword == "o" || keyword == "usemtl" || keyword == "mtllib";
    }

    std::string fileName_;
};


// Opens material libraries next to the OBJ file and remembers which could not be opened (the
// stock MaterialFileReader splits its folder at ':' and only reports failures as text).
// MTL illumination models 4, 6, 7 and 9 ask for glass (refraction). Maya writes illum 4 with Ni 1
// and Tf 1 1 1 on opaque materials: only a material that also bends light or lets it through is
// glass (CONTRACT.md: `Ni` other than 1, or `d` below 1). `indexGiven`: the library gives Ni (else
// 1.5, common glass).
bool isGlassIllum(int illum) { return illum == 4 || illum == 6 || illum == 7 || illum == 9; }
float glassIndex(const tinyobj::material_t& m, bool indexGiven) { return indexGiven ? float(m.ior) : 1.5f; }
bool isDielectric(const tinyobj::material_t& m, bool indexGiven) {
    return isGlassIllum(m.illum) && (glassIndex(m, indexGiven) != 1.0f || m.dissolve < 1.0f);
}

class MtlReader : public tinyobj::MaterialReader {
  public:
    explicit MtlReader(std::filesystem::path folder) : folder_(std::move(folder)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn,
                    std::string* err) override {
        // Each library once: a file that names it again and again must not multiply the
        // materials (or the warnings).
        if (auto seen = loaded_.find(name); seen != loaded_.end()) return seen->second;
        const std::filesystem::path path = folder_ / name;
        std::error_code ec;
        std::ifstream in;
        if (isReadableKind(std::filesystem::status(path, ec))) in.open(path, std::ios::binary);
        if (!in.is_open() || !in) {
            missing.push_back(path.string());
            return loaded_[name] = false;
        }
        const size_t first = materials->size();
        std::ostringstream text;
        text << in.rdbuf();
        noteGivenKeys(text.str());
        std::istringstream library(text.str());
        tinyobj::LoadMtl(matMap, materials, &library, warn, err);
        for (size_t m = first; m < materials->size() && !invalid; ++m)
            invalid = checkMaterial((*materials)[m], givenIndex.count((*materials)[m].name) > 0, FileLoc{path.string()});
        folders.resize(materials->size(), path.parent_path());
        return loaded_[name] = true;
    }

    // What is wrong with a material and the library that gives it.
    struct Problem {
        FileLoc library;
        std::string what;
    };

    // The first material of a library that the renderer cannot use: a colour or exponent that
    // is negative or not finite (tinyobjloader reads "Kd 1e39" as infinity). None when none.
    std::optional<Problem> invalid;

    std::vector<std::string> missing;

    // The folder of each material's library (texture file names are relative to it).
    std::vector<std::filesystem::path> folders;

    // Materials (by name) whose library gives Tf (or Kt) and Ni: tinyobjloader's defaults (Tf 0,
    // Ni 1) cannot be told from values a file gives.
    std::set<std::string> givenFilter, givenIndex;
    // Materials that use the MTL PBR extension (Pr, Pm, map_Pr, map_Pm): glTF's model.
    std::set<std::string> givenPbr;

  private:
    void noteGivenKeys(const std::string& text) {
        std::istringstream lines(text);
        std::string line, current;
        while (std::getline(lines, line)) {
            std::istringstream words(line);
            std::string key;
            words >> key;
            if (key == "newmtl") {
                std::getline(words >> std::ws, current);
                while (!current.empty() && std::isspace(static_cast<unsigned char>(current.back()))) current.pop_back();
            }
            if (key == "Tf" || key == "Kt") givenFilter.insert(current);
            if (key == "Ni") givenIndex.insert(current);
            if (key == "Pr" || key == "Pm" || key == "map_Pr" || key == "map_Pm") givenPbr.insert(current);
        }
    }

    static std::optional<Problem> checkMaterial(const tinyobj::material_t& m, bool indexGiven, const FileLoc& library) {
        auto bad = [](float x) { return !std::isfinite(x) || x < 0.0f; };
        std::string what;
        if (bad(m.diffuse[0]) || bad(m.diffuse[1]) || bad(m.diffuse[2]))
            what = "Kd";
        else if (bad(m.specular[0]) || bad(m.specular[1]) || bad(m.specular[2]))
            what = "Ks";
        else if (bad(m.shininess))
            what = "Ns";
        else if (bad(m.emission[0]) || bad(m.emission[1]) || bad(m.emission[2]))
            what = "Ke";
        else if (bad(m.transmittance[0]) || bad(m.transmittance[1]) || bad(m.transmittance[2]))
            what = "Tf";
        else if (bad(m.ior) || (isDielectric(m, indexGiven) && m.ior == 0.0f))
            what = "Ni";
        else if (bad(m.roughness) || bad(m.metallic))
            what = "Pr or Pm";
        else if (bad(m.dissolve))
            what = "d (or Tr)";
        if (what.empty()) return std::nullopt;
        return Problem{library, "material " + quote(m.name) + ": " + what + " must be finite and not negative"};
    }

    std::filesystem::path folder_;
    std::map<std::string, bool> loaded_;  // library name -> whether it could be read
};


glm::vec3 toVec3(const tinyobj::real_t* p) {
    return glm::vec3(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
}

// The scene texture of map_Kd `file` (relative to `folder`), read once per file; -1 with a
// warning naming it when it cannot be read (the material then keeps its colour).
int textureOf(const std::string& file, const std::filesystem::path& folder, const std::string& name,
              const std::string& material, std::map<std::string, int>& known, Scene& scene) {
    std::string relative = file;
    std::replace(relative.begin(), relative.end(), '\\', '/');  // as Windows exporters write them
    const std::filesystem::path path = folder / relative;
    if (auto seen = known.find(path.string()); seen != known.end()) return seen->second;
    int& index = known[path.string()] = -1;
    std::error_code ec;
    try {
        if (!isReadableKind(std::filesystem::status(path, ec)))
            failAt(FileLoc{path.string()}, "cannot open image file");
        Texture texture;
        texture.name = path.string();
        texture.image = readImage(path);
        scene.textures.push_back(std::move(texture));
        index = int(scene.textures.size() - 1);
    } catch (const InputError& e) {
        warnAt(FileLoc{name}, "material " + quote(material) + ": map_Kd: " + e.what() +
                                  "; the material keeps its colour");
    }
    return index;
}

// Drops a UTF-8 byte order mark, which would hide the first line's keyword from tinyobjloader,
// and blanks the comments: from '#' to the end of the line (\n, \r\n or \r), also after data
// ("f 1 2 3 # quad"), as exporters write them. Blanking keeps line numbers and spares
// tinyobjloader.
void blankComments(std::string& text) {
    if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
    for (size_t at = text.find('#'); at != std::string::npos; at = text.find('#', at)) {
        const size_t end = text.find_first_of("\r\n", at);
        std::fill(text.begin() + std::ptrdiff_t(at),
                  end == std::string::npos ? text.end() : text.begin() + std::ptrdiff_t(end), ' ');
        if (end == std::string::npos) break;
        at = end;
    }
}

// A text file that is not OBJ at all is refused; unknown statements in an OBJ are warnings.
void reportUnknownStatements(const ObjPreScan& scan, const std::string& name) {
    if (scan.statements == 0 && !scan.unknown.empty())
        failAt(FileLoc{name, scan.unknown.front().first},
               "not a scene file: no OBJ statement in it (this line starts with " +
                   quote(scan.unknown.front().second) + ")");
    constexpr size_t kMaxWarnings = 5;
    for (size_t k = 0; k < scan.unknown.size() && k < kMaxWarnings; ++k)
        warnAt(FileLoc{name, scan.unknown[k].first},
               "unknown statement " + quote(scan.unknown[k].second) + " ignored");
    if (scan.unknown.size() > kMaxWarnings)
        warnAt(FileLoc{name},
               std::to_string(scan.unknown.size() - kMaxWarnings) + " more unknown statements ignored");
}

// What tinyobjloader reads of the (pre-scanned) text.
struct ObjFile {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
};

// tinyobjloader's reading of the text, its material libraries read by mtlReader.
ObjFile readObjFile(const std::string& text, const std::string& name, MtlReader& mtlReader) {
    ObjFile obj;
    std::string warn, err;
    std::istringstream stream(text);
    // triangulate = false: tinyobjloader splits quads along the shorter diagonal, which is not the
    // contract's fan; addFaces fans the polygons itself.
    const bool ok =
        tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &warn, &err, &stream, &mtlReader,
                         /*triangulate=*/false, /*default_vcols_fallback=*/false);
    if (!ok) {
        std::string first = err.substr(0, err.find('\n'));
        failAt(FileLoc{name}, first.empty() ? "cannot parse OBJ file" : first);
    }
    if (mtlReader.invalid) failAt(mtlReader.invalid->library, mtlReader.invalid->what);
    for (const std::string& missing : mtlReader.missing)
        warnAt(FileLoc{name}, "cannot open material library " + missing + "; using the default material");
    return obj;
}

// The invariants the pre-scan relies on (a disagreement would misnumber triangles).
void checkAgainstPreScan(const ObjFile& obj, const ObjPreScan& scan, const std::string& name) {
    if (obj.attrib.vertices.size() / 3 != scan.vertices)
        failAt(FileLoc{name}, "read " + std::to_string(obj.attrib.vertices.size() / 3) +
                                  " vertices but the file has " + std::to_string(scan.vertices) +
                                  " 'v' lines");
    size_t faceCount = 0, indexCount = 0;
    for (const tinyobj::shape_t& shape : obj.shapes) {
        faceCount += shape.mesh.material_ids.size();
        indexCount += shape.mesh.indices.size();
    }
    size_t expectedIndices = 0;
    for (uint32_t n : scan.faceSizes) expectedIndices += n;
    if (faceCount != scan.faceSizes.size() || indexCount != expectedIndices)
        failAt(FileLoc{name}, "read " + std::to_string(faceCount) + " faces but the file has " +
                                  std::to_string(scan.faceSizes.size()) + " 'f' lines");
}

// d (1 - Tr) and map_d of a material that is not glass: alpha coverage, BLEND (rays pass with
// probability 1 - d times map_d). map_d is a scalar texture: the channel its -imfchan names (r, g,
// b; m, the matte channel, is A), else (tinyobjloader's default 'm', or l, luminance) A where the
// image has any alpha below 1 (an RGBA cut-out) and R where it has none (a grey mask).
void alphaCoverage(const tinyobj::material_t& m, const std::filesystem::path& folder, const std::string& name,
                   std::map<std::string, int>& textureFiles, Scene& scene, Material& material) {
    float d = static_cast<float>(m.dissolve);
    if (d > 1.0f) {
        warnAt(FileLoc{name}, "material " + quote(m.name) + ": d above 1 (or Tr below 0), clamped to 1");
        d = 1.0f;
    }
    int texture = -1;
    if (!m.alpha_texname.empty()) texture = textureOf(m.alpha_texname, folder, name, m.name, textureFiles, scene);
    if (d >= 1.0f && texture < 0) return;
    material.alphaMode = 2;  // glsl/common/alpha.h GPURT_ALPHA_BLEND
    material.alphaFactor = d;
    if (texture < 0) return;
    const char channel = m.alpha_texopt.imfchan;
    int c = channel == 'r' ? 0 : channel == 'g' ? 1 : channel == 'b' ? 2 : -1;
    if (c < 0) {
        const std::vector<uint32_t>& texels = scene.textures[size_t(texture)].image.texels;
        const bool cutOut = std::any_of(texels.begin(), texels.end(), [](uint32_t t) { return (t >> 24) != 255u; });
        c = cutOut ? 3 : 0;
    }
    material.alphaTexture = {texture, c};
}

// The scene material of an MTL material (its map_Kd added to the scene's textures).
Material sceneMaterial(const tinyobj::material_t& m, const std::filesystem::path& folder,
                       const MtlReader& mtlReader, const std::string& name,
                       std::map<std::string, int>& textureFiles, Scene& scene) {
    Material material;
    if (!m.diffuse_texname.empty())
        material.diffuseTexture = textureOf(m.diffuse_texname, folder, name, m.name, textureFiles, scene);
    material.name = m.name;
    material.diffuse = toVec3(m.diffuse);
    material.specular = toVec3(m.specular);
    material.shininess = static_cast<float>(m.shininess);
    material.emission = toVec3(m.emission);
    // MTL illumination models 4, 6, 7 and 9 are glass where Ni is not 1 or d is below 1
    // (isDielectric): refraction with index Ni (1.5, common glass, when the library gives none)
    // and the filter Tf (1 1 1 when it gives none). Otherwise they are opaque: Kd and Ks as usual.
    const bool indexGiven = mtlReader.givenIndex.count(m.name) > 0;
    if (isDielectric(m, indexGiven)) {
        material.ior = glassIndex(m, indexGiven);
        material.transmission = mtlReader.givenFilter.count(m.name) ? toVec3(m.transmittance) : glm::vec3(1.0f);
        if (glm::any(glm::greaterThan(material.transmission, glm::vec3(1.0f)))) {
            material.transmission = glm::min(material.transmission, glm::vec3(1.0f));
            warnAt(FileLoc{name}, "material " + quote(m.name) + ": Tf above 1, clamped to 1");
        }
    }
    if (!isDielectric(m, indexGiven)) alphaCoverage(m, folder, name, textureFiles, scene, material);
    // The MTL PBR extension (Pr roughness, Pm metallic, their maps' first channel, norm, map_Ke):
    // glTF's metallic-roughness model with Kd the base colour (glsl/common/materials/gltf.h).
    if (mtlReader.givenPbr.count(m.name) && material.ior == 0.0f) {
        material.model = GPURT_MODEL_GLTF;
        material.roughness = std::clamp(static_cast<float>(m.roughness), 0.0f, 1.0f);
        material.metallic = std::clamp(static_cast<float>(m.metallic), 0.0f, 1.0f);
        if (!(material.roughness == static_cast<float>(m.roughness)) || !(material.metallic == static_cast<float>(m.metallic)))
            warnAt(FileLoc{name}, "material " + quote(m.name) + ": Pr and Pm are clamped to [0, 1]");
        if (!m.roughness_texname.empty())
            material.roughnessTexture = {textureOf(m.roughness_texname, folder, name, m.name, textureFiles, scene), 0};
        if (!m.metallic_texname.empty())
            material.metallicTexture = {textureOf(m.metallic_texname, folder, name, m.name, textureFiles, scene), 0};
        if (!m.normal_texname.empty())
            material.normalTexture = textureOf(m.normal_texname, folder, name, m.name, textureFiles, scene);
        if (!m.emissive_texname.empty() && material.emits())
            material.emissiveTexture = textureOf(m.emissive_texname, folder, name, m.name, textureFiles, scene);
        return material;
    }
    // MTL illumination models 3, 5 and 7 turn on ray-traced reflection.
    if (m.illum == 3 || m.illum == 5 || m.illum == 7) material.reflectivity = material.specular;
    // A mirror reflects at most all light (a JSON scene's range): Ks above 1 with a
    // reflective illum model is clamped for the reflectivity, with a warning.
    if (glm::any(glm::greaterThan(material.reflectivity, glm::vec3(1.0f)))) {
        material.reflectivity = glm::min(material.reflectivity, glm::vec3(1.0f));
        warnAt(FileLoc{name}, "material " + quote(m.name) + ": reflectivity (Ks with illum " +
                                  std::to_string(m.illum) + ") above 1, clamped to 1");
    }
    return material;
}

// The faces as triangles, each polygon a fan around its first vertex (the contract's numbering),
// with their vertex normals when every vertex of the face has one and their texture coordinates
// when the scene has textures. Faces without a (known) material get the default one, appended
// after the MTL's.
void addFaces(const ObjFile& obj, const ObjPreScan& scan, Scene& scene) {
    uint32_t defaultMaterial = UINT32_MAX;
    auto materialFor = [&](int id) -> uint32_t {
        if (id >= 0 && static_cast<size_t>(id) < obj.materials.size())
            return static_cast<uint32_t>(id);
        if (defaultMaterial == UINT32_MAX) {
            defaultMaterial = static_cast<uint32_t>(scene.materials.size());
            scene.materials.push_back(Material{});
        }
        return defaultMaterial;
    };
    const tinyobj::attrib_t& attrib = obj.attrib;
    size_t expectedIndices = 0;
    for (uint32_t n : scan.faceSizes) expectedIndices += n;
    scene.triangles.reserve(expectedIndices - 2 * scan.faceSizes.size());
    size_t face = 0;
    for (const tinyobj::shape_t& shape : obj.shapes) {
        size_t first = 0;
        for (size_t f = 0; f < shape.mesh.material_ids.size(); ++f, ++face) {
            const uint32_t n = scan.faceSizes[face];
            const uint32_t material = materialFor(shape.mesh.material_ids[f]);
            auto vertex = [&](size_t i) {
                const int index = shape.mesh.indices[first + i].vertex_index;
                return scan.positions[static_cast<size_t>(index)];
            };
            // The face's vertex normals (v//vn, v/vt/vn), if every vertex has one.
            auto normal = [&](size_t i) {
                const int index = shape.mesh.indices[first + i].normal_index;
                return index >= 0 && 3 * size_t(index) + 2 < attrib.normals.size()
                           ? toVec3(&attrib.normals[3 * size_t(index)])
                           : glm::vec3(0.0f);
            };
            bool hasNormals = true;
            for (uint32_t i = 0; i < n && hasNormals; ++i)
                hasNormals = shape.mesh.indices[first + i].normal_index >= 0;
            // The face's texture coordinates (v/vt, v/vt/vn) as image coordinates: OBJ's v axis
            // points up, the image's rows down. Missing or not finite: 0.
            auto texcoord = [&](size_t i) {
                const int index = shape.mesh.indices[first + i].texcoord_index;
                if (index < 0 || 2 * size_t(index) + 1 >= attrib.texcoords.size()) return glm::vec2(0.0f);
                const glm::vec2 t(float(attrib.texcoords[2 * size_t(index)]), 1.0f - float(attrib.texcoords[2 * size_t(index) + 1]));
                return std::isfinite(t.x) && std::isfinite(t.y) ? t : glm::vec2(0.0f);
            };
            const bool textured = !scene.textures.empty();
            const glm::vec3 v0 = vertex(0);
            for (uint32_t i = 1; i + 1 < n; ++i) {
                scene.triangles.push_back({v0, vertex(i), vertex(i + 1)});
                scene.materialIds.push_back(material);
                if (hasNormals) {
                    scene.normals.resize(scene.triangles.size());
                    scene.normals.back() = {normal(0), normal(i), normal(i + 1)};
                }
                if (textured) scene.texcoords.push_back({texcoord(0), texcoord(i), texcoord(i + 1)});
            }
            first += n;
        }
    }
}

}  // namespace

Scene loadObj(const std::filesystem::path& path) { return parseObj(readSceneFile(path), path); }

Scene parseObj(std::string text, const std::filesystem::path& path) {
    const std::string name = path.string();
    blankComments(text);
    const ObjPreScan scan = ObjScanner(name).scan(text);
    reportUnknownStatements(scan, name);
    MtlReader mtlReader(path.parent_path());
    const ObjFile obj = readObjFile(text, name, mtlReader);
    checkAgainstPreScan(obj, scan, name);

    Scene scene;
    std::map<std::string, int> textureFiles;
    for (size_t m = 0; m < obj.materials.size(); ++m)
        scene.materials.push_back(
            sceneMaterial(obj.materials[m], mtlReader.folders[m], mtlReader, name, textureFiles, scene));
    addFaces(obj, scan, scene);
    if (scene.materials.empty()) scene.materials.push_back(Material{});
    if (!scene.normals.empty()) scene.normals.resize(scene.triangles.size());
    return scene;
}

}  // namespace gpurt
