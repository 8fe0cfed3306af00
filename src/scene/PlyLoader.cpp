// PLY reading: the header into elements and properties, then the data through one reader per
// encoding (ASCII tokens with line numbers, or binary values of either byte order), every count
// checked against the bytes that are left before anything is allocated. An ASCII file of one
// element a line is read on all cores first (ParallelAsciiReader), the serial reader its fallback.
#include "scene/PlyLoader.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "base/LargeArray.h"
#include "base/Parallel.h"
#include "image/Colour.h"
#include "image/InputError.h"
#include "scene/DecimalNumber.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Type> typeNamed(std::string_view name) {
    static const std::pair<const char*, Type> kTypes[] = {
        {"char", Type::Int8},     {"int8", Type::Int8},       {"uchar", Type::UInt8},   {"uint8", Type::UInt8},
        {"short", Type::Int16},   {"int16", Type::Int16},     {"ushort", Type::UInt16}, {"uint16", Type::UInt16},
        {"int", Type::Int32},     {"int32", Type::Int32},     {"uint", Type::UInt32},   {"uint32", Type::UInt32},
        {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
    for (const auto& [n, t] : kTypes)
        if (name == n) return t;
    return std::nullopt;
}

size_t sizeOf(Type t) {
    switch (t) {
        case Type::Int8:
        case Type::UInt8: return 1;
        case Type::Int16:
        case Type::UInt16: return 2;
        case Type::Int32:
        case Type::UInt32:
        case Type::Float32: return 4;
        case Type::Float64: return 8;
    }
    return 0;
}

bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

// Whether the integer v is within the range of `type`.
bool fits(Type type, double v) {
    switch (type) {
        case Type::Int8: return v >= -128 && v <= 127;
        case Type::UInt8: return v >= 0 && v <= 255;
        case Type::Int16: return v >= -32768 && v <= 32767;
        case Type::UInt16: return v >= 0 && v <= 65535;
        case Type::Int32: return v >= -2147483648.0 && v <= 2147483647.0;
        case Type::UInt32: return v >= 0 && v <= 4294967295.0;
        default: return true;
    }
}

struct Property {
    std::string name;
    bool list = false;
    Type countType = Type::UInt8;  // lists only
    Type type = Type::Float32;     // the value's, or a list item's
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
    size_t line = 0;  // of its header line

    // The fewest bytes one element takes in a binary file (an empty list is its count alone).
    uint64_t minBinaryBytes() const {
        uint64_t bytes = 0;
        for (const Property& p : properties) bytes += sizeOf(p.list ? p.countType : p.type);
        return bytes;
    }
};

enum class Format { Ascii, Little, Big };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t dataStart = 0;  // byte offset of the data
    size_t lines = 0;      // header lines (the ASCII data's first line is lines + 1)
};

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

