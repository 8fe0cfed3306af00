#!/usr/bin/env python3
"""The scaling table with a column per accelerator (issue 25): for each scene, `gpurt bench` with
--accel grid and --accel bvh, primary and shadow rays, the gl and cpu backends beside Embree's best,
in one run; and what --accel auto chose. Prints a Markdown table (ms and the ratio to Embree) and
writes OUT/accel-table.json.

    scripts/bench-accel.py [--gpurt build/gpurt] [--size 1024x1024] [--runs 3] [--out out]

The dragon (scripts/fetch-dragon.sh, out/models/dragon.ply) joins when it is there. Run it on a
quiet machine: llvmpipe's passes slow down far more than Embree's under load.
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def bench(gpurt, scene, accel, rays, size, runs):
    cmd = [gpurt, 'bench', scene, '--accel', accel, '--rays', rays, '--size', size, '--runs', str(runs), '--json']
    out = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {out.returncode}: {out.stderr.strip()}")
    return json.loads(out.stdout)


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--gpurt', default='build/gpurt')
    p.add_argument('--size', default='1024x1024')
    p.add_argument('--runs', type=int, default=3)
    p.add_argument('--out', default='out')
    a = p.parse_args()
    scenes = ['scenes/boxes.json', '../shared/models/teapot.obj', 'scenes/room.json', '../shared/models/bunny_lo.obj',
              'scenes/highlow.json', '../shared/models/bunny.obj', 'scenes/cornell_blocks.json',
              '../shared/models/cornell_box.obj']
    dragon = os.path.join(ROOT, 'out/models/dragon.ply')
    if os.path.exists(dragon):
        scenes.append(dragon)
    rows = []
    for scene in scenes:
        row = {'scene': scene}
        for rays in ('primary', 'shadow'):
            for accel in ('grid', 'bvh', 'auto'):
                j = bench(a.gpurt, scene, accel, rays, a.size, a.runs)
                by = {b['backend']: b for b in j['backends']}
                row['triangles'] = j['triangles']
                row[f'{rays}_{accel}'] = {'gl': by['gl']['ms'], 'cpu': by['cpu']['ms'],
                                         'embree': by['embree']['ms'], 'chosen': j['accel'],
                                         'build_ms': j['grid_ms'],
                                         'agree_gl': by['gl'].get('agreement'), 'agree_cpu': by['cpu'].get('agreement')}
                print(f"{os.path.basename(scene):>18} {rays:>7} {accel:>4}: gl {by['gl']['ms']:8.2f} ms, "
                      f"cpu {by['cpu']['ms']:8.2f} ms, embree {by['embree']['ms']:7.2f} ms ({j['accel']})",
                      file=sys.stderr, flush=True)
        rows.append(row)
    os.makedirs(os.path.join(ROOT, a.out), exist_ok=True)
    with open(os.path.join(ROOT, a.out, 'accel-table.json'), 'w') as f:
        json.dump(rows, f, indent=1)
    print(f"| scene (triangles) | rays | gl grid ms | gl bvh ms | bvh / grid (gl) | cpu grid ms | cpu bvh ms | "
          f"embree ms | auto chose | auto gl / embree |")
    print('|---|---|---|---|---|---|---|---|---|---|')
    for r in rows:
        for rays in ('primary', 'shadow'):
            g, b, au = r[f'{rays}_grid'], r[f'{rays}_bvh'], r[f'{rays}_auto']
            embree = min(g['embree'], b['embree'], au['embree'])  # Embree's best of the three runs
            print(f"| {os.path.basename(r['scene'])} ({r['triangles']}) | {rays} | {g['gl']:.2f} | {b['gl']:.2f} | "
                  f"{g['gl'] / b['gl']:.2f}x | {g['cpu']:.2f} | {b['cpu']:.2f} | {embree:.2f} | {au['chosen']} | "
                  f"{embree / au['gl']:.3f} |")


if __name__ == '__main__':
    main()
