#!/usr/bin/env python3
"""Rewrites a binary little-endian PLY file as binary big-endian (the same header otherwise, every
value's bytes reversed), for the big-endian test asset (scripts/make-test-assets.sh). Handles
scalar and list properties of every PLY type; refuses anything else.
    scripts/ply-byteswap.py IN.ply OUT.ply"""
import struct
import sys

SIZES = {"char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2, "int16": 2, "uint16": 2,
         "int": 4, "uint": 4, "int32": 4, "uint32": 4, "float": 4, "float32": 4, "double": 8, "float64": 8}
UNSIGNED = {1: "B", 2: "H", 4: "I"}


def main(src, dst):
    data = open(src, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii")
    if "format binary_little_endian 1.0" not in header:
        sys.exit("ply-byteswap: %s is not binary little endian" % src)
    elements = []
    for line in header.splitlines():
        w = line.split()
        if w and w[0] == "element":
            elements.append((int(w[2]), []))
        elif w and w[0] == "property":
            elements[-1][1].append((SIZES[w[2]], SIZES[w[3]]) if w[1] == "list" else (None, SIZES[w[1]]))
    out = bytearray(header.replace("binary_little_endian", "binary_big_endian").encode("ascii"))
    pos = end
    for count, props in elements:
        for _ in range(count):
            for list_size, size in props:
                n = 1
                if list_size:
                    (n,) = struct.unpack("<" + UNSIGNED[list_size], data[pos:pos + list_size])
                    out += data[pos:pos + list_size][::-1]
                    pos += list_size
                for _ in range(n):
                    out += data[pos:pos + size][::-1]
                    pos += size
    if pos != len(data):
        sys.exit("ply-byteswap: %s has %d bytes after its elements" % (src, len(data) - pos))
    open(dst, "wb").write(bytes(out))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