std::string shown(std::string_view text) {
    std::string out = "'";
    for (unsigned char c : text.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? char(c) : '?';
    return out + (text.size() > 40 ? "...'" : "'");
}

Header readHeader(std::string_view bytes, const std::string& name) {
    auto fail = [&](size_t line, const std::string& what) { failAt(FileLoc{name, line}, what); };
    if (!looksLikePly(std::string(bytes.substr(0, 5)))) failAt(FileLoc{name}, "not a PLY file (it does not start with 'ply')");
    Header header;
    bool haveFormat = false;
    size_t pos = 0, line = 0;
    while (true) {
        const size_t end = bytes.find('\n', pos);
        if (end == std::string_view::npos) fail(line + 1, "the header has no end_header line");
        ++line;
        std::string_view text(bytes.data() + pos, end - pos);
        if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
        pos = end + 1;
        for (unsigned char c : text)
            if ((c < 0x20 && c != '\t') || c >= 0x7f) fail(line, "binary data in the header");
        const std::vector<std::string_view> w = words(text);
        if (line == 1) continue;  // "ply"
        if (w.empty()) continue;
        const std::string_view keyword = w[0];
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (w.size() != 1) fail(line, "end_header followed by " + shown(w[1]));
            break;
        }
        if (keyword == "format") {
            if (haveFormat) fail(line, "a second format line");
            if (w.size() != 3) fail(line, "format needs an encoding and a version");
            if (w[1] == "ascii") header.format = Format::Ascii;
            else if (w[1] == "binary_little_endian") header.format = Format::Little;
            else if (w[1] == "binary_big_endian") header.format = Format::Big;
            else fail(line, "unknown format " + shown(w[1]) + " (ascii, binary_little_endian, binary_big_endian)");
            if (w[2] != "1.0") fail(line, "unknown PLY version " + shown(w[2]) + " (1.0)");
            haveFormat = true;
        } else if (keyword == "element") {
            if (!haveFormat) fail(line, "element before the format line");
            if (w.size() != 3) fail(line, "element needs a name and a count");
            Element e;
            e.name = std::string(w[1]);
            e.line = line;
            const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
            if (ec != std::errc() || p != w[2].data() + w[2].size())
                fail(line, "element count " + shown(w[2]) + " is not a whole number");
            for (const Element& other : header.elements)
                if (other.name == e.name) fail(line, "element " + shown(e.name) + " declared twice");
            header.elements.push_back(std::move(e));
        } else if (keyword == "property") {
            if (header.elements.empty()) fail(line, "property before any element");
            Property p;
            const bool list = w.size() >= 2 && w[1] == "list";
            if (w.size() != (list ? 5u : 3u))
                fail(line, list ? "property list needs a count type, an item type and a name"
                                : "property needs a type and a name");
            p.list = list;
            if (list) {
                const std::optional<Type> count = typeNamed(w[2]);
                if (!count) fail(line, "unknown type " + shown(w[2]));
                if (!isInteger(*count)) fail(line, "a list's count type must be an integer type, not " + shown(w[2]));
                p.countType = *count;
            }
            const std::optional<Type> type = typeNamed(w[list ? 3 : 1]);
            if (!type) fail(line, "unknown type " + shown(w[list ? 3 : 1]));
            p.type = *type;
            p.name = std::string(w.back());
            for (const Property& other : header.elements.back().properties)
                if (other.name == p.name) fail(line, "property " + shown(p.name) + " declared twice");
            header.elements.back().properties.push_back(std::move(p));
        } else {
            fail(line, "unknown header line " + shown(keyword));
        }
    }
    if (!haveFormat) fail(line, "the header has no format line");
    header.dataStart = pos;
    header.lines = line;
    return header;
}

// Values of the data, in order, whatever the encoding; `fail` names the place in messages.
class DataReader {
  public:
    DataReader(std::string_view bytes, const Header& header, const std::string& name)
        : bytes_(bytes), format_(header.format), pos_(header.dataStart), line_(header.lines + 1), name_(name) {}

    // "FILE:LINE: what" (ASCII), "FILE: ELEMENT INDEX (byte B): what" (binary).
    [[noreturn]] void fail(const std::string& what) const {
        if (format_ == Format::Ascii) failAt(FileLoc{name_, line_}, what);
        if (element_)
            failAt(FileLoc{name_}, element_->name + " " + std::to_string(index_) + " (byte " + std::to_string(pos_) +
                                       "): " + what);
        failAt(FileLoc{name_}, what);
    }

    // Before reading `count` elements of `e`: the bytes left can hold them (nothing is allocated
    // for counts the file cannot back).
    void checkRoom(const Element& e) const {
        const uint64_t left = bytes_.size() - pos_;
        // ASCII: at least one character and a separator per value.
        const uint64_t each = format_ == Format::Ascii ? 2 * std::max<uint64_t>(e.properties.size(), 1) : e.minBinaryBytes();
        const uint64_t room = format_ == Format::Ascii ? (left + 1) / each : left / std::max<uint64_t>(each, 1);
        if (each > 0 && e.count > room)
            failAt(FileLoc{name_, e.line}, std::to_string(e.count) + " " + e.name + " elements of at least " +
                                               std::to_string(each) + " bytes, but only " + std::to_string(left) +
                                               " bytes of data follow (the header does not match the data)");
    }

    double value(Type type) {
        return format_ == Format::Ascii ? asciiValue(type) : binaryValue(type);
    }

    // The end of the data: nothing but (ASCII) white space may follow.
    void finish() {
        if (format_ == Format::Ascii) {
            skipSpace();
            if (pos_ < bytes_.size()) fail("data after the last element (the header does not match the data)");
        } else if (pos_ != bytes_.size()) {
            fail(std::to_string(bytes_.size() - pos_) + " bytes after the last element (the header does not match the data)");
        }
    }

