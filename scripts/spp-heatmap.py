#!/usr/bin/env python3
"""The spp AOV of an adaptive render as a heat map PNG (README's picture beside the render):
  build/gpurt render SCENE ... --noise-threshold T --aov spp=spp.pfm
  python3 scripts/spp-heatmap.py spp.pfm heat.png [--max N]
Dark blue: the fewest samples (--min-spp), through red to yellow: the most (--max, default the
largest count in the file). Only the standard library (zlib, struct)."""
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pfm import read_pfm  # noqa: E402


def colour(t):
    """A dark-blue, magenta, orange, yellow ramp for t in [0, 1]."""
    stops = [(0.0, (20, 20, 80)), (0.35, (150, 30, 140)), (0.7, (240, 110, 40)), (1.0, (255, 240, 120))]
    for (t0, c0), (t1, c1) in zip(stops, stops[1:]):
        if t <= t1:
            u = (t - t0) / (t1 - t0)
            return bytes(int(a + (b - a) * u) for a, b in zip(c0, c1))
    return bytes(stops[-1][1])


def write_png(path, w, h, rows):
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + row for row in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    w, h, channels, values = read_pfm(sys.argv[1])
    if channels != 1:
        raise SystemExit(f"{sys.argv[1]}: not a one-channel PFM (the spp AOV)")
    top = float(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[3] == "--max" else max(values)
    low = min(values)
    span = max(1e-9, top - low)
    # PFM rows run bottom to top.
    rows = [b"".join(colour(min(1.0, (values[y * w + x] - low) / span)) for x in range(w)) for y in reversed(range(h))]
    write_png(sys.argv[2], w, h, rows)


if __name__ == "__main__":
    main()
