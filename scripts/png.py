"""8-bit RGB PNG files for the scripts (crops and side-by-side pictures), standard library only."""
import struct
import zlib


def read_png(path):
    """(width, height, rows): rows top first, each bytes of R, G, B (an alpha channel is dropped)."""
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        kind, chunk = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", chunk[:10])
            if depth != 8 or colour not in (2, 6):
                raise ValueError(f"{path}: not an 8-bit RGB or RGBA PNG")
        elif kind == b"IDAT":
            idat += chunk
    raw = zlib.decompress(idat)
    bpp = 3 if colour == 2 else 4
    stride = w * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        kind = raw[i]
        line = bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if bpp == 3 else bytes(v for k, v in enumerate(line) if k % 4 != 3))
        prev = line
    return w, h, rows


def write_png(path, w, h, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + r for r in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def crop(image, x, y, w, h):
    return w, h, [row[3 * x:3 * (x + w)] for row in image[2][y:y + h]]


def side_by_side(images, gap=4):
    """The images in a row, top-aligned, `gap` white pixels apart."""
    h = max(i[1] for i in images)
    w = sum(i[0] for i in images) + gap * (len(images) - 1)
    rows = []
    for y in range(h):
        parts = []
        for k, (iw, ih, r) in enumerate(images):
            parts.append(r[y] if y < ih else b"\xff" * (3 * iw))
            if k + 1 < len(images):
                parts.append(b"\xff" * (3 * gap))
        rows.append(b"".join(parts))
    return w, h, rows