    void setPlace(const Element& e, uint64_t index) {
        element_ = &e;
        index_ = index;
    }

  private:
    void skipSpace() {
        while (pos_ < bytes_.size()) {
            const char c = bytes_[pos_];
            if (c == '\n') ++line_;
            else if (c != ' ' && c != '\t' && c != '\r') break;
            ++pos_;
        }
    }

    double asciiValue(Type type) {
        skipSpace();
        if (pos_ >= bytes_.size()) fail("the data ends early (the header declares more)");
        const size_t start = pos_;
        while (pos_ < bytes_.size() && !std::strchr(" \t\r\n", bytes_[pos_])) ++pos_;
        const char* first = bytes_.data() + start;
        const char* last = bytes_.data() + pos_;
        if (isInteger(type)) {
            long long v = 0;
            const auto [p, ec] = std::from_chars(first, last, v);
            if (ec != std::errc() || p != last) fail(shown(std::string_view(first, size_t(last - first))) + " is not an integer");
            if (!fits(type, double(v))) fail(std::to_string(v) + " does not fit its property's type");
            return double(v);
        }
        double v = 0;
        const auto [p, ec] = std::from_chars(first, last, v);
        if ((ec != std::errc() && ec != std::errc::result_out_of_range) || p != last)
            fail(shown(std::string_view(first, size_t(last - first))) + " is not a number");
        if (ec == std::errc::result_out_of_range) fail(shown(std::string_view(first, size_t(last - first))) + " is out of range");
        return type == Type::Float32 ? double(float(v)) : v;
    }

    double binaryValue(Type type) {
        const size_t n = sizeOf(type);
        if (bytes_.size() - pos_ < n) fail("the data ends early (the header declares more)");
        unsigned char b[8];
        std::memcpy(b, bytes_.data() + pos_, n);
        pos_ += n;
        if ((format_ == Format::Big) == (std::endian::native == std::endian::little)) std::reverse(b, b + n);
        switch (type) {
            case Type::Int8: return double(std::bit_cast<int8_t>(b[0]));
            case Type::UInt8: return double(b[0]);
            case Type::Int16: { int16_t v; std::memcpy(&v, b, 2); return double(v); }
            case Type::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return double(v); }
            case Type::Int32: { int32_t v; std::memcpy(&v, b, 4); return double(v); }
            case Type::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return double(v); }
            case Type::Float32: { float v; std::memcpy(&v, b, 4); return double(v); }
            case Type::Float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0;
    }

    std::string_view bytes_;
    Format format_;
    size_t pos_;
    size_t line_;
    const std::string& name_;
    const Element* element_ = nullptr;
    uint64_t index_ = 0;
};

// The index of the property called one of `names` in e, or -1.
int propertyIndex(const Element& e, std::initializer_list<const char*> names) {
    for (size_t k = 0; k < e.properties.size(); ++k)
        for (const char* n : names)
            if (e.properties[k].name == n) return int(k);
    return -1;
}

// Where the mesh is in the elements: the vertex element with its x, y, z (and nx, ny, nz, and
// red, green, blue) properties, the face element, if any, with its list of vertex indices, and the
// tristrips element, if any, with its strips.
struct MeshLayout {
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    const Element* strips = nullptr;
    int position[3] = {-1, -1, -1};  // property indices in vertex
    int normal[3] = {-1, -1, -1};    // all -1 without normals
    bool hasNormals = false;
    int color[3] = {-1, -1, -1};  // red, green, blue; all -1 unless the vertex has all three
    bool hasColors = false;
    int indices = -1;       // property index in face
    int stripIndices = -1;  // property index in strips
};

// A list property of integers called vertex_indices (or vertex_index) in e: its index.
int indexList(const Element& e, const std::string& name) {
    const int indices = propertyIndex(e, {"vertex_indices", "vertex_index"});
    if (indices < 0) failAt(FileLoc{name}, "the " + e.name + " element has no vertex_indices list");
    const Property& p = e.properties[size_t(indices)];
    if (!p.list || !isInteger(p.type))
        failAt(FileLoc{name}, "the " + e.name + " property " + p.name + " is not a list of integers");
    return indices;
}

