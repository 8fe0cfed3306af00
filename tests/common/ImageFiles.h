// BMP and TGA files written here, byte by byte from their specifications (Microsoft's
// BITMAPFILEHEADER and BITMAPINFOHEADER; Truevision's TGA 2.0), for the tests of the texture
// readers: the reader under test is stb_image, so the files must not come from it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gpurt::test {

inline void putLittleEndian(std::string& out, uint32_t v, int bytes) {
    for (int k = 0; k < bytes; ++k) out += char((v >> (8 * k)) & 0xffu);
}

// An uncompressed BMP of `rgba` (width x height texels, r g b a bytes, top row first): 24 bits a
// pixel (alpha dropped) or 32 (BGRA), rows bottom first, each padded to 4 bytes.
inline std::string bmpOf(int width, int height, int bits, const std::vector<unsigned char>& rgba) {
    const uint32_t row = uint32_t((width * bits + 31) / 32 * 4);
    const uint32_t pixels = row * uint32_t(height);
    std::string out = "BM";
    putLittleEndian(out, 14 + 40 + pixels, 4);  // file size
    putLittleEndian(out, 0, 4);                 // reserved
    putLittleEndian(out, 14 + 40, 4);           // offset of the pixels
    putLittleEndian(out, 40, 4);                // BITMAPINFOHEADER
    putLittleEndian(out, uint32_t(width), 4);
    putLittleEndian(out, uint32_t(height), 4);  // positive: bottom row first
    putLittleEndian(out, 1, 2);                 // planes
    putLittleEndian(out, uint32_t(bits), 2);
    putLittleEndian(out, 0, 4);  // BI_RGB
    putLittleEndian(out, pixels, 4);
    for (int k = 0; k < 4; ++k) putLittleEndian(out, k < 2 ? 2835 : 0, 4);  // 72 dpi, palette sizes
    for (int y = height - 1; y >= 0; --y) {
        const size_t start = out.size();
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
            out += char(p[2]);
            out += char(p[1]);
            out += char(p[0]);
            if (bits == 32) out += char(p[3]);
        }
        out.append(row - (out.size() - start), '\0');
    }
    return out;
}

// A true-colour TGA of `rgba` (as bmpOf), 24 or 32 bits a pixel (BGR(A)), the top row first
// (descriptor bit 5) or the bottom row first, uncompressed (type 2) or run-length encoded (type 10:
// runs of equal pixels as run packets, the rest as raw packets, at most 128 pixels a packet and
// never across a row, as the specification asks).
inline std::string tgaOf(int width, int height, int bits, bool topFirst, bool rle, const std::vector<unsigned char>& rgba) {
    std::string out;
    out += char(0);            // no image id
    out += char(0);            // no colour map
    out += char(rle ? 10 : 2);  // true colour
    out.append(5, '\0');       // colour map specification
    putLittleEndian(out, 0, 2);  // x origin
    putLittleEndian(out, 0, 2);  // y origin
    putLittleEndian(out, uint32_t(width), 2);
    putLittleEndian(out, uint32_t(height), 2);
    out += char(bits);
    out += char((bits == 32 ? 8 : 0) | (topFirst ? 0x20 : 0));  // alpha bits, origin
    auto pixel = [&](int x, int y) {
        const unsigned char* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
        std::string b{char(p[2]), char(p[1]), char(p[0])};
        if (bits == 32) b += char(p[3]);
        return b;
    };
    for (int r = 0; r < height; ++r) {
        const int y = topFirst ? r : height - 1 - r;
        if (!rle) {
            for (int x = 0; x < width; ++x) out += pixel(x, y);
            continue;
        }
        int x = 0;
        while (x < width) {
            int run = 1;
            while (x + run < width && run < 128 && pixel(x + run, y) == pixel(x, y)) ++run;
            if (run > 1) {
                out += char(0x80 | (run - 1));
                out += pixel(x, y);
                x += run;
                continue;
            }
            int raw = 1;  // up to the next run of two equal pixels
            while (x + raw < width && raw < 128 && !(x + raw + 1 < width && pixel(x + raw, y) == pixel(x + raw + 1, y))) ++raw;
            out += char(raw - 1);
            for (int k = 0; k < raw; ++k) out += pixel(x + k, y);
            x += raw;
        }
    }
    return out;
}

}  // namespace gpurt::test
