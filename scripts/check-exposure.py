#!/usr/bin/env python3
"""How well the default light exposes models: renders each scene with `gpurt render` (both
integrators) with the prim AOV, and prints, over the pixels that show the model, the mean of each
PNG pixel's largest channel (the contract asks 0.25..0.75) and the share with a channel at 255
(under 2%). Standard library only.

    scripts/check-exposure.py [--gpurt build/gpurt] [--size 96] [--spp-path 4] SCENE...
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib


def read_png_rgb(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n', path
    pos, idat, width, height, ctype = 8, b'', 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            width, height, depth, ctype = struct.unpack('>IIBB', body[:10])
            assert depth == 8 and ctype in (2, 6), (depth, ctype)
        elif kind == b'IDAT':
            idat += body
        pos += 12 + length
    channels = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def read_pfm(path):
    data = open(path, 'rb').read()
    parts = data.split(b'\n', 3)
    kind, dims, scale = parts[0], parts[1].split(), float(parts[2])
    width, height = int(dims[0]), int(dims[1])
    channels = 3 if kind == b'PF' else 1
    fmt = ('<' if scale < 0 else '>') + 'f' * (width * height * channels)
    values = struct.unpack(fmt, parts[3][:4 * width * height * channels])
    # PFM rows are bottom first.
    return width, height, channels, [values[(height - 1 - y) * width * channels:(height - y) * width * channels]
                                     for y in range(height)]


def exposure(gpurt, scene, integrator, size, spp, extra):
    with tempfile.TemporaryDirectory() as tmp:
        png, prim = os.path.join(tmp, 'o.png'), os.path.join(tmp, 'p.pfm')
        cmd = [gpurt, 'render', scene, '-o', png, '--size', f'{size}x{size}', '--integrator', integrator,
               '--aov', 'prim=' + prim] + (['--spp', str(spp)] if integrator == 'path' else []) + extra
        subprocess.run(cmd, check=True)
        w, h, ch, rows = read_png_rgb(png)
        _, _, pch, prows = read_pfm(prim)
        n = clipped = 0
        total = 0.0
        for y in range(h):
            for x in range(w):
                if prows[y][x * pch] < 0:
                    continue
                largest = max(rows[y][x * ch:x * ch + 3])
                n += 1
                clipped += largest == 255
                total += largest / 255.0
        return (total / n if n else float('nan')), (clipped / n if n else float('nan')), n


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--gpurt', default='build/gpurt')
    ap.add_argument('--size', type=int, default=96)
    ap.add_argument('--spp-path', type=int, default=4)
    ap.add_argument('--extra', default='', help='more gpurt options, space separated')
    ap.add_argument('scenes', nargs='+')
    a = ap.parse_args()
    bad = 0
    for scene in a.scenes:
        for integrator in ('whitted', 'path'):
            mean, clip, n = exposure(a.gpurt, scene, integrator, a.size, a.spp_path, a.extra.split())
            ok = 0.25 <= mean <= 0.75 and clip < 0.02
            bad += not ok
            print(f'{scene:45s} {integrator:8s} mean {mean:.3f} clipped {100 * clip:5.2f}% '
                  f'({n} pixels) {"ok" if ok else "OUT OF RANGE"}')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