MeshLayout meshLayout(const Header& header, const std::string& name) {
    auto fail = [&](const std::string& what) { failAt(FileLoc{name}, what); };
    MeshLayout layout;
    for (const Element& e : header.elements) {
        if (e.name == "vertex") layout.vertex = &e;
        if (e.name == "face") layout.face = &e;
        if (e.name == "tristrips") layout.strips = &e;
    }
    const Element* vertex = layout.vertex;
    if (!vertex) fail("no vertex element");
    for (int a = 0; a < 3; ++a) {
        const char* axis[] = {"x", "y", "z"};
        const char* naxis[] = {"nx", "ny", "nz"};
        const char* channel[] = {"red", "green", "blue"};
        layout.position[a] = propertyIndex(*vertex, {axis[a]});
        layout.normal[a] = propertyIndex(*vertex, {naxis[a]});
        layout.color[a] = propertyIndex(*vertex, {channel[a]});
        if (layout.position[a] < 0) fail(std::string("line ") + std::to_string(vertex->line) + ": the vertex element has no property " + axis[a]);
        if (vertex->properties[size_t(layout.position[a])].list) fail(std::string("the vertex property ") + axis[a] + " is a list");
    }
    const int* normal = layout.normal;
    layout.hasNormals = normal[0] >= 0 || normal[1] >= 0 || normal[2] >= 0;
    if (layout.hasNormals && (normal[0] < 0 || normal[1] < 0 || normal[2] < 0))
        fail("the vertex element has some of nx, ny, nz but not all three");
    // Colours need all three channels, none a list; otherwise they are reported unused.
    layout.hasColors = true;
    for (int c : layout.color) layout.hasColors = layout.hasColors && c >= 0 && !vertex->properties[size_t(c)].list;
    if (!layout.hasColors) std::fill(layout.color, layout.color + 3, -1);
    if (layout.face) layout.indices = indexList(*layout.face, name);
    if (layout.strips) layout.stripIndices = indexList(*layout.strips, name);
    return layout;
}

// The properties and elements gpurt reads past (CONTRACT.md: nothing is dropped silently), for one
// warning: "vertex confidence, face flags, element edge". The vertex's s, t, u, v and alpha are
// left out of it, as the brief of the reader says: they are common and carry nothing gpurt shows.
std::string unusedParts(const Header& header, const MeshLayout& layout) {
    std::string unused;
    auto add = [&](const std::string& what) { unused += (unused.empty() ? "" : ", ") + what; };
    for (const Element& e : header.elements) {
        if (&e != layout.vertex && &e != layout.face && &e != layout.strips) {
            add("element " + e.name);
            continue;
        }
        for (size_t k = 0; k < e.properties.size(); ++k) {
            const int i = int(k);
            const std::string& n = e.properties[k].name;
            bool used = false;
            if (&e == layout.vertex) {
                for (int a = 0; a < 3; ++a)
                    used = used || i == layout.position[a] || i == layout.normal[a] || i == layout.color[a];
                used = used || n == "s" || n == "t" || n == "u" || n == "v" || n == "alpha";
            }
            if (&e == layout.face) used = i == layout.indices;
            if (&e == layout.strips) used = i == layout.stripIndices;
            if (!used) add(e.name + " " + n);
        }
    }
    return unused;
}

// The mesh's values as the data gives them (the indices not yet checked).
struct MeshData {
    std::vector<glm::vec3> positions, normals, colors;
    std::vector<uint32_t> faceSizes;
    std::vector<double> faceIndices;   // every face's, one face after another
    std::vector<double> stripIndices;  // every tristrips element's list, one after another (-1: restart)
};

// A colour channel of type `type` as an sRGB-encoded value in [0, 1]: integers over the largest of
// their type, floats as they are (negative values 0).
float colorChannel(double v, Type type) {
    double scale = 1.0;
    switch (type) {
        case Type::Int8: scale = 127.0; break;
        case Type::UInt8: scale = 255.0; break;
        case Type::Int16: scale = 32767.0; break;
        case Type::UInt16: scale = 65535.0; break;
        case Type::Int32: scale = 2147483647.0; break;
        case Type::UInt32: scale = 4294967295.0; break;
        default: break;
    }
    return std::clamp(float(v / scale), 0.0f, 1.0f);
}

