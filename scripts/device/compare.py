#!/usr/bin/env python3
"""Compares each PNG in GOT_DIR with the PNG of the same name in REF_DIR (8-bit RGB/RGBA).

  compare.py REF_DIR GOT_DIR

Prints one line per image: mean and max absolute difference over the RGB channels (0-255 scale),
the fraction of pixels whose largest channel difference is > 1 and > 8, and the mean of each image.
Uses numpy + PIL when importable, else a pure-Python PNG decoder (slow but dependency-free).
"""
import os
import struct
import sys
import zlib


def decode_png_pure(path):
    """Returns (width, height, channels, bytes) of an 8-bit non-interlaced PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, hdr = 8, [], None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            hdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    w, h, depth, ctype, _, _, interlace = hdr
    if depth != 8 or interlace:
        raise ValueError("only 8-bit non-interlaced PNGs")
    ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(b"".join(idat))
    stride = w * ch
    out = bytearray(h * stride)
    prev = bytearray(stride)
    p = 0
    for y in range(h):
        ft = raw[p]
        line = bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        if ft == 1:
            for i in range(ch, stride):
                line[i] = (line[i] + line[i - ch]) & 255
        elif ft == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif ft == 3:
            for i in range(stride):
                a = line[i - ch] if i >= ch else 0
                line[i] = (line[i] + ((a + prev[i]) >> 1)) & 255
        elif ft == 4:
            for i in range(stride):
                a = line[i - ch] if i >= ch else 0
                b = prev[i]
                c = prev[i - ch] if i >= ch else 0
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                pr = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                line[i] = (line[i] + pr) & 255
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return w, h, ch, bytes(out)


def compare_pure(ref, got):
    w1, h1, c1, a = decode_png_pure(ref)
    w2, h2, c2, b = decode_png_pure(got)
    if (w1, h1) != (w2, h2):
        return "size differs: ref %dx%d, got %dx%d" % (w1, h1, w2, h2)
    total = mx = n1 = n8 = 0
    sa = sb = 0
    for i in range(w1 * h1):
        m = 0
        for k in range(3):
            x, y = a[i * c1 + k], b[i * c2 + k]
            d = abs(x - y)
            total += d
            sa += x
            sb += y
            if d > m:
                m = d
        if m > mx:
            mx = m
        n1 += m > 1
        n8 += m > 8
    n = w1 * h1
    return "mean_abs %.6f max_abs %d frac>1 %.5f frac>8 %.5f mean_ref %.2f mean_got %.2f (%dx%d, pure python)" % (
        total / (3.0 * n), mx, n1 / n, n8 / n, sa / (3.0 * n), sb / (3.0 * n), w1, h1)


def compare_numpy(ref, got):
    import numpy as np
    from PIL import Image
    a = np.asarray(Image.open(ref).convert("RGB"), dtype=np.int16)
    b = np.asarray(Image.open(got).convert("RGB"), dtype=np.int16)
    if a.shape != b.shape:
        return "size differs: ref %s, got %s" % (a.shape, b.shape)
    d = np.abs(a - b)
    m = d.max(axis=2)
    return "mean_abs %.6f max_abs %d frac>1 %.5f frac>8 %.5f mean_ref %.2f mean_got %.2f (%dx%d, numpy)" % (
        d.mean(), d.max(), (m > 1).mean(), (m > 8).mean(), a.mean(), b.mean(), a.shape[1], a.shape[0])


def main():
    ref_dir, got_dir = sys.argv[1], sys.argv[2]
    try:
        import numpy  # noqa: F401
        from PIL import Image  # noqa: F401
        fast = True
    except ImportError:
        fast = False

    def compare(ref, got):
        if fast:
            try:
                return compare_numpy(ref, got)
            except Exception as e:  # fall back to the pure decoder
                print("compare: numpy path failed (%s), pure python instead" % e)
        return compare_pure(ref, got)
    names = sorted(n for n in os.listdir(got_dir) if n.endswith(".png"))
    if not names:
        print("compare: no PNGs in", got_dir)
    for name in names:
        ref = os.path.join(ref_dir, name)
        if not os.path.exists(ref):
            print("compare %-40s no reference" % name)
            continue
        try:
            print("compare %-40s %s" % (name, compare(ref, os.path.join(got_dir, name))))
        except Exception as e:  # one bad image must not stop the others
            print("compare %-40s error: %s" % (name, e))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
