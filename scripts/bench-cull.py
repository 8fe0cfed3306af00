#!/usr/bin/env python3
"""The cost of back-face culling on gl (docs/PERFORMANCE.md, "Back-face culling"): the teapot of
tests/assets/gltf as single-sided and as double-sided copies, `gpurt bench` primary and shadow rays
with each accelerator, for each binary given, alternating, ROUNDS rounds; prints each figure (ms,
bench's median of 5 runs) of every round.

    scripts/bench-cull.py [--rounds 3] GPURT [GPURT ...]
"""
import argparse
import json
import os
import shutil
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('gpurt', nargs='+')
    p.add_argument('--rounds', type=int, default=3)
    a = p.parse_args()
    work = tempfile.mkdtemp()
    try:
        src = os.path.join(ROOT, 'tests/assets/gltf')
        shutil.copy(os.path.join(src, 'teapot.bin'), work)
        gltf = json.load(open(os.path.join(src, 'teapot.gltf')))
        for sided, name in ((False, 'one'), (True, 'two')):
            for m in gltf.get('materials', []):
                m['doubleSided'] = sided
            json.dump(gltf, open(os.path.join(work, f'teapot_{name}.gltf'), 'w'))
        res = {}
        for _ in range(a.rounds):
            for accel in ('grid', 'bvh'):
                for rays in ('primary', 'shadow'):
                    for side in ('one', 'two'):
                        for b in a.gpurt:
                            o = subprocess.run([b, 'bench', os.path.join(work, f'teapot_{side}.gltf'), '--accel', accel,
                                                '--rays', rays, '--backend', 'gl', '--runs', '5', '--json'],
                                               capture_output=True, text=True, check=True)
                            res.setdefault((accel, rays, f'{side}-sided', b), []).append(json.loads(o.stdout)['ms'])
        for k, v in sorted(res.items()):
            print(*k, ' / '.join(f'{x:.2f}' for x in v), f'(fastest {min(v):.2f})')
    finally:
        shutil.rmtree(work)


if __name__ == '__main__':
    main()