// Element i of e: the face's and strips' indices and the vertex's coordinates, normal and colour
// are kept, other values read and dropped.
void readElement(DataReader& in, const Element& e, uint64_t i, const MeshLayout& layout, MeshData& data) {
    const bool isVertex = &e == layout.vertex, isFace = &e == layout.face, isStrips = &e == layout.strips;
    in.setPlace(e, i);
    for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (p.list) {
            const double n = in.value(p.countType);
            if (n < 0) in.fail("a list of " + std::to_string(int64_t(n)) + " items");
            if (isFace && int(k) == layout.indices) {
                if (n < 3) in.fail("a face of " + std::to_string(int64_t(n)) + " vertices; a face needs at least 3");
                data.faceSizes.push_back(uint32_t(n));
                for (double j = 0; j < n; ++j) data.faceIndices.push_back(in.value(p.type));
            } else if (isStrips && int(k) == layout.stripIndices) {
                data.stripIndices.push_back(-1.0);  // each list starts a strip
                for (double j = 0; j < n; ++j) data.stripIndices.push_back(in.value(p.type));
            } else {
                for (double j = 0; j < n; ++j) in.value(p.type);
            }
            continue;
        }
        const double v = in.value(p.type);
        if (!isVertex) continue;
        for (int a = 0; a < 3; ++a) {
            if (int(k) == layout.position[a]) {
                if (!std::isfinite(float(v))) in.fail("vertex coordinate is not a finite float");
                data.positions[size_t(i)][a] = float(v);
            }
            if (int(k) == layout.normal[a]) {
                if (!std::isfinite(float(v))) in.fail("normal component is not a finite float");
                data.normals[size_t(i)][a] = float(v);
            }
            if (int(k) == layout.color[a]) {
                if (!std::isfinite(float(v))) in.fail("colour component is not a finite float");
                data.colors[size_t(i)][a] = colorChannel(v, p.type);
            }
        }
    }
}

// The data, element by element in header order; each element's count is checked against the
// bytes left before anything is sized by it.
MeshData readData(std::string_view bytes, const Header& header, const MeshLayout& layout, const std::string& name) {
    MeshData data;
    DataReader in(bytes, header, name);
    for (const Element& e : header.elements) {
        in.checkRoom(e);
        if (&e == layout.vertex) {
            data.positions.resize(size_t(e.count));
            if (layout.hasNormals) data.normals.resize(size_t(e.count));
            if (layout.hasColors) data.colors.resize(size_t(e.count));
        }
        if (e.properties.empty()) continue;  // elements of nothing take no bytes
        for (uint64_t i = 0; i < e.count; ++i) readElement(in, e, i, layout, data);
    }
    in.finish();
    return data;
}

// Builds the scene's triangles from vertex indices, each checked against the vertices; the
// vertex colours are sRGB-decoded to linear once here.
class TriangleBuilder {
  public:
    TriangleBuilder(const MeshData& data, bool hasNormals, bool hasColors, const std::string& name, Scene& scene)
        : data_(data), hasNormals_(hasNormals), name_(name), scene_(scene) {
        if (!hasColors) return;
        linearColors_.resize(data.colors.size());
        for (size_t v = 0; v < data.colors.size(); ++v)
            for (int c = 0; c < 3; ++c) linearColors_[v][c] = decodeSrgb(data.colors[v][c]);
    }

    // Index `index` of `what`, checked: a vertex.
    size_t vertex(double index, const std::string& what) const {
        if (index < 0 || index >= double(data_.positions.size()))
            failAt(FileLoc{name_}, what + ": vertex index " + std::to_string(int64_t(index)) + " is out of range (" +
                                       std::to_string(data_.positions.size()) + " vertices)");
        return size_t(index);
    }

    void add(size_t a, size_t b, size_t c) {
        const std::vector<glm::vec3>& p = data_.positions;
        scene_.triangles.push_back({p[a], p[b], p[c]});
        scene_.materialIds.push_back(0);
        if (hasNormals_) scene_.normals.push_back({data_.normals[a], data_.normals[b], data_.normals[c]});
        if (!linearColors_.empty()) scene_.colors.push_back({linearColors_[a], linearColors_[b], linearColors_[c]});
    }

    // The faces as triangle fans around their first vertex.
    void faces() {
        size_t at = 0;
        for (size_t f = 0; f < data_.faceSizes.size(); ++f) {
            const size_t n = data_.faceSizes[f];
            const std::string what = "face " + std::to_string(f);
            for (size_t j = 0; j < n; ++j) vertex(data_.faceIndices[at + j], what);
            const auto v = [&](size_t j) { return size_t(data_.faceIndices[at + j]); };
            for (size_t j = 1; j + 1 < n; ++j) add(v(0), v(j), v(j + 1));
            at += n;
        }
    }

