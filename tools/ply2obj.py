#!/usr/bin/env python3
"""Converts an ASCII PLY triangle mesh (plain or .gz), such as the Stanford dragon, to a Wavefront OBJ.

    tools/ply2obj.py dragon_vrip.ply.gz dragon.obj

Only vertex positions (the first three vertex properties) and faces are kept; polygons stay
polygons (gpurt fans them, CONTRACT.md). Writes to a temporary file and renames it.
"""
import gzip
import os
import sys


def main(src, dst):
    opener = gzip.open if src.endswith('.gz') else open
    with opener(src, 'rt') as f:
        if f.readline().strip() != 'ply':
            sys.exit(f'{src}: not a PLY file')
        vertices = faces = 0
        while True:
            line = f.readline()
            if not line:
                sys.exit(f'{src}: no end_header')
            words = line.split()
            if words[:2] == ['format', 'binary_little_endian'] or words[:2] == ['format', 'binary_big_endian']:
                sys.exit(f'{src}: binary PLY is not supported, only ASCII')
            if words[:2] == ['element', 'vertex']:
                vertices = int(words[2])
            if words[:2] == ['element', 'face']:
                faces = int(words[2])
            if words == ['end_header']:
                break
        tmp = dst + '.tmp-ply2obj'
        with open(tmp, 'w') as out:
            for _ in range(vertices):
                p = f.readline().split()
                out.write(f'v {p[0]} {p[1]} {p[2]}\n')
            for _ in range(faces):
                p = f.readline().split()
                n = int(p[0])
                out.write('f ' + ' '.join(str(int(x) + 1) for x in p[1:1 + n]) + '\n')
        os.replace(tmp, dst)
    print(f'{dst}: {vertices} vertices, {faces} faces')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit('usage: ply2obj.py IN.ply[.gz] OUT.obj')
    main(sys.argv[1], sys.argv[2])
