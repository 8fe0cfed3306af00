#!/usr/bin/env python3
"""Writes a procedural sky as a latitude-longitude Radiance .hdr (flat RGBE scanlines), in the
contract's convention (CONTRACT.md: u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi, the
top row first): a blue sky that pales towards the horizon, a small warm sun (1.5 degrees
across, radiance 5000: the real one's half degree would be a fraction of a texel at these sizes,
with a soft glow) and a grey-brown ground. Standard library only.

    scripts/make-sky.py OUT.hdr [--width 1024] [--sun-azimuth 40] [--sun-elevation 30]
"""
import argparse
import math


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return bytes(4)
    f, e = math.frexp(m)
    s = f * 256.0 / m
    return bytes([min(255, int(r * s + 0.5)), min(255, int(g * s + 0.5)), min(255, int(b * s + 0.5)), e + 128])


def sky(d, sun):
    x, y, z = d
    cos_sun = x * sun[0] + y * sun[1] + z * sun[2]
    if y >= 0.0:
        t = math.sqrt(y)
        base = (0.5 + (0.1 - 0.5) * t, 0.6 + (0.2 - 0.6) * t, 0.75 + (0.45 - 0.75) * t)
    else:
        t = min(1.0, -6.0 * y)
        base = (0.55 + (0.22 - 0.55) * t, 0.6 + (0.19 - 0.6) * t, 0.65 + (0.15 - 0.65) * t)
    glow = 3.0 * max(0.0, cos_sun) ** 256 + 0.3 * max(0.0, cos_sun) ** 8
    disc = 5000.0 if cos_sun > math.cos(math.radians(0.75)) else 0.0
    sunlight = (1.0, 0.9, 0.75)
    return tuple(base[c] + (glow + disc) * sunlight[c] for c in range(3))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('out')
    ap.add_argument('--width', type=int, default=1024)
    ap.add_argument('--sun-azimuth', type=float, default=40.0, help='degrees from -z towards +x')
    ap.add_argument('--sun-elevation', type=float, default=30.0, help='degrees above the horizon')
    a = ap.parse_args()
    w, h = a.width, a.width // 2
    az, el = math.radians(a.sun_azimuth), math.radians(a.sun_elevation)
    sun = (math.cos(el) * math.sin(az), math.sin(el), -math.cos(el) * math.cos(az))
    out = bytearray(b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n' % (h, w))
    for j in range(h):
        theta = (j + 0.5) / h * math.pi
        for i in range(w):
            phi = ((i + 0.5) / w - 0.5) * 2.0 * math.pi
            d = (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))
            out += rgbe(*sky(d, sun))
    with open(a.out, 'wb') as f:
        f.write(out)


if __name__ == '__main__':
    main()