    // The strips (-1 restarts one; each tristrips element's list starts one): triangle k of a strip
    // is (s_k, s_k+1, s_k+2) for even k and (s_k+1, s_k, s_k+2) for odd k, OpenGL's order, which
    // keeps the winding. A triangle with a vertex twice (the turns a strip makes to go on) is
    // skipped, but counts for the alternation.
    void strips() {
        const std::vector<double>& s = data_.stripIndices;
        size_t strip = 0, k = 0;  // k: the triangle's place in its strip
        for (size_t i = 0; i < s.size(); ++i) {
            if (s[i] == -1.0) {
                if (i > 0 && s[i - 1] != -1.0) ++strip;
                k = 0;
                continue;
            }
            vertex(s[i], "triangle strip " + std::to_string(strip));
            if (i < 2 || s[i - 1] == -1.0 || s[i - 2] == -1.0) continue;
            const size_t a = size_t(s[i - 2]), b = size_t(s[i - 1]), c = size_t(s[i]);
            if (a != b && b != c && a != c) {
                if (k % 2 == 0) add(a, b, c);
                else add(b, a, c);
            }
            ++k;
        }
    }

  private:
    const MeshData& data_;
    bool hasNormals_;
    const std::string& name_;
    Scene& scene_;
    std::vector<glm::vec3> linearColors_;
};

// The faces and strips, in the order of their elements; one default material.
Scene meshScene(const MeshData& data, const MeshLayout& layout, const std::string& name) {
    Scene scene;
    scene.materials.push_back(Material{});
    TriangleBuilder build(data, layout.hasNormals, layout.hasColors, name, scene);
    const bool stripsFirst = layout.strips && (!layout.face || layout.strips < layout.face);
    if (stripsFirst) build.strips();
    build.faces();
    if (!stripsFirst) build.strips();
    return scene;
}

// ---- The ASCII data on all cores ----
// The common layout of an ASCII PLY: one element a line, in header order. The data is cut into
// chunks at line starts; the workers count each chunk's lines, then read each line as the element
// its number says (vertices straight into their place, faces into the chunk's lists), then write
// the faces' triangles at the offsets the chunks' counts give. A file this cannot read exactly as
// the serial reader would without complaint (a blank line or an element over two lines, a value
// or face the serial reader refuses, an index out of range, strips) is read again by the serial
// reader, which then gives its triangles or its error: the two agree on every file.

// The text's value as the serial reader's asciiValue reads it; false where that would refuse it.
bool asciiNumber(const char* first, const char* last, Type type, double& out) {
    if (isInteger(type)) {
        long long v = 0;
        const auto [p, ec] = std::from_chars(first, last, v);
        if (ec != std::errc() || p != last || !fits(type, double(v))) return false;
        out = double(v);
        return true;
    }
    double v = 0;
    if (!parseDecimal(first, last, v)) return false;
    out = type == Type::Float32 ? double(float(v)) : v;
    return true;
}

bool isLineSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// The next value of the line [p, end) as `type`; false at the line's end or for a refused value.
bool nextValue(const char*& p, const char* end, Type type, double& out) {
    while (p < end && isLineSpace(*p)) ++p;
    if (p == end) return false;
    const char* first = p;
    while (p < end && !isLineSpace(*p)) ++p;
    return asciiNumber(first, p, type, out);
}

struct AsciiChunk {
    size_t begin = 0, end = 0;  // bytes; begin is a line's start
    size_t firstLine = 0, lines = 0;
    std::vector<uint32_t> faceSizes, faceIndices;
    size_t triangles = 0, firstTriangle = 0;
};

class ParallelAsciiReader {
  public:
    ParallelAsciiReader(std::string_view bytes, const Header& header, const MeshLayout& layout, const PlyReadOptions& options)
        : bytes_(bytes), header_(header), layout_(layout), threads_(resolveThreads(options.threads)),
          chunkBytes_(std::max<size_t>(1, options.chunkBytes)) {}

