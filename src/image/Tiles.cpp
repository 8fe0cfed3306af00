#include "image/Tiles.h"

#include "image/AtomicFile.h"
#include "image/ExrIO.h"
#include "image/ImageIO.h"
#include "image/InputError.h"

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

namespace gpurt {

std::filesystem::path tileSidecar(const std::filesystem::path& file) { return file.string() + ".tile"; }

uint32_t crc32Of(const void* data, size_t bytes, uint32_t crc) {
    const auto* p = static_cast<const unsigned char*>(data);
    while (bytes > 0) {  // zlib takes lengths as uInt
        const uInt n = uInt(std::min<size_t>(bytes, 1u << 30));
        crc = uint32_t(crc32(crc, p, n));
        p += n;
        bytes -= n;
    }
    return crc;
}

void addTileSidecar(AtomicFileSet& files, const std::filesystem::path& file, const TileInfo& t) {
    nlohmann::json j;
    j["gpurt_tile"] = 1;
    j["output"] = t.output;
    j["tile"] = t.tile;
    j["tiles"] = t.tiles;
    j["width"] = t.width;
    j["height"] = t.height;
    j["row"] = t.row;
    j["rows"] = t.rows;
    j["fingerprint"] = t.fingerprint;
    j["crc32"] = t.crc;
    const std::string text = j.dump(1) + "\n";
    files.add(tileSidecar(file), [&](std::FILE* f) {
        if (std::fwrite(text.data(), 1, text.size(), f) != text.size())
            throw InputError(tileSidecar(file).string() + ": cannot write");
    });
}

namespace {

TileInfo readSidecar(const std::filesystem::path& tile) {
    const std::filesystem::path side = tileSidecar(tile);
    std::ifstream in(side, std::ios::binary);
    if (!in) throw InputError(tile.string() + ": not a tile (no " + side.filename().string() + " beside it)");
    std::stringstream text;
    text << in.rdbuf();
    TileInfo t;
    try {
        const nlohmann::json j = nlohmann::json::parse(text.str());
        if (j.at("gpurt_tile").get<int>() != 1) throw std::runtime_error("unknown version");
        t.output = j.at("output").get<std::string>();
        t.tile = j.at("tile").get<int>();
        t.tiles = j.at("tiles").get<int>();
        t.width = j.at("width").get<int>();
        t.height = j.at("height").get<int>();
        t.row = j.at("row").get<int>();
        t.rows = j.at("rows").get<int>();
        t.fingerprint = j.at("fingerprint").get<std::string>();
        t.crc = j.at("crc32").get<uint32_t>();
    } catch (const std::exception& e) {
        throw InputError(side.string() + ": not a tile description (" + e.what() + ")");
    }
    if (t.tiles < 1 || t.tile < 0 || t.tile >= t.tiles || t.width < 1 || t.height < t.tiles || t.row < 0 ||
        t.rows < 1 || t.row + t.rows > t.height)
        throw InputError(side.string() + ": tile " + std::to_string(t.tile) + "/" + std::to_string(t.tiles) +
                         " does not fit its image");
    return t;
}

}  // namespace

void stitchTiles(const std::filesystem::path& output, const std::vector<std::filesystem::path>& tiles) {
    if (tiles.empty()) throw InputError("stitch: no tiles given");
    const std::string ext = output.extension().string();
    const bool png = ext == ".png", exr = ext == ".exr";
    if (!png && !exr && ext != ".pfm") throw InputError(output.string() + ": stitch writes .png, .exr or .pfm");
    checkOutputPath(output);
    TileInfo first;
    std::map<int, std::pair<std::filesystem::path, TileInfo>> byIndex;
    std::vector<unsigned char> rgb;
    std::vector<float> values;
    int channels = 0;
    for (size_t k = 0; k < tiles.size(); ++k) {
        const std::filesystem::path& tile = tiles[k];
        const TileInfo t = readSidecar(tile);
        if (k == 0) first = t;
        if (t.fingerprint != first.fingerprint || t.width != first.width || t.height != first.height ||
            t.tiles != first.tiles || t.output != first.output)
            throw InputError(tile.string() + ": a tile of another image or output than " + tiles[0].string());
        const std::string kind = t.output == "png" ? "PNG" : tile.extension() == ".exr" ? "EXR" : "PFM";
        if (kind != (png ? "PNG" : exr ? "EXR" : "PFM"))
            throw InputError(tile.string() + ": a " + kind + " tile for " + output.string());
        if (!byIndex.emplace(t.tile, std::make_pair(tile, t)).second)
            throw InputError(tile.string() + ": tile " + std::to_string(t.tile) + " given twice (also " +
                             byIndex[t.tile].first.string() + ")");
        if (png) {
            int w = 0, h = 0;
            const std::vector<unsigned char> pixels = readPngRgb8(tile, w, h);
            if (w != t.width || h != t.rows || crc32Of(pixels.data(), pixels.size()) != t.crc)
                throw InputError(tile.string() + ": damaged (its pixels do not match its " +
                                 tileSidecar(tile).filename().string() + ")");
            rgb.resize(size_t(t.width) * size_t(t.height) * 3);
            std::copy(pixels.begin(), pixels.end(), rgb.begin() + std::ptrdiff_t(size_t(t.row) * size_t(t.width) * 3));
        } else {
            int w = 0, h = 0, c = 0;
            std::vector<float> v;
            if (exr) {
                v = readExr(tile, exrLayout(t.output), w, h);
                c = int(exrLayout(t.output).channels.size());
            } else {
                v = readPfm(tile, w, h, c);
            }
            if (w != t.width || h != t.rows || (channels != 0 && c != channels) ||
                crc32Of(v.data(), v.size() * sizeof(float)) != t.crc)
                throw InputError(tile.string() + ": damaged (its values do not match its " +
                                 tileSidecar(tile).filename().string() + ")");
            channels = c;
            values.resize(size_t(t.width) * size_t(t.height) * size_t(c));
            std::copy(v.begin(), v.end(), values.begin() + std::ptrdiff_t(size_t(t.row) * size_t(t.width) * size_t(c)));
        }
    }
    for (int i = 0; i < first.tiles; ++i)
        if (!byIndex.count(i))
            throw InputError("stitch: tile " + std::to_string(i) + "/" + std::to_string(first.tiles) + " of " +
                             tiles[0].string() + "'s image is missing");
    // The tiles' rows must be the balanced bands of --tile: together exactly the image, each once.
    int next = 0;
    for (const auto& [index, entry] : byIndex) {
        const auto& [tile, t] = entry;
        if (t.row != next) throw InputError(tile.string() + ": its rows do not follow the tile before it");
        next = t.row + t.rows;
    }
    if (next != first.height)
        throw InputError(byIndex.rbegin()->second.first.string() + ": the tiles do not cover the image");
    if (png) {
        writePngRgb8(output, first.width, first.height, rgb);
    } else if (exr) {
        AtomicFileSet file;
        writeExr(file, output, first.width, first.height, exrLayout(first.output), values);
        file.commit();
    } else {
        writePfm(output, first.width, first.height, channels, values);
    }
}

void parseFrames(const std::string& text, int& first, int& last) {
    auto number = [&](const std::string& digits) {
        if (digits.empty() || digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos)
            throw InputError("--frames: '" + text + "' is not A:B with 0 <= A <= B <= 999999");
        return std::stoi(digits);
    };
    const size_t colon = text.find(':');
    if (colon == std::string::npos) throw InputError("--frames: '" + text + "' is not A:B");
    first = number(text.substr(0, colon));
    last = number(text.substr(colon + 1));
    if (first > last) throw InputError("--frames: " + text + ": the first frame is after the last");
}

namespace {

// The frame conversion in `pattern`: its position and length, the field width (0: none); throws
// unless there is exactly one and every other '%' is "%%".
struct FrameField {
    size_t at = std::string::npos, length = 0;
    int width = 0;
};

FrameField frameField(const std::string& option, const std::string& pattern) {
    FrameField field;
    auto refuse = [&](const std::string& why) {
        throw InputError(option + ": '" + pattern + "' " + why + " (the frame number as %04d, %d; %% for %)");
    };
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') continue;
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            ++i;
            continue;
        }
        size_t j = i + 1;
        int width = 0;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        if (zero) ++j;
        if (zero && j < pattern.size() && pattern[j] >= '1' && pattern[j] <= '9') width = pattern[j++] - '0';
        if (j >= pattern.size() || pattern[j] != 'd' || (zero && width == 0))
            refuse("has a '%' that is not a frame number");
        if (field.at != std::string::npos) refuse("has more than one frame number");
        field.at = i;
        field.length = j + 1 - i;
        field.width = width;
        i = j;
    }
    if (field.at == std::string::npos) refuse("has no frame number");
    return field;
}

}  // namespace

void checkFramePattern(const std::string& option, const std::string& pattern) { frameField(option, pattern); }

std::string frameFileName(const std::string& pattern, int frame) {
    const FrameField field = frameField("frame pattern", pattern);
    char number[16];
    std::snprintf(number, sizeof number, "%0*d", field.width, frame);
    auto unescape = [](const std::string& text) {
        std::string out;
        for (size_t i = 0; i < text.size(); ++i) {
            out += text[i];
            if (text[i] == '%' && i + 1 < text.size() && text[i + 1] == '%') ++i;
        }
        return out;
    };
    return unescape(pattern.substr(0, field.at)) + number + unescape(pattern.substr(field.at + field.length));
}

}  // namespace gpurt