    std::optional<Scene> read() {
        if (layout_.strips) return std::nullopt;
        cutChunks();
        size_t lines = 0;
        for (AsciiChunk& c : chunks_) {
            c.firstLine = lines;
            lines += c.lines;
        }
        // Each element with properties takes one line (those without take no bytes).
        size_t expected = 0;
        for (const Element& e : header_.elements) {
            if (e.properties.empty()) continue;
            if (e.count > bytes_.size()) return std::nullopt;  // more lines than bytes: the serial reader says so
            firstLine_.push_back({&e, expected});
            expected += size_t(e.count);
        }
        if (lines < expected) return std::nullopt;  // the serial reader says where the data ends
        expectedLines_ = expected;
        vertexCount_ = size_t(layout_.vertex->count);
        positions_.resize(vertexCount_);
        if (layout_.hasNormals) normals_.resize(vertexCount_);
        if (layout_.hasColors) colors_.resize(vertexCount_);
        std::atomic<bool> ok{true};
        parallelChunks(chunks_.size(), 1, threads_, [&](size_t c, size_t, size_t) {
            if (ok && !readChunk(chunks_[c])) ok = false;
        });
        if (!ok) return std::nullopt;
        return scene();
    }

  private:
    void cutChunks() {
        const size_t size = bytes_.size();
        for (size_t begin = header_.dataStart; begin < size;) {
            size_t end = std::min(size, begin + chunkBytes_);
            if (end < size) {
                const void* nl = std::memchr(bytes_.data() + end - 1, '\n', size - (end - 1));
                end = nl ? size_t(static_cast<const char*>(nl) - bytes_.data()) + 1 : size;
            }
            AsciiChunk chunk;
            chunk.begin = begin;
            chunk.end = end;
            chunks_.push_back(std::move(chunk));
            begin = end;
        }
        parallelChunks(chunks_.size(), 1, threads_, [&](size_t c, size_t, size_t) {
            AsciiChunk& chunk = chunks_[c];
            const char* p = bytes_.data() + chunk.begin;
            const char* end = bytes_.data() + chunk.end;
            size_t lines = 0;
            while (const void* nl = std::memchr(p, '\n', size_t(end - p))) {
                ++lines;
                p = static_cast<const char*>(nl) + 1;
            }
            chunk.lines = lines + (p < end ? 1 : 0);  // a last line without its line end
        });
    }

    bool readChunk(AsciiChunk& chunk) {
        const char* p = bytes_.data() + chunk.begin;
        const char* end = bytes_.data() + chunk.end;
        size_t line = chunk.firstLine;
        size_t element = std::upper_bound(firstLine_.begin(), firstLine_.end(), line,
                                          [](size_t l, const auto& f) { return l < f.second; }) - firstLine_.begin();
        while (p < end) {
            const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
            const char* lineEnd = nl ? nl : end;
            if (line < expectedLines_) {
                while (element < firstLine_.size() && line >= firstLine_[element].second) ++element;
                const auto& [e, first] = firstLine_[element - 1];
                if (!readLine(p, lineEnd, *e, line - first, chunk)) return false;
            } else {
                for (const char* q = p; q < lineEnd; ++q)
                    if (!isLineSpace(*q)) return false;  // data after the last element
            }
            ++line;
            p = nl ? nl + 1 : end;
        }
        return true;
    }

    // One line as element i of e; false where it is not exactly that, read without complaint.
    bool readLine(const char* p, const char* end, const Element& e, size_t i, AsciiChunk& chunk) {
        const bool isVertex = &e == layout_.vertex, isFace = &e == layout_.face;
        double v = 0;
        for (size_t k = 0; k < e.properties.size(); ++k) {
            const Property& prop = e.properties[k];
            if (prop.list) {
                if (!nextValue(p, end, prop.countType, v) || v < 0) return false;
                const size_t n = size_t(v);
                if (isFace && int(k) == layout_.indices) {
                    if (n < 3) return false;
                    chunk.faceSizes.push_back(uint32_t(n));
                    chunk.triangles += n - 2;
                    for (size_t j = 0; j < n; ++j) {
                        if (!nextValue(p, end, prop.type, v) || !(v >= 0) || v >= double(vertexCount_)) return false;
                        chunk.faceIndices.push_back(uint32_t(v));
                    }
                } else {
                    for (size_t j = 0; j < n; ++j)
                        if (!nextValue(p, end, prop.type, v)) return false;
                }
                continue;
            }
            if (!nextValue(p, end, prop.type, v)) return false;
            if (!isVertex) continue;
            for (int a = 0; a < 3; ++a) {
                if (int(k) == layout_.position[a]) {
                    if (!std::isfinite(float(v))) return false;
                    positions_[i][a] = float(v);
                }
                if (int(k) == layout_.normal[a]) {
                    if (!std::isfinite(float(v))) return false;
                    normals_[i][a] = float(v);
                }
                if (int(k) == layout_.color[a]) {
                    if (!std::isfinite(float(v))) return false;
                    colors_[i][a] = colorChannel(v, prop.type);
                }
            }
        }
        for (; p < end; ++p)
            if (!isLineSpace(*p)) return false;  // more values than the element has
        return true;
    }

    // The faces' triangles (fans around their first vertex), as TriangleBuilder makes them.
    Scene scene() {
        Scene scene;
        scene.materials.push_back(Material{});
        if (layout_.hasColors)
            parallelChunks(colors_.size(), 65536, threads_, [&](size_t begin, size_t end, size_t) {
                for (size_t v = begin; v < end; ++v)
                    for (int c = 0; c < 3; ++c) colors_[v][c] = decodeSrgb(colors_[v][c]);
            });
        size_t triangles = 0;
        for (AsciiChunk& c : chunks_) {
            c.firstTriangle = triangles;
            triangles += c.triangles;
        }
        scene.triangles.resize(triangles);
        scene.materialIds.resize(triangles);
        if (layout_.hasNormals) scene.normals.resize(triangles);
        if (layout_.hasColors) scene.colors.resize(triangles);
        parallelChunks(chunks_.size(), 1, threads_, [&](size_t c, size_t, size_t) {
            const AsciiChunk& chunk = chunks_[c];
            size_t t = chunk.firstTriangle, at = 0;
            for (const uint32_t n : chunk.faceSizes) {
                const uint32_t* v = chunk.faceIndices.data() + at;
                for (size_t j = 1; j + 1 < n; ++j, ++t) {
                    const uint32_t a = v[0], b = v[j], d = v[j + 1];
                    scene.triangles[t] = {positions_[a], positions_[b], positions_[d]};
                    scene.materialIds[t] = 0;
                    if (layout_.hasNormals) scene.normals[t] = {normals_[a], normals_[b], normals_[d]};
                    if (layout_.hasColors) scene.colors[t] = {colors_[a], colors_[b], colors_[d]};
                }
                at += n;
            }
        });
        return scene;
    }

    std::string_view bytes_;
    const Header& header_;
    const MeshLayout& layout_;
    int threads_;
    size_t chunkBytes_;
    std::vector<AsciiChunk> chunks_;
    std::vector<std::pair<const Element*, size_t>> firstLine_;  // elements with properties: their first line
    size_t expectedLines_ = 0, vertexCount_ = 0;
    LargeArray<glm::vec3> positions_, normals_, colors_;
};

Scene parsePlyBytes(std::string_view bytes, const std::string& name, const PlyReadOptions& options) {
    const Header header = readHeader(bytes, name);
    const MeshLayout layout = meshLayout(header, name);
    std::optional<Scene> fast;
    if (header.format == Format::Ascii && options.parallel) fast = ParallelAsciiReader(bytes, header, layout, options).read();
    Scene scene = fast ? std::move(*fast) : meshScene(readData(bytes, header, layout, name), layout, name);
    if (const std::string unused = unusedParts(header, layout); !unused.empty())
        warnAt(FileLoc{name}, "not used: " + unused);
    if (scene.triangles.empty())
        warnAt(FileLoc{name}, std::string("no triangles (") +
                                  (layout.face || layout.strips ? "its faces and strips make none"
                                                                : "no face or tristrips element: a point cloud?") +
                                  "): nothing to render");
    return scene;
}

}  // namespace

bool looksLikePly(const std::string& head) {
    return head.compare(0, 4, "ply\n") == 0 || head.compare(0, 5, "ply\r\n") == 0;
}

Scene parsePly(const std::string& bytes, const std::string& name, const PlyReadOptions& options) {
    return parsePlyBytes(bytes, name, options);
}

Scene loadPly(const std::filesystem::path& path) {
    const LargeArray<char> bytes = readSceneBytes(path);
    return parsePlyBytes(std::string_view(bytes.data(), bytes.size()), path.string(), PlyReadOptions{});
}

}  // namespace gpurt
